#pragma once
// A window of a VPL cache (RegularVpls, isr's clusters) bound as a uniform block, the way every
// VPL-cache gather of the Nichols family reads its VPLs (shaders/techniques/nichols/vpl_window.glsl).
//
// Why a uniform block and not the SSBO the cache lives in: on llvmpipe (Mesa 22.3) a uniform-block read
// at a loop index is one vector gather per component, while an SSBO read at a non-constant offset is a
// per-lane loop with a bounds branch per component, and a texelFetch goes through the sampler. Measured
// on cornell-box-dynamic at 256² (isr, 1255 cluster VPLs, interleaved runs): the gather took 6.5× less
// time with the window than with the SSBO, same image (bench/results/interactive-*.json). On a GPU the
// three paths are alike; the window costs one bind per draw.
// A window holds at most kMaxRecords records and never more than GL_MAX_UNIFORM_BLOCK_SIZE allows (GL
// guarantees 16 KiB: 341 records); the draws that read a cache are therefore at most size() VPLs each.
#include "techniques/nichols/RegularVpls.h"

#include <string>
#include <utility>
#include <vector>

namespace bounce::nichols {

class VplWindow {
public:
    // 1024 records = 48 KiB, under the 64 KiB uniform blocks of llvmpipe and the NVIDIA driver; bounce's
    // choice (fewer draws per gather; larger arrays gain nothing on llvmpipe).
    static constexpr int kMaxRecords = 1024;
    // Records per window on the current context (VPL_WINDOW of vpl_window.glsl).
    static int size();
    // The program defines vpl_window.glsl needs: {"VPL_WINDOW", size()}.
    static std::vector<std::pair<std::string, std::string>> defines();
    // `defines` with defines() appended (a gather's other defines, e.g. VplVisibility's).
    static std::vector<std::pair<std::string, std::string>> withDefines(std::vector<std::pair<std::string, std::string>> defines);
    // Window starts are multiples of 16 records (768 bytes, a multiple of every GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT
    // seen: 16 on llvmpipe, 256 on NVIDIA; checked).
    static constexpr int kAlignRecords = 16;
    // VPLs per draw for a gather whose loop budget allows `budget` VPLs: at most size(), a multiple of
    // kAlignRecords when at least that (so every draw's VPLs lie in one window).
    static int perDraw(int budget);
    // Binds the window holding records [first, first + count) of `cache` (clamped to its end) at
    // BINDING_UBO_VPL_WINDOW and returns the record its element 0 holds (the shader's u_windowFirst).
    // `cache` must hold paddedRecords(records) records (its VPLs and the padding): every window's bound
    // range is a whole window, the block's data size (GL: a shorter range is undefined; issue 29 #13).
    static int bind(const gl::Buffer& cache, int first, int count);
    // Records a cache of `records` VPLs allocates: through the end of the window that starts at its last
    // record's aligned start.
    static int paddedRecords(int records);
};

}  // namespace bounce::nichols
