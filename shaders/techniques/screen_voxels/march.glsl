// Voxel ray marching through the screen-space binary voxelization (Nichols 2010 §5.3.3.1, checklist
// item 19): voxelMarch, the thesis's uniform samples, and voxelTrace, an exact column traversal. The thesis found a 3D DDA slow on its GPU ("varying numbers of loop iterations") and
// samples the segment uniformly instead; thin occluders a sample skips are partly caught "by checking
// multiple bits in texels fetched from the voxel buffer. This essentially thickens the ray": each of
// the `steps` segments tests every bit between the slices of its two ends, widened by `thickness`
// bits on each side, in the column under its midpoint. Points outside the camera frustum or the grid's
// depth range are empty: the voxelization only knows what the camera sees (a limitation the thesis
// does not discuss). The caller applies the origin bias.
// Include after defining nothing; needs u_voxels (screen_voxels_shared.h) and s_voxels at
// BINDING_TEX_VOXELS (usampler2DArray, one layer per 128 bits).
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
layout(binding = BINDING_TEX_VOXELS) uniform usampler2DArray s_voxels;

// Any bit of slices [s0, s1] set in column `texel`?
bool voxelBitsSet(ivec2 texel, int s0, int s1) {
    for (int w = s0 / 32; w <= s1 / 32; ++w) {
        int lo = max(s0 - 32 * w, 0), hi = min(s1 - 32 * w, 31);
        uint mask = (hi == 31 ? 0xFFFFFFFFu : ((1u << uint(hi + 1)) - 1u)) & ~((1u << uint(lo)) - 1u);
        uvec4 t = texelFetch(s_voxels, ivec3(texel, w / 4), 0);
        if ((t[w % 4] & mask) != 0u) return true;
    }
    return false;
}

#ifdef SV_OUTER_GRID
// A second grid for the parts of segments outside the camera's frustum or its grid's depth range,
// which the screen-space grid cannot see (area-light's voxelOutside: an orthographic grid over the
// scene's and the lights' bounds, built like the first). A shader defines SV_OUTER_GRID before
// including this file and has the grid bound at BINDING_UBO_VOXELS_OUTER / BINDING_TEX_VOXELS_OUTER;
// a grid of 0 bits (grid.z) is empty (the setting off).
layout(std140, binding = BINDING_UBO_VOXELS_OUTER) uniform OuterVoxelBlock { ScreenVoxelsGpu u_outerVoxels; };
layout(binding = BINDING_TEX_VOXELS_OUTER) uniform usampler2DArray s_outerVoxels;

// Near either end of a segment the outer grid holds the end's own surface (and, for a light set in a
// ceiling, the ceiling): within this many of its voxels (the larger of a column's side and a slice's
// depth) from an end the outer grid is not tested, as the origin bias keeps a ray off its own surface
// in the camera's grid (an assumption).
const float kOuterEndVoxels = 1.5;

// Any bit of slices [s0, s1] set in the outer grid's column `texel`?
bool outerBitsSet(ivec2 texel, int s0, int s1) {
    for (int w = s0 / 32; w <= s1 / 32; ++w) {
        int lo = max(s0 - 32 * w, 0), hi = min(s1 - 32 * w, 31);
        uint mask = (hi == 31 ? 0xFFFFFFFFu : ((1u << uint(hi + 1)) - 1u)) & ~((1u << uint(lo)) - 1u);
        uvec4 t = texelFetch(s_outerVoxels, ivec3(texel, w / 4), 0);
        if ((t[w % 4] & mask) != 0u) return true;
    }
    return false;
}

// The outer grid's verdict on the march segments of a -> b, tested as voxelMarch tests its segments:
// the slices between a segment's end depths (+- thickness) in the column under its midpoint; segments
// whose midpoint lies within kOuterEndVoxels of a or b are free. What depends on a -> b alone is
// computed once per ray (outerRay): the grid is orthographic, so its clip coordinates and view
// depths are affine along the segment and each step interpolates them (the per-step transforms and
// column sizes they replace were half of area-light's frame on courtyard sky; same image).
struct OuterRay {
    vec4 ca, cb;         // clip coordinates of a and b in the outer grid
    float za, zb;        // their view depths
    float skip, span;  // metres: kOuterEndVoxels voxels, |b - a| (not `length`: a method name in GLSL, glslang refuses it as a member)
};
OuterRay outerRay(vec3 a, vec3 b) {
    OuterRay r;
    vec2 res = u_outerVoxels.grid.xy;
    // Column sides (m) of the orthographic grid: 2 / |d ndc / d world| per column count.
    mat4 m4 = u_outerVoxels.clipFromWorld;
    float column = max(2.0 / (length(vec3(m4[0][0], m4[1][0], m4[2][0])) * res.x),
                       2.0 / (length(vec3(m4[0][1], m4[1][1], m4[2][1])) * res.y));
    r.skip = kOuterEndVoxels * max(column, u_outerVoxels.depth.w);
    r.span = distance(a, b);
    r.ca = m4 * vec4(a, 1.0);
    r.cb = m4 * vec4(b, 1.0);
    r.za = -(u_outerVoxels.viewFromWorld * vec4(a, 1.0)).z;
    r.zb = -(u_outerVoxels.viewFromWorld * vec4(b, 1.0)).z;
    return r;
}
// Whether the segment between fractions t0 < t1 of the ray is blocked in the outer grid.
bool outerSegmentBlocked(OuterRay r, float t0, float t1, int thickness) {
    int bits = int(u_outerVoxels.grid.z);
    if (bits < 1) return false;
    float tm = 0.5 * (t0 + t1);
    if (tm * r.span < r.skip || (1.0 - tm) * r.span < r.skip) return false;
    vec4 cm = mix(r.ca, r.cb, tm);
    vec2 ndc = cm.xy / cm.w;
    if (cm.w <= 0.0 || any(greaterThan(abs(ndc), vec2(1.0)))) return false;
    float z0 = mix(r.za, r.zb, t0), z1 = mix(r.za, r.zb, t1);
    float u0 = (min(z0, z1) - u_outerVoxels.depth.x) * u_outerVoxels.depth.z;
    float u1 = (max(z0, z1) - u_outerVoxels.depth.x) * u_outerVoxels.depth.z;
    int s0 = max(int(floor(u0)) - thickness, 0), s1 = min(int(floor(u1)) + thickness, bits - 1);
    if (s0 > s1) return false;
    vec2 res = u_outerVoxels.grid.xy;
    return outerBitsSet(clamp(ivec2((ndc * 0.5 + 0.5) * res), ivec2(0), ivec2(res) - 1), s0, s1);
}
#endif

// Fraction of the segment a -> b (world) before its first occupied sample, 1.0 when it is free.
// With SV_OUTER_GRID, the samples outside the camera's frustum or its grid's depth range are tested
// in the outer grid instead of counting as free.
float voxelMarch(vec3 a, vec3 b, int steps, int thickness) {
    vec4 ca = u_voxels.clipFromWorld * vec4(a, 1.0), cb = u_voxels.clipFromWorld * vec4(b, 1.0);
    float za = -(u_voxels.viewFromWorld * vec4(a, 1.0)).z, zb = -(u_voxels.viewFromWorld * vec4(b, 1.0)).z;
    int bits = int(u_voxels.grid.z);
    vec2 res = u_voxels.grid.xy;
    float prevSlice = (za - u_voxels.depth.x) * u_voxels.depth.z;
#ifdef SV_OUTER_GRID
    OuterRay outer = outerRay(a, b);
#endif
    for (int i = 1; i <= steps; ++i) {
        float t = float(i) / float(steps), tm = (float(i) - 0.5) / float(steps);
        float slice = (mix(za, zb, t) - u_voxels.depth.x) * u_voxels.depth.z;
        vec4 cm = mix(ca, cb, tm);
        vec2 ndc = cm.xy / cm.w;
        float s0f = min(prevSlice, slice), s1f = max(prevSlice, slice);
        prevSlice = slice;
        int s0 = max(int(floor(s0f)) - thickness, 0), s1 = min(int(floor(s1f)) + thickness, bits - 1);
        if (cm.w <= 0.0 || any(greaterThan(abs(ndc), vec2(1.0))) || s0 > s1) {
#ifdef SV_OUTER_GRID
            if (outerSegmentBlocked(outer, float(i - 1) / float(steps), t, thickness))
                return (float(i) - 1.0) / float(steps);
#endif
            continue;
        }
        ivec2 texel = clamp(ivec2((ndc * 0.5 + 0.5) * res), ivec2(0), ivec2(res) - 1);
        if (voxelBitsSet(texel, s0, s1)) return (float(i) - 1.0) / float(steps);
    }
    return 1.0;
}

// Shortens [t0, t1] to where f0 + t (f1 - f0) >= 0 (Liang-Barsky clipping of a segment by one plane).
void voxelClip(float f0, float f1, inout float t0, inout float t1) {
    if (f0 < 0.0 && f1 < 0.0) {
        t1 = -1.0;  // wholly outside
    } else if (f0 < 0.0) {
        t0 = max(t0, f0 / (f0 - f1));
    } else if (f1 < 0.0) {
        t1 = min(t1, f0 / (f0 - f1));
    }
}

// Fraction of the segment a -> b (world) before the first voxel column in which it meets an occupied
// bit, 1.0 when it meets none. Unlike voxelMarch's uniform samples, this visits every column the
// segment's projection crosses (a 2D DDA over the grid, Amanatides & Woo 1987) and tests the slices
// between the segment's depths where it enters and leaves that column, widened by `thickness` bits each
// side: a surface crossed anywhere is found, however thin and however grazing the view of it (uniform
// samples a column or more apart step over a table top seen edge-on; bounce's extension, the thesis
// samples uniformly). The part of the segment outside the camera's frustum or the grid's depth range is
// free. With skipEndColumns the columns of the segment's two end points are not tested: they hold the
// end points' own surfaces and, at a concave edge, the adjacent one (the gathers' receivers and VPLs).
// Cost: at most grid.x + grid.y - 1 columns, each testing at most bits / 32 words
// (VplVisibility::loopIterationsPerTest).
float voxelTrace(vec3 a, vec3 b, int thickness, bool skipEndColumns) {
    vec4 ca = u_voxels.clipFromWorld * vec4(a, 1.0), cb = u_voxels.clipFromWorld * vec4(b, 1.0);
    float za = -(u_voxels.viewFromWorld * vec4(a, 1.0)).z, zb = -(u_voxels.viewFromWorld * vec4(b, 1.0)).z;
    float t0 = 0.0, t1 = 1.0;
    voxelClip(ca.w + ca.x, cb.w + cb.x, t0, t1);
    voxelClip(ca.w - ca.x, cb.w - cb.x, t0, t1);
    voxelClip(ca.w + ca.y, cb.w + cb.y, t0, t1);
    voxelClip(ca.w - ca.y, cb.w - cb.y, t0, t1);
    voxelClip(za - u_voxels.depth.x, zb - u_voxels.depth.x, t0, t1);
    voxelClip(u_voxels.depth.y - za, u_voxels.depth.y - zb, t0, t1);
    if (t0 >= t1) return 1.0;
    vec2 res = u_voxels.grid.xy;
    int bits = int(u_voxels.grid.z);
    vec4 c0 = mix(ca, cb, t0), c1 = mix(ca, cb, t1);
    float z0 = mix(za, zb, t0), z1 = mix(za, zb, t1);
    // Column coordinates of the clipped ends, kept kInside columns inside the grid: an end clipped to
    // the frustum's far side lies on the border, whose floor() would be one column past the grid.
    const float kInside = 1e-3;  // columns
    vec2 p0 = clamp((c0.xy / c0.w * 0.5 + 0.5) * res, vec2(0.0), res - kInside);
    vec2 p1 = clamp((c1.xy / c1.w * 0.5 + 0.5) * res, vec2(0.0), res - kInside);
    vec2 d = p1 - p0;
    ivec2 cell = ivec2(floor(p0));
    ivec2 first = cell, last = ivec2(floor(p1));
    // The end points' own columns are skipped only where the segment had its ends there (not where it
    // was clipped).
    bool skipFirst = skipEndColumns && t0 == 0.0, skipLast = skipEndColumns && t1 == 1.0;
    ivec2 stepDir = ivec2(sign(d));
    const float kNever = 1e30;  // screen parameter of a boundary the segment does not cross
    vec2 sDelta = vec2(d.x != 0.0 ? 1.0 / abs(d.x) : kNever, d.y != 0.0 ? 1.0 / abs(d.y) : kNever);
    vec2 sMax = vec2(d.x > 0.0 ? (floor(p0.x) + 1.0 - p0.x) * sDelta.x : (d.x < 0.0 ? (p0.x - floor(p0.x)) * sDelta.x : kNever),
                     d.y > 0.0 ? (floor(p0.y) + 1.0 - p0.y) * sDelta.y : (d.y < 0.0 ? (p0.y - floor(p0.y)) * sDelta.y : kNever));
    float sIn = 0.0;
    int maxCells = int(res.x + res.y);
    for (int i = 0; i < maxCells; ++i) {
        float sOut = min(min(sMax.x, sMax.y), 1.0);
        // Screen parameter s -> fraction between the clipped ends (perspective: 1/w is linear in s).
        float uIn = sIn * c0.w / ((1.0 - sIn) * c1.w + sIn * c0.w);
        float uOut = sOut * c0.w / ((1.0 - sOut) * c1.w + sOut * c0.w);
        float sliceIn = (mix(z0, z1, uIn) - u_voxels.depth.x) * u_voxels.depth.z;
        float sliceOut = (mix(z0, z1, uOut) - u_voxels.depth.x) * u_voxels.depth.z;
        int s0 = max(int(floor(min(sliceIn, sliceOut))) - thickness, 0);
        int s1 = min(int(floor(max(sliceIn, sliceOut))) + thickness, bits - 1);
        bool skip = (skipFirst && cell == first) || (skipLast && cell == last);
        if (!skip && s0 <= s1 && voxelBitsSet(clamp(cell, ivec2(0), ivec2(res) - 1), s0, s1)) return mix(t0, t1, uIn);
        if (sOut >= 1.0) break;
        if (sMax.x < sMax.y) {
            cell.x += stepDir.x;
            sIn = sMax.x;
            sMax.x += sDelta.x;
        } else {
            cell.y += stepDir.y;
            sIn = sMax.y;
            sMax.y += sDelta.y;
        }
    }
    return 1.0;
}
