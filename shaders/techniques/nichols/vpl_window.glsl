// A window of the VPL cache (Nichols 2010 §4.2.1.2's VPL cache, shaders/techniques/nichols/vpl.glsl) read
// as a uniform block: VPL_WINDOW records (host define) starting at the draw's first VPL. The host binds
// the range (techniques/nichols/VplWindow.h, which says why a uniform block: llvmpipe reads it with
// vector gathers where an SSBO read is a per-lane loop). Include after techniques/nichols/vpl.glsl.
layout(std140, binding = BINDING_UBO_VPL_WINDOW) uniform VplWindowBlock { Vpl u_vplWindow[VPL_WINDOW]; };
