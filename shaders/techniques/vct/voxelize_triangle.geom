// Rauwendaal 2013 section 4.1.1 (Fig. 4.4 / 4.5): triangle-parallel voxelization, one geometry-shader
// invocation per triangle looping over the dominant-plane box, the depth range and the remaining two
// projections, writing every overlapped voxel (volume.glsl). With VCT_HYBRID it is pass 1 of the
// hybrid voxelizer (section 4.1.3, Figs. 4.15/4.18): a triangle whose projected area on its dominant
// plane exceeds the cutoff (voxels^2) is not voxelized here but appended, as three (vertex, object)
// corners, to the large-triangle buffer that pass 2 draws indirectly (large.vert).
// Attributes per voxel are interpolated by hand (the thesis: "the triangle-parallel path must
// interpolate attributes manually"): barycentrics of the voxel column's centre on the plane.
// The box is split over VCT_INVOCATIONS geometry-shader invocations, invocation i taking rows
// bmin.x + i, + VCT_INVOCATIONS, ...: one invocation looping over a large triangle's whole box (~10^6
// iterations at N=512) outlasts a GPU watchdog, and past llvmpipe's loop budget its loops end
// silently (issue 29 #10). Invocation 0 counts a triangle whose share of the box's voxels may pass
// u_loopBudget (c_counts[8], the counter oversizedTriangles, warned about by the host). The estimate
// leaves out the injection's own loops (a lower bound: on llvmpipe one invocation a triangle lost a
// quarter of cornell-box's writes at N=64 uncounted, hence the default of 8).
// Defines: VCT_STORAGE, VCT_CONSERVATIVE (0/1), VCT_HYBRID (0/1), VCT_INVOCATIONS (1..32; the GL 4.5
// minimum of GL_MAX_GEOMETRY_SHADER_INVOCATIONS is 32). Uniform: u_loopBudget. Emits no primitives.
#if VCT_STORAGE == 2 && VCT_FLOAT_ATOMICS  // SH_F32 (vct_shared.h is not included yet) with float atomics
#extension GL_NV_shader_atomic_float : require
#endif
#define VCT_WRITE 1
#include "common/scene.glsl"
#include "techniques/vct/volume.glsl"
#include "techniques/vct/overlap.glsl"
#include "techniques/vct/inject.glsl"

#ifndef VCT_INVOCATIONS
#define VCT_INVOCATIONS 1
#endif
layout(triangles, invocations = VCT_INVOCATIONS) in;
layout(points, max_vertices = 1) out;

in vec3 vg_posWorld[];
in vec3 vg_normal[];
in vec2 vg_uv[];
flat in uint vg_object[];
flat in uint vg_vertex[];

uniform uint u_loopBudget;  // the device profile's shader loop budget (gl::shaderLoopIterationBudget)

#if VCT_HYBRID
layout(std430, binding = BINDING_SSBO_TECH3) writeonly buffer LargeTriangles { uvec2 l_corners[]; };
uniform uint u_largeCapacity;  // triangles the buffer holds
#endif

void main() {
    const bool conservative = VCT_CONSERVATIVE != 0;
    int N = int(u_vct.grid.x + 0.5);
    VoxTri t = voxTriSetup(gl_in[0].gl_Position.xyz, gl_in[1].gl_Position.xyz, gl_in[2].gl_Position.xyz,
                           conservative, N);
    if (!t.valid) return;
#if VCT_HYBRID
    // The classification metric of section 4.1.3: the triangle's area projected on its dominant
    // plane, in voxel units^2 (t.n.z = |cross(e0, e1)| along the depth axis = twice that area).
    float projectedArea = 0.5 * t.n.z;
    if (projectedArea > u_vct.voxelize.y) {
        if (gl_InvocationID != 0) return;
        uint slot = atomicAdd(c_counts[4], 3u) / 3u;  // the pass-2 DrawArraysIndirectCommand's count
        atomicAdd(c_counts[2], 1u);
        if (slot < u_largeCapacity) {
            for (int k = 0; k < 3; ++k) l_corners[slot * 3u + uint(k)] = uvec2(vg_vertex[k], vg_object[k]);
        }
        return;
    }
#endif
    if (gl_InvocationID == 0) {
        atomicAdd(c_counts[1], 1u);
        // This invocation's loop iterations at most: its rows x the box's columns x (depth range + 1),
        // plus the row loop itself.
        uvec3 box = uvec3(t.bmax - t.bmin + 1);
        uint rows = (box.x + uint(VCT_INVOCATIONS) - 1u) / uint(VCT_INVOCATIONS);
        if (float(rows) * float(box.y) * float(box.z + 1u) + float(rows) > float(u_loopBudget)) atomicAdd(c_counts[8], 1u);  // float: no 32-bit overflow
    }
    uint material = u_objects[vg_object[0]].info.x;
    bool twoSided = u_materials[material].params.w > 0.5;
    bool masked = u_materials[material].alpha.x > 0.0;
    // Barycentric set-up in the dominant (XY) projection, never degenerate after the swizzle.
    vec2 a = t.v0.xy, b = t.v1.xy, c = t.v2.xy;
    float area2 = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    for (int x = t.bmin.x + gl_InvocationID; x <= t.bmax.x; x += VCT_INVOCATIONS) {
        for (int y = t.bmin.y; y <= t.bmax.y; ++y) {
            vec2 p = vec2(x, y);
            if (!voxTestXY(t, p)) continue;
            ivec2 zr = voxDepthRange(t, p, conservative);
            if (zr.x > zr.y) continue;
            if (masked) {
                // An alpha-masked material's voxel column exists where the mask covers the column
                // centre's point on the triangle (one sample per column, as the injection's attributes).
                vec2 q = p + 0.5;
                float l1 = ((q.x - a.x) * (c.y - a.y) - (c.x - a.x) * (q.y - a.y)) / area2;
                float l2 = ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / area2;
                vec2 uvq = (1.0 - l1 - l2) * vg_uv[0] + l1 * vg_uv[1] + l2 * vg_uv[2];
                if (materialMasked(material, uvq)) continue;
            }
            bool shaded = false;
            vec3 radiance = vec3(0.0);
            for (int z = zr.x; z <= zr.y; ++z) {
                if (!voxTestYZZX(t, vec3(x, y, z))) continue;
                if (!shaded && u_vct.range.w < 0.5) {
                    // Attributes at the column centre on the triangle's plane, extrapolated where the
                    // centre lies outside the triangle (a voxel the overlap test keeps near an edge),
                    // as the fragment-parallel path does for its dilated triangle (Eq. 4.4). Clamping
                    // moved those voxels' points onto the edge: 5 % off under a point light.
                    vec2 q = p + 0.5;
                    float l1 = ((q.x - a.x) * (c.y - a.y) - (c.x - a.x) * (q.y - a.y)) / area2;  // weight of b
                    float l2 = ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / area2;  // weight of c
                    vec3 w = vec3(1.0 - l1 - l2, l1, l2);
                    vec3 xw = w.x * vg_posWorld[0] + w.y * vg_posWorld[1] + w.z * vg_posWorld[2];
                    vec3 nw = normalize(w.x * vg_normal[0] + w.y * vg_normal[1] + w.z * vg_normal[2] + 1e-12);
                    vec2 uv = w.x * vg_uv[0] + w.y * vg_uv[1] + w.z * vg_uv[2];
                    radiance = injectedRadiance(xw, nw, (1.0 - u_materials[material].params.y) * materialAlbedo(material, uv), twoSided);
                    shaded = true;
                }
                writeVoxel(voxUnswizzle(ivec3(x, y, z), t.axis), radiance);
            }
        }
    }
}
