#pragma once
// Out-of-GPU-memory detection (issue 29 #21). GL reports GL_OUT_OF_MEMORY only where a driver cannot
// back an allocation at all (llvmpipe, Mesa's hardware drivers at their limits); NVIDIA's and AMD's
// drivers instead place what does not fit in video memory in system memory, without an error, and
// the run goes on at a fraction of its speed. Where the driver says how much video memory is free
// (GL_NVX_gpu_memory_info's current available, GL_ATI_meminfo's free texture/VBO memory, both in
// KiB), an allocation past it is refused before it is made, as GL_OUT_OF_MEMORY is after. GL-free
// so the decision and its message are unit-tested (tests/unit/MemoryCheckTest.cpp).
#include <fmt/format.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace bounce::gl {

// The one-line error for an allocation of `bytes` when the driver reported GL_OUT_OF_MEMORY
// (`glError`) or reports only `freeBytes` of video memory free; "" when it fits.
inline std::string outOfMemoryMessage(std::string_view what, std::string_view name, uint64_t bytes, bool glError,
                                      std::optional<uint64_t> freeBytes) {
    if (glError)
        return fmt::format("out of GPU memory allocating {} '{}' ({:.1f} MB): try a smaller --size or smaller settings", what,
                           name, static_cast<double>(bytes) * 1e-6);
    if (freeBytes && bytes > *freeBytes)
        return fmt::format("out of GPU memory allocating {} '{}' ({:.1f} MB): the GPU reports {:.1f} MB of video memory free "
                           "(the driver would place it in system memory); try a smaller --size or smaller settings",
                           what, name, static_cast<double>(bytes) * 1e-6, static_cast<double>(*freeBytes) * 1e-6);
    return {};
}

}  // namespace bounce::gl
