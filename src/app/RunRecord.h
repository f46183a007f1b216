#pragma once
// Run records: the JSON that `bounce render --stats` writes. It holds what ran (scene, technique,
// every setting's value, GPU), and what it cost (per-frame total and per-pass GPU milliseconds,
// counters the technique reports), so a figure can be traced to the run that produced it.
#include "gpu/Context.h"
#include "techniques/Pipeline.h"

#include <nlohmann/json.hpp>

namespace bounce {

nlohmann::json gpuInfoJson(const gl::GpuInfo& info);
nlohmann::json frameStatsJson(const FrameStats& stats);
// Median of each pass over the frames ("frame" included), in milliseconds.
nlohmann::json medianPassTimes(const std::vector<FrameStats>& frames);

nlohmann::json renderRunRecord(const Scene& scene, Pipeline& pipeline, const std::vector<FrameStats>& frames,
                               const gl::GpuInfo& gpu, const nlohmann::json& extra);

}  // namespace bounce
