// Rauwendaal 2013 section 4.1.2: fragment-parallel voxelization, fragment stage. One fragment per
// voxel column of the swizzled XY plane: the exact 2D test (it removes the false positives of the
// dilated rasterization, Fig. 4.12), the depth range of the plane over the column, and the loop over
// it with the YZ and ZX tests (lines 15-20 of Fig. 4.4, 14-20 of Fig. 4.5). The surface attributes
// are those of the fragment (the column centre), so the radiance is injected once per fragment.
// Defines: VCT_STORAGE, VCT_CONSERVATIVE. Writes images only (no colour output).
#if VCT_STORAGE == 2 && VCT_FLOAT_ATOMICS  // SH_F32 (vct_shared.h is not included yet) with float atomics
#extension GL_NV_shader_atomic_float : require
#endif
#define VCT_WRITE 1
#include "common/scene.glsl"
#include "techniques/vct/volume.glsl"
#include "techniques/vct/overlap.glsl"
#include "techniques/vct/inject.glsl"

in vec3 gf_posWorld;
in vec3 gf_normal;
in vec2 gf_uv;
flat in uint gf_object;
flat in int gf_axis;
flat in vec3 gf_n;
flat in vec2 gf_dAB;
flat in ivec2 gf_zBounds;
flat in ivec4 gf_xyBounds;
flat in vec2 gf_nXY[3];
flat in vec2 gf_nYZ[3];
flat in vec2 gf_nZX[3];
flat in vec3 gf_dXY;
flat in vec3 gf_dYZ;
flat in vec3 gf_dZX;

void main() {
    const bool conservative = VCT_CONSERVATIVE != 0;
    VoxTri t;
    t.axis = gf_axis;
    t.n = gf_n;
    t.dA = gf_dAB.x;
    t.dB = gf_dAB.y;
    t.bmin = ivec3(0, 0, gf_zBounds.x);
    t.bmax = ivec3(0, 0, gf_zBounds.y);
    t.nXY = gf_nXY;
    t.nYZ = gf_nYZ;
    t.nZX = gf_nZX;
    t.dXY = gf_dXY;
    t.dYZ = gf_dYZ;
    t.dZX = gf_dZX;
    vec2 p = floor(gl_FragCoord.xy);
    // Step 1 of the test (section 4.1): only voxels in the triangle's bounding box. The dilated
    // triangle reaches past it near acute corners, where the edge tests alone still pass
    // ([HAMO05]'s AABB clipping; without it the conservative set grows by ~15 % on two-rooms).
    if (any(lessThan(ivec2(p), gf_xyBounds.xy)) || any(greaterThan(ivec2(p), gf_xyBounds.zw))) return;
    if (!voxTestXY(t, p)) return;
    ivec2 zr = voxDepthRange(t, p, conservative);
    if (zr.x > zr.y) return;
    // An alpha-masked texel is no surface (docs/scene.md): the column is sampled at its centre, once
    // per voxel column as the injection's attributes are.
    if (materialMasked(u_objects[gf_object].info.x, gf_uv)) return;
    vec3 radiance = vec3(0.0);
    if (u_vct.range.w < 0.5) {
        uint material = u_objects[gf_object].info.x;
        bool twoSided = u_materials[material].params.w > 0.5;
        radiance = injectedRadiance(gf_posWorld, normalize(gf_normal + 1e-12), (1.0 - u_materials[material].params.y) * materialAlbedo(material, gf_uv), twoSided);
    }
    for (int z = zr.x; z <= zr.y; ++z) {
        if (!voxTestYZZX(t, vec3(p, z))) continue;
        writeVoxel(voxUnswizzle(ivec3(ivec2(p), z), t.axis), radiance);
    }
}
