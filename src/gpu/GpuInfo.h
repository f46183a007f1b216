#pragma once
// What a GL context reports about its implementation (gl::Context::info()): strings, the device it
// runs on, and the limits bounce's setup checks and the portable-limits audit (gpu/PortableLimits.h)
// read. GL-free so the portable clamp is unit-tested.
#include "core/DeviceProfile.h"

#include <string>
#include <utility>
#include <vector>

namespace bounce::gl {

struct GpuInfo {
    std::string vendor, renderer, version, glslVersion;
    std::string platform;   // "egl-device", "egl-surfaceless", "glfw"
    int deviceIndex = -1;   // index into the EGL device enumeration; -1: surfaceless or windowed
    std::string deviceName;  // the EGL device's name (gpu/DeviceSelection.h), "" without one
    DeviceProfile profile = DeviceProfile::Llvmpipe;  // from the renderer, or BOUNCE_PROFILE
    bool profileOverridden = false;                     // BOUNCE_PROFILE set it
    bool debugContext = false;    // created with KHR_debug output (synchronous): tests; not measured runs
    bool portableLimits = false;  // BOUNCE_PORTABLE_LIMITS=1: the limits below are the GL 4.5 minimums
    int maxTextureSize = 0, max3dTextureSize = 0, maxArrayLayers = 0, maxCubeMapSize = 0;
    int maxColorAttachments = 0, maxDrawBuffers = 0;
    int maxUniformBlockSize = 0;
    long long maxShaderStorageBlockSize = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE is a 64-bit query
    int maxTextureBufferSize = 0;
    int maxComputeInvocations = 0;
    int maxComputeWorkGroupSize[3] = {0, 0, 0};
    int maxComputeWorkGroupCount[3] = {0, 0, 0};
    int maxComputeSharedMemorySize = 0;
    int maxGeometryOutputVertices = 0, maxGeometryInvocations = 0;
    int maxTransformFeedbackBuffers = 0;
    int maxImageUnits = 0, maxCombinedTextureUnits = 0;
    int maxCombinedImageUniforms = 0, maxCombinedStorageBlocks = 0;
    // Per stage: vertex, geometry, fragment, compute (gl::ShaderStage order).
    int maxImageUniforms[4] = {0, 0, 0, 0};
    int maxTextureImageUnits[4] = {0, 0, 0, 0};
    int maxStorageBlocks[4] = {0, 0, 0, 0};
    int maxUniformBlocks[4] = {0, 0, 0, 0};
    int maxColorTextureSamples = 0, maxDepthTextureSamples = 0;
    int timerQueryBits = 0;
    bool resetNotification = false;  // GL_RESET_NOTIFICATION_STRATEGY is GL_LOSE_CONTEXT_ON_RESET (issue 29 #22)
    std::vector<std::pair<std::string, bool>> extensions;  // extensions techniques care about
};

}  // namespace bounce::gl
