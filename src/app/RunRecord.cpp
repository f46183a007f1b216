#include "app/RunRecord.h"

#include <algorithm>
#include <map>

namespace bounce {

nlohmann::json gpuInfoJson(const gl::GpuInfo& info) {
    return {{"vendor", info.vendor},
            {"renderer", info.renderer},
            {"version", info.version},
            {"platform", info.platform},
            {"device", info.deviceIndex},
            {"device_name", info.deviceName},
            {"profile", std::string(profileName(info.profile))},
            {"debug_context", info.debugContext},
            {"portable_limits", info.portableLimits}};
}

nlohmann::json frameStatsJson(const FrameStats& s) {
    nlohmann::json passes = nlohmann::json::object();
    for (const auto& p : s.passes) passes[p.name] = p.milliseconds;
    const gl::LiveResources& r = s.resources;
    const nlohmann::json resources = {{"gl_objects", r.objects},       {"buffers", r.buffers},
                                      {"textures", r.textures},        {"framebuffers", r.framebuffers},
                                      {"vertex_arrays", r.vertexArrays}, {"programs", r.programs},
                                      {"shaders", r.shaders},          {"queries", r.queries},
                                      {"buffer_bytes", r.bufferBytes}, {"texture_bytes", r.textureBytes},
                                      {"rss_bytes", s.residentBytes}};
    return {{"frame", s.frame}, {"time_s", s.time}, {"cpu_ms", s.cpuMilliseconds}, {"gpu_ms", passes},
            {"counters", s.counters}, {"resources", resources}};
}

static double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

nlohmann::json medianPassTimes(const std::vector<FrameStats>& frames) {
    std::map<std::string, std::vector<double>> byName;
    std::vector<double> cpu;
    for (const FrameStats& f : frames) {
        for (const auto& p : f.passes) byName[p.name].push_back(p.milliseconds);
        cpu.push_back(f.cpuMilliseconds);
    }
    nlohmann::json out = nlohmann::json::object();
    for (auto& [name, values] : byName) out[name] = median(values);
    out["cpu"] = median(cpu);
    return out;
}

nlohmann::json firstFrameTimes(const std::vector<FrameStats>& frames) {
    nlohmann::json out = nlohmann::json::object();
    if (frames.empty()) return out;
    for (const auto& p : frames.front().passes) out[p.name] = p.milliseconds;
    out["cpu"] = frames.front().cpuMilliseconds;
    return out;
}

nlohmann::json medianPassTimesExcludingFirst(const std::vector<FrameStats>& frames) {
    if (frames.size() < 2) return nlohmann::json::object();
    return medianPassTimes(std::vector<FrameStats>(frames.begin() + 1, frames.end()));
}

nlohmann::json renderRunRecord(const Scene& scene, Pipeline& pipeline, const std::vector<FrameStats>& frames,
                               const gl::GpuInfo& gpu, const nlohmann::json& extra) {
    render::RenderSettings renderSettings = pipeline.renderSettings();
    nlohmann::json frameList = nlohmann::json::array();
    for (const FrameStats& f : frames) frameList.push_back(frameStatsJson(f));
    // The scale-derived defaults as used on this scene (Technique::derivedSettings), metres.
    std::map<std::string, double> derivedValues;
    pipeline.technique().derivedSettings(derivedValues);
    nlohmann::json derived = nlohmann::json::object();
    for (const auto& [name, value] : derivedValues) derived[name] = value;
    nlohmann::json record = {
        {"scene", {{"name", scene.name}, {"source", scene.source}, {"triangles", scene.triangleCount()},
                   {"lights", scene.lights.size()}}},
        {"technique", std::string(pipeline.technique().name())},
        {"settings", settingsToJson(pipeline.technique())},
        {"derived", derived},
        {"renderer", settingsToJson(renderSettings)},
        {"size", {pipeline.size().x, pipeline.size().y}},
        {"gpu", gpuInfoJson(gpu)},
        {"frames", frameList},
        {"median_ms", medianPassTimes(frames)},
        {"first_frame_ms", firstFrameTimes(frames)},
        {"median_ms_excluding_first", medianPassTimesExcludingFirst(frames)},
    };
    for (const auto& [k, v] : extra.items()) record[k] = v;
    return record;
}

}  // namespace bounce
