// `bounce info`: the EGL devices of this machine, the one a headless context uses, the GL
// implementation it gets, its device profile and the limits techniques rely on (docs/gpu.md).
#include "app/Cli.h"
#include "app/RunRecord.h"
#include "gpu/Context.h"
#include "gpu/DeviceSelection.h"

#include <nlohmann/json.hpp>

#include <iostream>

namespace bounce {

namespace {

nlohmann::json devicesJson(const std::vector<gl::EglDeviceDesc>& devices) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& d : devices)
        out.push_back({{"index", d.index}, {"name", d.name}, {"software", d.software}, {"driver", d.driver},
                       {"render_node", d.renderNode}, {"device_file", d.deviceFile}, {"cuda_device", d.cudaDevice}});
    return out;
}

nlohmann::json limitsJson(const gl::GpuInfo& i) {
    auto stages = [](const int (&v)[4]) { return nlohmann::json{{"vertex", v[0]}, {"geometry", v[1]}, {"fragment", v[2]}, {"compute", v[3]}}; };
    return {{"max_texture_size", i.maxTextureSize}, {"max_3d_texture_size", i.max3dTextureSize},
            {"max_array_layers", i.maxArrayLayers}, {"max_cube_map_size", i.maxCubeMapSize},
            {"max_color_attachments", i.maxColorAttachments}, {"max_uniform_block_size", i.maxUniformBlockSize},
            {"max_storage_block_size", i.maxShaderStorageBlockSize}, {"max_texture_buffer_size", i.maxTextureBufferSize},
            {"max_compute_invocations", i.maxComputeInvocations},
            {"max_compute_work_group_size", i.maxComputeWorkGroupSize},
            {"max_compute_work_group_count", i.maxComputeWorkGroupCount},
            {"max_compute_shared_memory", i.maxComputeSharedMemorySize},
            {"max_geometry_output_vertices", i.maxGeometryOutputVertices}, {"max_image_units", i.maxImageUnits},
            {"max_combined_texture_units", i.maxCombinedTextureUnits},
            {"max_color_texture_samples", i.maxColorTextureSamples}, {"max_depth_texture_samples", i.maxDepthTextureSamples},
            {"image_uniforms", stages(i.maxImageUniforms)}, {"samplers", stages(i.maxTextureImageUnits)},
            {"storage_blocks", stages(i.maxStorageBlocks)}, {"uniform_blocks", stages(i.maxUniformBlocks)},
            {"timer_query_bits", i.timerQueryBits}};
}

int runInfo(bool json) {
    auto devices = gl::enumerateEglDevices();
    if (!devices.ok()) return failCommand("info", devices.error().message);
    auto context = gl::Context::createHeadless();
    if (!context.ok()) return failCommand("info", context.error().message);
    const gl::GpuInfo& info = (*context)->info();
    if (json) {
        nlohmann::json out = gpuInfoJson(info);
        out["glsl"] = info.glslVersion;
        out["egl_devices"] = devicesJson(*devices);
        out["limits"] = limitsJson(info);
        nlohmann::json ext = nlohmann::json::object();
        for (const auto& [name, present] : info.extensions) ext[name] = present;
        out["extensions"] = ext;
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    std::cout << "EGL devices (--gpu N or BOUNCE_EGL_DEVICE=N picks one)\n";
    if (devices->empty()) std::cout << "  none (EGL_EXT_device_enumeration missing or no device)\n";
    for (const auto& d : *devices)
        std::cout << fmt::format("  {} {:<44} {}{}\n", d.index, d.name, d.software ? "software" : "hardware",
                                 d.index == info.deviceIndex ? "  <- in use" : "");
    std::cout << gl::formatInfo(info);
    return 0;
}

}  // namespace

void registerInfoCommand(CLI::App& root, CommandAction& action) {
    auto json = std::make_shared<bool>(false);
    CLI::App* c = root.add_subcommand("info", "list the EGL devices; print the GL vendor, renderer, version, device "
                                              "profile and limits of a headless context");
    c->add_flag("--json", *json, "print it as JSON (scripts/gpu-check.sh records it)");
    c->callback([&action, json] { action = [json] { return runInfo(*json); }; });
}

}  // namespace bounce
