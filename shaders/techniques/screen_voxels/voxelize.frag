// Screen-space binary voxelization (Nichols 2010 §5.3.3, checklist item 18; Eisemann & Décoret,
// "Single-pass GPU solid voxelization", 2006): every fragment of every triangle, without depth test or
// culling, sets the bits of its pixel's column that hold the view depths the triangle spans inside
// that column (one bit for a surface facing the camera, several at grazing angles); the framebuffer
// ORs the bits together (glLogicOp(GL_OR) on RGBA32UI targets). Slices are linear in view depth
// between the grid's near and far (as Eisemann & Décoret's uniform slicing). Output target k holds
// bits 128k .. 128k + 127 (component c, bit b = slice 128k + 32c + b).
// The span: the triangle's screen image clipped to the pixel's square (Sutherland-Hodgman, carrying
// depth / w and 1 / w, which are affine in screen space), whose vertices hold the extreme depths.
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
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
in vec3 g_posWorld;
flat in vec2 g_depthRange;
flat in vec3 g_screenX;
flat in vec3 g_screenY;
flat in vec3 g_depthOverW;
flat in vec3 g_invW;
uniform bool u_footprint;
layout(location = 0) out uvec4 o_bits[SV_MAX_LAYERS];

// A triangle clipped by the four sides of a square keeps at most 3 + 4 vertices.
#define SV_CLIP_VERTICES 7

// Keeps the part of polygon (x, y, depth / w, 1 / w) where sgn * (p[axis] - bound) >= 0.
void clipPolygon(inout vec4 poly[SV_CLIP_VERTICES], inout int count, int axis, float bound, float sgn) {
    vec4 kept[SV_CLIP_VERTICES];
    int n = 0;
    for (int i = 0; i < count; ++i) {
        vec4 a = poly[i], b = poly[(i + 1) % count];
        float da = sgn * (a[axis] - bound), db = sgn * (b[axis] - bound);
        if (da >= 0.0 && n < SV_CLIP_VERTICES) kept[n++] = a;
        if ((da >= 0.0) != (db >= 0.0) && n < SV_CLIP_VERTICES) kept[n++] = mix(a, b, da / (da - db));
    }
    poly = kept;
    count = n;
}

// The view-depth range of the triangle inside this fragment's pixel; false when the triangle has no
// finite screen image or the clip left nothing (rounding at a vertex), for the fallback.
bool exactSpan(out float zLo, out float zHi) {
    zLo = zHi = 0.0;
    if (g_invW == vec3(0.0)) return false;
    vec4 poly[SV_CLIP_VERTICES];
    for (int i = 0; i < 3; ++i) poly[i] = vec4(g_screenX[i], g_screenY[i], g_depthOverW[i], g_invW[i]);
    int count = 3;
    vec2 p0 = floor(gl_FragCoord.xy);
    clipPolygon(poly, count, 0, p0.x, 1.0);
    clipPolygon(poly, count, 0, p0.x + 1.0, -1.0);
    clipPolygon(poly, count, 1, p0.y, 1.0);
    clipPolygon(poly, count, 1, p0.y + 1.0, -1.0);
    if (count == 0) return false;
    zLo = 1e30;
    zHi = -1e30;
    for (int i = 0; i < count; ++i) {
        float z = poly[i].z / poly[i].w;
        zLo = min(zLo, z);
        zHi = max(zHi, z);
    }
    return true;
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
    if (u1 >= 0.0 && u0 < float(bits)) {  // else outside the grid's depth range: not represented
        int s0 = max(int(floor(u0)), 0), s1 = min(int(floor(u1)), bits - 1);
        for (int w = s0 / 32; w <= s1 / 32; ++w) {
            int lo = max(s0 - 32 * w, 0), hi = min(s1 - 32 * w, 31);
            words[w / 4][w % 4] = (hi == 31 ? 0xFFFFFFFFu : ((1u << uint(hi + 1)) - 1u)) & ~((1u << uint(lo)) - 1u);
        }
    }
    for (int k = 0; k < SV_MAX_LAYERS; ++k) o_bits[k] = words[k];
}
