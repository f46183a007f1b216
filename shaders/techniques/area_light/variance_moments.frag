// Variance visibility for sharp lobes, the query pass (Nichols 2010 §5.3.3.3, checklist item 21;
// after variance shadow maps, Donnelly & Lauritzen 2006). A rendered specular cell whose lobe holds
// fewer than lobeVpls VPLs sends visibility queries to the lobe samples instead of binary rays: per
// query the first and second moments of the occluder distance along the ray. With 2x2 interleaving
// (as the thesis: 24 queries, 12 floats per pixel in three RGBA float targets) the cell of parity s
// sends queries k = s, s + 4, ..., s + 20 of the 24. Distances are fractions of the ray's length
// (1 = free), so that the blur can average neighbours whose rays differ in length (an assumption;
// the thesis stores distances). A query that is not sent (off the light, broad lobe) stores -1.
// Host uniforms: u_level, u_levelOrigin. Inputs: eye pyramid geometry, normal, lobe (TECH0..2),
// u_frame, voxel grid. Output: moments (image BINDING_IMG0, rgba32f atlas array, layer 3 light + j/2,
// components 2 (j % 2) and 2 (j % 2) + 1 for query j of the cell's six).
#include "techniques/nichols/atlas.glsl"
#include "techniques/area_light/area_common.glsl"
#include "techniques/area_light/lobe.glsl"
#include "techniques/area_light/lobe_samples.glsl"
#define SV_OUTER_GRID  // rays beyond the camera's frustum are tested in the grid along the lights (voxelOutside)
#include "techniques/screen_voxels/march.glsl"
#include "common/frame.glsl"
layout(early_fragment_tests) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_lobe;
layout(rgba32f, binding = BINDING_IMG0) writeonly uniform image2DArray i_moments;
layout(std430, binding = BINDING_SSBO_TECH1) buffer StatsBlock { uint u_stats[AL_STAT_COUNT]; };
layout(location = 0) out vec4 o_unused;

void main() {
    ivec2 cell = ivec2(gl_FragCoord.xy) - u_levelOrigin;
    vec4 g = texelFetch(s_geometry, ivec3(cell, 0), u_level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, ivec3(cell, 0), u_level).xyz + vec3(0.0, 0.0, 1e-12));
    float roughness = texelFetch(s_lobe, ivec3(cell, 0), u_level).x;
    vec3 R = reflect(-normalize(u_frame.eyePosition.xyz - x), n);
    float theta = lobeHalfAngle(roughness, u_pass.lobe.x);
    vec3 origin = x + n * u_pass.march.z;
    int s = alParity(cell, 4);
    uint queries = 0u;
    for (int i = 0; i < int(u_pass.counts.x); ++i) {
        AreaLightGpu L = u_pass.lights[i];
        LobeFootprint f = lobeFootprint(L, x, R, theta);
        bool sharp = f.vplsInLobe < u_pass.lobe.y;
        vec4 texel[3] = vec4[3](vec4(-1.0), vec4(-1.0), vec4(-1.0));
        for (int j = 0; j < 6; ++j) {
            int k = s + 4 * j;
            vec3 y;
            vec2 uv;
            if (!sharp || !lobeSamplePoint(L, x, R, f, k, y, uv)) continue;
            float d = voxelMarch(origin, rayEnd(L, y, x), int(u_pass.march.x), int(u_pass.march.y));
            ++queries;
            texel[j / 2][2 * (j % 2)] = d;
            texel[j / 2][2 * (j % 2) + 1] = d * d;
        }
        for (int l = 0; l < 3; ++l) imageStore(i_moments, ivec3(gl_FragCoord.xy, 3 * i + l), texel[l]);
    }
    atomicAdd(u_stats[AL_STAT_RAYS_CAST], queries);
    o_unused = vec4(0.0);
}
