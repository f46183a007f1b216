// Sparse path of techniques/vct/passes.glsl (Rauwendaal 2013 section 5.4): one invocation per entry
#if VCT_STORAGE == 2 && VCT_PASS == 1 && VCT_FLOAT_ATOMICS  // SH_F32 (vct_shared.h is not included yet)
#extension GL_NV_shader_atomic_float : require
#endif
// of the active-voxel list, an indirect dispatch whose size common/list_args.comp wrote from the
// list's count (gpu/ListDispatch.h). A compute job, not the point list drawn with the rasterizer off
// that it was: these passes write, and GL leaves the number of vertex-shader invocations that load and
// store undefined (issue 29 #17); the SH-F32 normalisation run twice would divide twice.
#include "common/constants.glsl"
#include "techniques/vct/passes.glsl"
layout(local_size_x = 64) in;
#include "common/dispatch.glsl"
void main() {
    uint i = linearInvocation();
    if (i >= min(in_count, in_capacity)) return;
    processVoxel(unpackVoxel(in_voxels[i]));
}
