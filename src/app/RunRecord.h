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
// The first recorded frame's pass times and CPU time (its set-up work, e.g. radiosity's initial
// solution, shows here), and the median of each over the recorded frames after it (issue 30: a
// median over every frame hides a long first frame). Empty objects when there are no such frames.
nlohmann::json firstFrameTimes(const std::vector<FrameStats>& frames);
nlohmann::json medianPassTimesExcludingFirst(const std::vector<FrameStats>& frames);

nlohmann::json renderRunRecord(const Scene& scene, Pipeline& pipeline, const std::vector<FrameStats>& frames,
                               const gl::GpuInfo& gpu, const nlohmann::json& extra);

}  // namespace bounce
