#pragma once
// Limits of shader execution that the GL API does not report but that decide whether a long shader
// computes what it says. They depend on the device profile (core/DeviceProfile.h): llvmpipe cuts long
// loops silently, GPUs do not (docs/gpu.md "Device profile").
#include "core/DeviceProfile.h"

namespace bounce::gl {

// Mesa's llvmpipe ends every loop of one shader invocation once all its loops together have run this
// many iterations (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS, "shared between every loop in a shader"),
// silently: a gather over 131072 VPLs in one invocation drops about half of them. It is llvmpipe's
// budget only; code that refuses settings or sizes batches by it asks shaderLoopIterationBudget() (the
// current device profile's; issue 29 #19).
inline constexpr int kShaderLoopIterationBudget = 65535;

// On a GPU nothing counts loop iterations; what bounds a draw is the driver's watchdog (Windows TDR's
// default 2 s, TdrDelay; Linux amdgpu's 10 s lockup timeout; NVIDIA without a display: none). One
// invocation of 2^24 iterations of a gather loop (tens of instructions each, at ~1 GHz) takes
// 0.2-0.5 s on one lane: a bound no default comes near, kept so that a runaway setting is still
// refused with a message rather than hanging the GPU. Draws stay batched by the techniques' own
// batch sizes (a watchdog limits a whole draw, not one invocation).
inline constexpr int kGpuShaderLoopIterationBudget = 1 << 24;

// The loop budget of one shader invocation on `profile`: 65535 on llvmpipe, 2^24 on a GPU.
constexpr int shaderLoopIterationBudget(DeviceProfile profile) {
    return profile == DeviceProfile::Llvmpipe ? kShaderLoopIterationBudget : kGpuShaderLoopIterationBudget;
}
// The same for the current context (llvmpipe's without one).
int shaderLoopIterationBudget();

}  // namespace bounce::gl
