// Dense path of techniques/vct/passes.glsl: one invocation per voxel of the level written.
#if VCT_STORAGE == 2 && VCT_PASS == 1 && VCT_FLOAT_ATOMICS  // SH_F32 (vct_shared.h is not included yet)
#extension GL_NV_shader_atomic_float : require
#endif
#include "common/constants.glsl"
#include "techniques/vct/passes.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
uniform int u_size;  // voxels per side of the level processed
void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, ivec3(u_size)))) return;
    processVoxel(p);
}
