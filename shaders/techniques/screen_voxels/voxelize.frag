// Screen-space binary voxelization (Nichols 2010 §5.3.3, checklist item 18; Eisemann & Décoret,
// "Single-pass GPU solid voxelization", 2006): every fragment of every triangle, without depth test or
// culling, sets the bits of its pixel's column that hold the view depths the triangle spans inside
// that column (one bit for a surface facing the camera, several at grazing angles); the framebuffer
// ORs the bits together (glLogicOp(GL_OR) on RGBA32UI targets). Slices are linear in view depth
// between the grid's near and far (as Eisemann & Décoret's uniform slicing). Output target k holds
// bits 128k .. 128k + 127 (component c, bit b = slice 128k + 32c + b).
// The span: the depths at the vertices of the triangle's screen image clipped to the pixel's square
// (depth / w and 1 / w are affine in screen space), found without building the clipped polygon.
// Setting only the bit of the centre's depth left a surface seen at a grazing angle (a floor, a table
// top at eye level) with empty slices between its columns' bits, through which rays passed undetected
// (ScreenVoxelsGpuTest.GrazingSurfacesHaveNoDepthGaps); the earlier footprint, the centre's depth +-
// half its change over one column, reached past the triangle's edges (voxelize.geom) and blocked rays
// passing within a column of an edge seen edge-on (area-light: the Cornell tall block's lit face lost
// 18 % of its light under its own top face's voxels).
// u_footprint = false is the thesis's voxel (area-light's voxelFootprint=false): one bit, the slice
// at the column centre.
// Inputs: voxelize.geom's world position, vertex data and triangle depth range, u_voxels
// (BINDING_UBO_VOXELS), u_footprint. Outputs: up to SV_MAX_LAYERS uvec4.
#include "common/scene.glsl"
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
in vec3 g_posWorld;
in vec2 g_uv;
flat in uint g_object;
flat in vec2 g_depthRange;
flat in vec3 g_screenX;
flat in vec3 g_screenY;
flat in vec3 g_depthOverW;
flat in vec3 g_invW;
uniform bool u_footprint;
layout(location = 0) out uvec4 o_bits[SV_MAX_LAYERS];

// Widens [lo, hi] by the view depth at a point of the triangle given by its depth / w and 1 / w.
void include(vec2 dw, inout float lo, inout float hi) {
    float z = dw.x / dw.y;
    lo = min(lo, z);
    hi = max(hi, z);
}

// The view-depth range of the triangle inside this fragment's pixel square; false when the triangle
// has no finite screen image (the fallback). Depth / w and 1 / w are affine on the triangle's screen
// image, so the extremes lie at the vertices of the triangle clipped to the square: the triangle's
// vertices inside the square, the square's corners inside the triangle, and where the triangle's
// edges cross the square's sides. Each candidate is tested directly (no clipped polygon is built:
// llvmpipe spills such arrays to memory, 60x the cost of the whole voxelization).
bool exactSpan(out float zLo, out float zHi) {
    zLo = 1e30;
    zHi = -1e30;
    if (g_invW == vec3(0.0)) return false;
    vec2 lo = floor(gl_FragCoord.xy), hi = lo + 1.0;
    vec2 v0 = vec2(g_screenX.x, g_screenY.x), v1 = vec2(g_screenX.y, g_screenY.y), v2 = vec2(g_screenX.z, g_screenY.z);
    vec2 a0 = vec2(g_depthOverW.x, g_invW.x), a1 = vec2(g_depthOverW.y, g_invW.y), a2 = vec2(g_depthOverW.z, g_invW.z);
    for (int i = 0; i < 3; ++i) {
        vec2 p = i == 0 ? v0 : (i == 1 ? v1 : v2), q = i == 0 ? v1 : (i == 1 ? v2 : v0);
        vec2 ap = i == 0 ? a0 : (i == 1 ? a1 : a2), aq = i == 0 ? a1 : (i == 1 ? a2 : a0);
        if (all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi))) include(ap, zLo, zHi);
        vec2 d = q - p;
        for (int k = 0; k < 4; ++k) {  // the square's sides x = lo.x, x = hi.x, y = lo.y, y = hi.y
            int axis = k / 2;
            float side = (k % 2) == 0 ? lo[axis] : hi[axis];
            if (d[axis] == 0.0) continue;
            float t = (side - p[axis]) / d[axis];
            float other = p[1 - axis] + t * d[1 - axis];
            if (t >= 0.0 && t <= 1.0 && other >= lo[1 - axis] && other <= hi[1 - axis]) include(mix(ap, aq, t), zLo, zHi);
        }
    }
    float area = (v1.x - v0.x) * (v2.y - v0.y) - (v1.y - v0.y) * (v2.x - v0.x);
    if (area != 0.0) {
        for (int k = 0; k < 4; ++k) {  // the square's corners, by their barycentric coordinates
            vec2 c = vec2((k & 1) == 0 ? lo.x : hi.x, (k & 2) == 0 ? lo.y : hi.y);
            float b1 = ((c.x - v0.x) * (v2.y - v0.y) - (c.y - v0.y) * (v2.x - v0.x)) / area;
            float b2 = ((v1.x - v0.x) * (c.y - v0.y) - (v1.y - v0.y) * (c.x - v0.x)) / area;
            if (b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0) include((1.0 - b1 - b2) * a0 + b1 * a1 + b2 * a2, zLo, zHi);
        }
    }
    return zLo <= zHi;
}

void main() {
    float z = -(u_voxels.viewFromWorld * vec4(g_posWorld, 1.0)).z;
    float zLo = z, zHi = z;
    if (u_footprint && !exactSpan(zLo, zHi)) {
        // Fallback: the plane's depth +- half its change over one column, within the triangle's range.
        float halfFootprint = 0.5 * (abs(dFdx(z)) + abs(dFdy(z)));
        zLo = max(z - halfFootprint, g_depthRange.x);
        zHi = min(z + halfFootprint, g_depthRange.y);
    }
    int bits = int(u_voxels.grid.z);
    float u0 = (min(zLo, z) - u_voxels.depth.x) * u_voxels.depth.z;
    float u1 = (max(zHi, z) - u_voxels.depth.x) * u_voxels.depth.z;
    uvec4 words[SV_MAX_LAYERS];
    for (int k = 0; k < SV_MAX_LAYERS; ++k) words[k] = uvec4(0u);
    // An alpha-masked texel is no surface (docs/scene.md): it sets no bit (OR with zero, no discard).
    bool masked = materialMasked(u_objects[g_object].info.x, g_uv);
    if (!masked && u1 >= 0.0 && u0 < float(bits)) {  // else outside the grid's depth range: not represented
        int s0 = max(int(floor(u0)), 0), s1 = min(int(floor(u1)), bits - 1);
        for (int w = s0 / 32; w <= s1 / 32; ++w) {
            int lo = max(s0 - 32 * w, 0), hi = min(s1 - 32 * w, 31);
            words[w / 4][w % 4] = (hi == 31 ? 0xFFFFFFFFu : ((1u << uint(hi + 1)) - 1u)) & ~((1u << uint(lo)) - 1u);
        }
    }
    for (int k = 0; k < SV_MAX_LAYERS; ++k) o_bits[k] = words[k];
}
