// Sparse path of techniques/vct/passes.glsl (Rauwendaal 2013 section 5.4): a point list of the
#if VCT_STORAGE == 2 && VCT_PASS == 1 && VCT_FLOAT_ATOMICS  // SH_F32 (vct_shared.h is not included yet)
#extension GL_NV_shader_atomic_float : require
#endif
// active-voxel list drawn indirectly with the rasterizer disabled, one vertex per listed voxel.
#include "common/constants.glsl"
#include "techniques/vct/passes.glsl"
void main() {
    if (uint(gl_VertexID) >= in_capacity) return;
    processVoxel(unpackVoxel(in_voxels[gl_VertexID]));
    gl_Position = vec4(0.0);
}
