#pragma once
// Which EGL device a headless context uses, decided without EGL so that the rules are unit-tested
// (tests/unit/DeviceSelectionTest.cpp); gpu/EglContext.cpp enumerates the devices and applies them.
//
// EGL's device enumeration (EGL_EXT_device_enumeration) is the only list that a headless context can
// pick from: CUDA_VISIBLE_DEVICES does not change it, so the choice is an index into it, given by the
// global option `--gpu N` or the environment variable BOUNCE_EGL_DEVICE=N (the option wins). Without
// one, the hardware devices are tried in enumeration order (an eglInitialize failure moves on to the
// next), then Mesa's surfaceless platform (llvmpipe). BOUNCE_EGL_PLATFORM=device|surfaceless narrows
// the automatic choice. docs/gpu.md "Device selection" is the user's guide.
#include "core/Error.h"

#include <optional>
#include <string>
#include <vector>

namespace bounce::gl {

// One entry of the EGL device enumeration, as `bounce info` lists it.
struct EglDeviceDesc {
    int index = 0;
    bool software = false;     // EGL_MESA_device_software: Mesa's llvmpipe device
    std::string name;          // vendor/renderer (EGL_EXT_device_query_name) or driver and node
    std::string driver;        // kernel driver of its DRM node ("nvidia", "amdgpu", "i915"), if known
    std::string renderNode;    // /dev/dri/renderD128 (EGL_EXT_device_drm_render_node), if known
    std::string deviceFile;    // /dev/dri/card0 (EGL_EXT_device_drm), if known
    int cudaDevice = -1;       // EGL_NV_device_cuda: the CUDA ordinal, -1 if not an NVIDIA device
};

// The EGL device enumeration of this process (gpu/EglContext.cpp; needs libEGL, no context).
Expected<std::vector<EglDeviceDesc>> enumerateEglDevices();

// An explicit device index and where it came from ("--gpu" or "BOUNCE_EGL_DEVICE"), for messages.
struct DeviceRequest {
    std::optional<int> index;
    std::string source;
    std::string platform;  // BOUNCE_EGL_PLATFORM: "", "device" or "surfaceless"
};

// A device to try: an index into the enumeration, or Mesa's surfaceless platform (index -1).
struct DeviceCandidate {
    int index = -1;
    bool surfaceless() const { return index < 0; }
};

// The devices to try in order (the first that initialises wins). Errors: an index past the
// enumeration (names the device count), an index with BOUNCE_EGL_PLATFORM=surfaceless, no hardware
// device with BOUNCE_EGL_PLATFORM=device, an unknown platform.
Expected<std::vector<DeviceCandidate>> chooseDevices(const std::vector<EglDeviceDesc>& devices,
                                                     const DeviceRequest& request);

// Parses a device index given as text ("--gpu" / "BOUNCE_EGL_DEVICE" value): a non-negative integer.
Expected<int> parseDeviceIndex(const std::string& text, const std::string& source);

// The request from the process: the index set by setDeviceOverride (--gpu) or else BOUNCE_EGL_DEVICE,
// and BOUNCE_EGL_PLATFORM. An unparsable BOUNCE_EGL_DEVICE is an error.
Expected<DeviceRequest> deviceRequestFromEnvironment();
// `--gpu N`: overrides BOUNCE_EGL_DEVICE for this process (and is passed on to sweep workers).
void setDeviceOverride(std::optional<int> index);

// "index N (name)" / "surfaceless" for logs and `bounce info`.
std::string describeCandidate(const std::vector<EglDeviceDesc>& devices, const DeviceCandidate& c);

// True for Mesa's software rasterisers (llvmpipe, softpipe, swrast) and lavapipe behind zink.
bool isSoftwareRenderer(const std::string& renderer);

// A GPU device node: /dev/nvidia0 or a DRM render node whose driver is not a software one.
struct DeviceNode {
    std::string path;
    std::string driver;  // sysfs driver name, "" if unknown
};
// The GPU device nodes of this machine (/dev/nvidia0, /dev/dri/renderD*), vgem excluded.
std::vector<DeviceNode> gpuDeviceNodes();
// The one-line warning for a software renderer on a machine with GPU device nodes, or none.
std::optional<std::string> softwareFallbackWarning(const std::string& renderer, const std::vector<DeviceNode>& nodes);

// The EGL device index each of `jobs` sweep workers uses: round robin over the hardware devices
// (empty: no hardware device, every worker takes the automatic choice). An explicit request pins
// every worker to it.
std::vector<std::optional<int>> sweepWorkerDevices(const std::vector<EglDeviceDesc>& devices,
                                                    const DeviceRequest& request, int jobs);
// The default worker count of `bounce sweep`: one per hardware device, 1 without any.
int defaultSweepJobs(const std::vector<EglDeviceDesc>& devices, const DeviceRequest& request);

}  // namespace bounce::gl
