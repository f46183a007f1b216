#pragma once
// One-line setup refusals of GPU objects past a device limit (issue 29 findings #6 and #16): a storage
// buffer past GL_MAX_SHADER_STORAGE_BLOCK_SIZE or a buffer texture past GL_MAX_TEXTURE_BUFFER_SIZE is
// not an error GL reports: shaders then read and write out of bounds silently. Each message names the
// settings, what needs the object, its size and the device's limit (GpuInfo: under
// BOUNCE_PORTABLE_LIMITS=1 the GL 4.5 minimums, so these refusals are testable on llvmpipe).
#include "core/Error.h"
#include "gpu/GpuInfo.h"

#include <cstddef>
#include <string_view>

namespace bounce::gl {

inline Expected<void> checkStorageBuffer(const GpuInfo& info, size_t bytes, std::string_view settings, std::string_view what) {
    if (info.maxShaderStorageBlockSize > 0 && bytes > static_cast<unsigned long long>(info.maxShaderStorageBlockSize))
        return makeError("{}: {} needs a storage buffer of {} bytes ({:.0f} MiB), past this GL's GL_MAX_SHADER_STORAGE_BLOCK_SIZE "
                         "of {} bytes; lower the setting",
                         settings, what, bytes, static_cast<double>(bytes) / (1024.0 * 1024.0), info.maxShaderStorageBlockSize);
    return {};
}

inline Expected<void> checkTextureBuffer(const GpuInfo& info, size_t texels, std::string_view settings, std::string_view what) {
    if (info.maxTextureBufferSize > 0 && texels > static_cast<size_t>(info.maxTextureBufferSize))
        return makeError("{}: {} needs a buffer texture of {} texels, past this GL's GL_MAX_TEXTURE_BUFFER_SIZE of {} texels; lower the setting",
                         settings, what, texels, info.maxTextureBufferSize);
    return {};
}

}  // namespace bounce::gl
