// Coarse-to-fine, empty-aware upsampling and combination (Nichols 2010 §3.2.5, checklist item 6),
// one level per dispatch from the coarsest down to 0. A cell of level k "has data" if it was rendered
// at k (atlas alpha) or lies under a coarser cell with data (parent result, nearest). Its value is
// rendered + inherited: splatting (multires-splat) adds each VPL's light at its own levels, and the
// one-pass stencil renders every pixel at one level, so the sets are disjoint there. With
// u_replaceInherited (area-light's incremental stencil, §5.3.4, re-renders finer cells under coarse
// ones that were already lit) the rendered value replaces the inherited one. An inherited cell becomes the (1,2,1)x(1,2,1) tent-weighted
// average of the 3x3 neighbours that have data (weights are an assumption; the thesis does not give
// them); a cell rendered at this level keeps its value (deviation: the thesis's pseudo-code filters it
// too, which blurs full-resolution results across edges). Output only where the cell has data, so
// energy never crosses into or out of empty cells.
// u_filter (nichols::UpsampleFilter) 1 and 2 replace the empty-aware filter for comparison: 1 copies the
// inherited (nearest parent) value; 2 interpolates the parent level bilinearly at the cell centre,
// empty parents counting as black (the naive reconstruction §3.2.5 avoids).
// Host uniforms: u_level, u_levelOrigin, u_size, u_parentSize, u_hasParent, u_replaceInherited, u_filter.
// Inputs: atlas (BINDING_TEX_TECH0), result of level k+1 (BINDING_TEX_TECH1, lod k+1).
// Output: result of level k (image BINDING_IMG0, rgba32f 2D array mip k; alpha 1 = has data).
#include "techniques/nichols/atlas.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2D s_atlas;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_parent;
layout(rgba32f, binding = BINDING_IMG0) writeonly uniform image2DArray i_result;
uniform ivec2 u_size;
uniform ivec2 u_parentSize;
uniform bool u_hasParent;
uniform bool u_replaceInherited;
uniform int u_filter;  // 0 empty-aware (thesis), 1 nearest, 2 naive bilinear

vec4 cellValue(ivec2 c) {
    vec4 rendered = texelFetch(s_atlas, u_levelOrigin + c, 0);
    vec4 inherited = u_hasParent ? texelFetch(s_parent, ivec3(min(c / 2, u_parentSize - 1), 0), u_level + 1) : vec4(0.0);
    if (u_replaceInherited) return rendered.a > 0.5 ? vec4(rendered.rgb, 1.0) : inherited;
    return vec4(rendered.rgb + inherited.rgb, max(rendered.a, inherited.a));
}

// Every cell's 3x3 neighbourhood comes from a (8 + 2)^2 tile of cellValue()s that the workgroup
// fetches once (two texel fetches per tile cell instead of eighteen per cell: on llvmpipe each fetch
// with per-lane coordinates is a loop over the lanes). Cells outside the level are alpha 0, which the
// filter skips as it skips empty cells.
const int kTile = 8 + 2;
shared vec4 s_tile[kTile * kTile];

vec4 tileValue(ivec2 local) {
    return s_tile[local.y * kTile + local.x];
}

void main() {
    ivec2 tileOrigin = ivec2(gl_WorkGroupID.xy) * 8 - 1;
    for (int i = int(gl_LocalInvocationIndex); i < kTile * kTile; i += 64) {
        ivec2 n = tileOrigin + ivec2(i % kTile, i / kTile);
        bool inside = all(greaterThanEqual(n, ivec2(0))) && all(lessThan(n, u_size));
        s_tile[i] = inside ? cellValue(n) : vec4(0.0);
    }
    barrier();
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, u_size))) return;
    ivec2 local = ivec2(gl_LocalInvocationID.xy) + 1;
    vec4 own = tileValue(local);
    vec4 result = vec4(0.0);
    bool renderedHere = texelFetch(s_atlas, u_levelOrigin + c, 0).a > 0.5;
    if (renderedHere) {
        result = vec4(own.rgb, 1.0);
    } else if (own.a > 0.5 && u_filter == 1) {
        result = vec4(own.rgb, 1.0);
    } else if (own.a > 0.5 && u_filter == 2) {
        // Parent texel space: cell c's centre is at (c + 0.5) / 2 - 0.5; empty parents are black (rgb 0
        // where alpha 0, as the result level stores them).
        vec2 p = (vec2(c) + 0.5) * 0.5 - 0.5;
        ivec2 p0 = ivec2(floor(p));
        vec2 f = p - vec2(p0);
        vec3 sum = vec3(0.0);
        for (int dy = 0; dy <= 1; ++dy)
            for (int dx = 0; dx <= 1; ++dx) {
                ivec2 q = clamp(p0 + ivec2(dx, dy), ivec2(0), u_parentSize - 1);
                vec4 v = texelFetch(s_parent, ivec3(q, 0), u_level + 1);
                sum += (dx == 1 ? f.x : 1.0 - f.x) * (dy == 1 ? f.y : 1.0 - f.y) * (v.a > 0.5 ? v.rgb : vec3(0.0));
            }
        result = vec4(sum, 1.0);
    } else if (own.a > 0.5) {
        vec3 sum = vec3(0.0);
        float weight = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                vec4 v = tileValue(local + ivec2(dx, dy));
                if (v.a < 0.5) continue;
                float w = float((2 - abs(dx)) * (2 - abs(dy)));
                sum += w * v.rgb;
                weight += w;
            }
        result = vec4(sum / weight, 1.0);
    }
    imageStore(i_result, ivec3(c, 0), result);
}
