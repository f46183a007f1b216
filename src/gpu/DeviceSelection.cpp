#include "gpu/DeviceSelection.h"

#include "core/DeviceProfile.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace bounce::gl {

namespace {

std::optional<int> g_override;

// Kernel drivers of DRM render nodes that have no GPU behind them.
constexpr const char* kSoftwareDrmDrivers[] = {"vgem", "vkms"};

std::string deviceCountText(size_t n) {
    if (n == 0) return "this machine has no EGL device";
    if (n == 1) return "this machine has 1 EGL device, index 0";
    return fmt::format("this machine has {} EGL devices, indices 0..{}", n, n - 1);
}

}  // namespace

Expected<int> parseDeviceIndex(const std::string& text, const std::string& source) {
    int value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < 0)
        return makeError("{} '{}' is not a device index (0, 1, ...; `bounce info` lists the EGL devices)", source, text);
    return value;
}

void setDeviceOverride(std::optional<int> index) { g_override = index; }

Expected<DeviceRequest> deviceRequestFromEnvironment() {
    DeviceRequest r;
    if (const char* p = std::getenv("BOUNCE_EGL_PLATFORM")) r.platform = p;
    if (g_override) {
        r.index = *g_override;
        r.source = "--gpu";
    } else if (const char* d = std::getenv("BOUNCE_EGL_DEVICE"); d && *d) {
        BOUNCE_TRY(r.index, parseDeviceIndex(d, "BOUNCE_EGL_DEVICE"));
        r.source = "BOUNCE_EGL_DEVICE";
    }
    return r;
}

Expected<std::vector<DeviceCandidate>> chooseDevices(const std::vector<EglDeviceDesc>& devices,
                                                     const DeviceRequest& request) {
    const std::string& platform = request.platform;
    if (!platform.empty() && platform != "device" && platform != "surfaceless")
        return makeError("BOUNCE_EGL_PLATFORM='{}' is not 'device' or 'surfaceless'", platform);
    if (request.index) {
        const int i = *request.index;
        const std::string source = request.source.empty() ? std::string("device") : request.source;
        if (platform == "surfaceless")
            return makeError("{} {} names an EGL device but BOUNCE_EGL_PLATFORM=surfaceless uses none", source, i);
        if (i < 0 || static_cast<size_t>(i) >= devices.size())
            return makeError("{} {}: no such EGL device ({}; `bounce info` lists them)", source, i,
                             deviceCountText(devices.size()));
        return std::vector<DeviceCandidate>{{i}};  // the device asked for, and no other
    }
    std::vector<DeviceCandidate> out;
    if (platform != "surfaceless")
        for (const EglDeviceDesc& d : devices)
            if (!d.software) out.push_back({d.index});
    if (platform == "device" && out.empty())
        return makeError("BOUNCE_EGL_PLATFORM=device but no hardware EGL device was found ({})",
                         deviceCountText(devices.size()));
    if (platform != "device") out.push_back({-1});
    return out;
}

std::string describeCandidate(const std::vector<EglDeviceDesc>& devices, const DeviceCandidate& c) {
    if (c.surfaceless()) return "surfaceless platform";
    for (const EglDeviceDesc& d : devices)
        if (d.index == c.index) return fmt::format("EGL device {} ({})", d.index, d.name);
    return fmt::format("EGL device {}", c.index);
}

bool isSoftwareRenderer(const std::string& renderer) { return profileOfRenderer(renderer) == DeviceProfile::Llvmpipe; }

std::vector<DeviceNode> gpuDeviceNodes() {
    namespace fs = std::filesystem;
    std::vector<DeviceNode> out;
    std::error_code ec;
    if (fs::exists("/dev/nvidia0", ec)) out.push_back({"/dev/nvidia0", "nvidia"});
    std::vector<std::string> nodes;
    for (const auto& entry : fs::directory_iterator("/dev/dri", ec))
        if (entry.path().filename().string().rfind("renderD", 0) == 0) nodes.push_back(entry.path().string());
    std::sort(nodes.begin(), nodes.end());
    for (const std::string& node : nodes) {
        const fs::path driver = fs::path("/sys/class/drm") / fs::path(node).filename() / "device/driver";
        std::error_code e;
        const fs::path target = fs::read_symlink(driver, e);
        const std::string name = e ? std::string() : target.filename().string();
        if (std::find(std::begin(kSoftwareDrmDrivers), std::end(kSoftwareDrmDrivers), name) != std::end(kSoftwareDrmDrivers))
            continue;
        out.push_back({node, name});
    }
    return out;
}

std::optional<std::string> softwareFallbackWarning(const std::string& renderer, const std::vector<DeviceNode>& nodes) {
    if (!isSoftwareRenderer(renderer) || nodes.empty()) return std::nullopt;
    std::string list;
    for (const DeviceNode& n : nodes)
        list += (list.empty() ? "" : ", ") + n.path + (n.driver.empty() ? "" : " (" + n.driver + ")");
    return fmt::format("rendering on the software renderer '{}' although this machine has GPU device nodes ({}): the "
                       "GPU's EGL driver is missing or failed (NVIDIA: libnvidia-egl and its glvnd vendor file "
                       "10_nvidia.json); `bounce info` lists the EGL devices, --gpu N picks one",
                       renderer, list);
}

std::vector<std::optional<int>> sweepWorkerDevices(const std::vector<EglDeviceDesc>& devices,
                                                    const DeviceRequest& request, int jobs) {
    std::vector<std::optional<int>> out(static_cast<size_t>(std::max(jobs, 0)));
    if (request.index) {
        std::fill(out.begin(), out.end(), request.index);
        return out;
    }
    if (request.platform == "surfaceless") return out;
    std::vector<int> gpus;
    for (const EglDeviceDesc& d : devices)
        if (!d.software) gpus.push_back(d.index);
    if (gpus.empty()) return out;
    for (size_t i = 0; i < out.size(); ++i) out[i] = gpus[i % gpus.size()];
    return out;
}

int defaultSweepJobs(const std::vector<EglDeviceDesc>& devices, const DeviceRequest& request) {
    if (request.index || request.platform == "surfaceless") return 1;
    const auto gpus = std::count_if(devices.begin(), devices.end(), [](const EglDeviceDesc& d) { return !d.software; });
    return std::max(1, static_cast<int>(gpus));
}

}  // namespace bounce::gl
