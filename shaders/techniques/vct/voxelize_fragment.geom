// Rauwendaal 2013 section 4.1.2: fragment-parallel voxelization, geometry stage. Per triangle: the
// dominant-axis swizzle (Eq. 4.1), the factored overlap constants (passed flat to the fragment
// stage), and conservative rasterization by Hertel et al.'s dilation (Eq. 4.2): each edge is moved
// outwards by l = sqrt(2)/2 voxel (half a pixel diagonal, pixel = voxel column) and the new vertex is
// the intersection of its two moved edges. Attributes of the dilated vertices are extrapolated from
// the original triangle by their barycentric coordinates (Eqs. 4.3-4.4), so interpolation over the
// original region matches the undilated triangle. The viewport is N x N over the swizzled XY plane.
// Also the pass 2 of the hybrid voxelizer (fed by large.vert). Defines: VCT_CONSERVATIVE.
#include "techniques/vct/volume.glsl"
#include "techniques/vct/overlap.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 vg_posWorld[];
in vec3 vg_normal[];
in vec2 vg_uv[];
flat in uint vg_object[];
flat in uint vg_vertex[];

out vec3 gf_posWorld;
out vec3 gf_normal;
out vec2 gf_uv;
flat out uint gf_object;
flat out int gf_axis;
flat out vec3 gf_n;
flat out vec2 gf_dAB;
flat out ivec2 gf_zBounds;
flat out ivec4 gf_xyBounds;  // the triangle's voxel box in the dominant plane (min.xy, max.xy)
flat out vec2 gf_nXY[3];
flat out vec2 gf_nYZ[3];
flat out vec2 gf_nZX[3];
flat out vec3 gf_dXY;
flat out vec3 gf_dYZ;
flat out vec3 gf_dZX;

const float kDilation = 0.70710678;  // l = sqrt(2)/2 voxel: half the diagonal of a unit pixel (4.1.2)

vec3 barycentric2D(vec2 q, vec2 a, vec2 b, vec2 c) {
    float area2 = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    float wb = ((q.x - a.x) * (c.y - a.y) - (c.x - a.x) * (q.y - a.y)) / area2;
    float wc = ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / area2;
    return vec3(1.0 - wb - wc, wb, wc);
}

void main() {
    const bool conservative = VCT_CONSERVATIVE != 0;
    int N = int(u_vct.grid.x + 0.5);
    VoxTri t = voxTriSetup(gl_in[0].gl_Position.xyz, gl_in[1].gl_Position.xyz, gl_in[2].gl_Position.xyz,
                           conservative, N);
    if (!t.valid) return;
    vec2 v[3] = vec2[3](t.v0.xy, t.v1.xy, t.v2.xy);
    float orientation = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
    if (abs(orientation) < 1e-12) return;
    float s = orientation > 0.0 ? 1.0 : -1.0;
    vec2 outward[3];  // unit outward normal of edge i = v[i] -> v[i + 1]
    for (int i = 0; i < 3; ++i) {
        vec2 e = v[(i + 1) % 3] - v[i];
        outward[i] = s * normalize(vec2(e.y, -e.x));
    }
    for (int i = 0; i < 3; ++i) {
        // Intersection of the edges i-1 and i, each moved outwards by l: solve
        // n_{i-1} . d = l and n_i . d = l for the offset d.
        vec2 a = outward[(i + 2) % 3], b = outward[i];
        float det = a.x * b.y - a.y * b.x;
        vec2 d = abs(det) > 1e-6 ? kDilation * vec2(b.y - a.y, a.x - b.x) / det : vec2(0.0);
        vec2 q = v[i] + d;
        vec3 w = barycentric2D(q, v[0], v[1], v[2]);
        gf_posWorld = w.x * vg_posWorld[0] + w.y * vg_posWorld[1] + w.z * vg_posWorld[2];
        gf_normal = w.x * vg_normal[0] + w.y * vg_normal[1] + w.z * vg_normal[2];
        gf_uv = w.x * vg_uv[0] + w.y * vg_uv[1] + w.z * vg_uv[2];
        gf_object = vg_object[0];
        gf_axis = t.axis;
        gf_n = t.n;
        gf_dAB = vec2(t.dA, t.dB);
        gf_zBounds = ivec2(t.bmin.z, t.bmax.z);
        gf_xyBounds = ivec4(t.bmin.xy, t.bmax.xy);
        gf_nXY = t.nXY;
        gf_nYZ = t.nYZ;
        gf_nZX = t.nZX;
        gf_dXY = t.dXY;
        gf_dYZ = t.dYZ;
        gf_dZX = t.dZX;
        gl_Position = vec4(q / float(N) * 2.0 - 1.0, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
