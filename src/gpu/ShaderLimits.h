#pragma once
// Limits of shader execution that the GL API does not report but that decide whether a long shader
// computes what it says.

namespace bounce::gl {

// Mesa's llvmpipe ends every loop of one shader invocation once all its loops together have run this
// many iterations (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS, "shared between every loop in a shader"),
// silently: a gather over 131072 VPLs in one invocation drops about half of them. Desktop drivers have
// no such count but kill a draw that runs for seconds (the watchdog), so passes that loop over many
// VPLs or tree nodes split the work into draws that each stay within this budget on every driver.
inline constexpr int kShaderLoopIterationBudget = 65535;

}  // namespace bounce::gl
