// Specular gather from textured area lights (Nichols 2010 §5.3.2.1 and §5.3.3.3; checklist item 17),
// the separate "Phong" pass of Fig. 5.3. The thesis's BRDF is pure Phong (R.L)^n; bounce's specular
// lobe is GGX (docs/scene.md), evaluated inside the sum as Eq. 5.2 keeps it:
//   S = sum_j f_s(x, l_j, v) cos(x->y_j, N_x) L_j A_j V cos(y_j->x, N_y) / |x - y_j|^2,
// with f_s = D G / (4 cos_i cos_o) without Fresnel (the final pass multiplies the pixel's Schlick
// F(N.V): a deviation, the Fresnel term of each VPL direction is not kept per cell). A lobe that
// holds fewer than u_pass.lobe.y (thesis: 9) VPLs would show single VPL reflections; the light texture
// is then sampled directly 25 times on a regular 5x5 grid centred where R meets the light, spaced by
// the lobe footprint / 5 and read at the mip level of that spacing (§5.3.2.1). Visibility: each VPL or
// sample is ray-marched (binary), or, for the lobe samples with u_variance, shaded with the variance
// visibility of §5.3.3.3 from the moments variance_moments.frag stored.
// VPLs in the lobe: the footprint is the lobe cone's cross-section where R meets the light plane,
// radius t tan(theta) over |cos(R, N_light)| (an assumption; the thesis does not say how it counts).
// One draw sums VPLs [u_vplFirst, u_vplEnd); the 5x5 samples go with the first draw.
// Host uniforms: u_level, u_levelOrigin, u_levelSize, u_vplFirst, u_vplEnd, u_variance. Inputs: eye pyramid geometry, normal
// and lobe pyramid (BINDING_TEX_TECH0..2), light textures (units kLightTexture0 + i), VPLs
// (BINDING_SSBO_TECH0), u_frame, voxel grid. Output: specular radiance / F (alpha 1 = rendered).
#include "techniques/nichols/atlas.glsl"
#include "techniques/area_light/area_common.glsl"
#include "techniques/area_light/lobe.glsl"
#include "techniques/area_light/lobe_samples.glsl"
#define SV_OUTER_GRID  // rays beyond the camera's frustum are tested in the grid along the lights (voxelOutside)
#include "techniques/screen_voxels/march.glsl"
#include "common/brdf.glsl"
#include "common/frame.glsl"
layout(early_fragment_tests) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_lobe;
layout(binding = BINDING_TEX_AREA_LIGHT) uniform sampler2D s_light0;
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_light1;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2D s_light2;
layout(binding = BINDING_TEX_INPUT2) uniform sampler2D s_light3;
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { AreaVplGpu u_vpls[]; };
layout(std430, binding = BINDING_SSBO_TECH1) buffer StatsBlock { uint u_stats[AL_STAT_COUNT]; };
uniform uint u_vplFirst;
uniform uint u_vplEnd;
layout(location = 0) out vec4 o_radiance;

// Variance visibility (§5.3.3.3): the moments variance_moments.frag wrote at this level.
layout(rgba32f, binding = BINDING_IMG0) readonly uniform image2DArray i_moments;
uniform bool u_variance;
uniform ivec2 u_levelSize;

// Visibility of lobe query k of light i from the moments of the same-parity cells (the ones that sent
// query k) in the 3x3 neighbourhood: the screen-space blur of §5.3.3.3, then Chebyshev's one-sided
// bound p = sigma^2 / (sigma^2 + (t - mu)^2) for the receiver at t = 1 (the light, in ray fractions)
// beyond the mean occluder distance mu (Donnelly & Lauritzen 2006). No neighbour query: 1.
float varianceVisibility(ivec2 cell, int i, int k) {
    int s = k % 4, j = k / 4;
    vec2 m = vec2(0.0);
    float count = 0.0;
    for (int c = 0; c < alRegionCells(1); ++c) {
        ivec2 q;
        if (!alSubsetCell(cell, 1, u_levelSize, 4, s, c, q)) continue;
        vec4 t = imageLoad(i_moments, ivec3(u_levelOrigin + q, 3 * i + j / 2));
        vec2 d = (j % 2) == 0 ? t.xy : t.zw;
        if (d.x < 0.0) continue;  // not sent (off the light, or a broad lobe there)
        m += d;
        count += 1.0;
    }
    if (count == 0.0) return 1.0;
    m /= count;
    float mu = m.x, variance = max(m.y - mu * mu, 1e-6);
    return mu >= 1.0 - 1e-4 ? 1.0 : variance / (variance + (1.0 - mu) * (1.0 - mu));
}

vec3 lightTexel(int i, vec2 uv, float lod) {
    // Constant sampler names in each branch: no sampler indexing (llvmpipe, GLSL 4.50 rules).
    if (i == 0) return textureLod(s_light0, uv, lod).rgb;
    if (i == 1) return textureLod(s_light1, uv, lod).rgb;
    if (i == 2) return textureLod(s_light2, uv, lod).rgb;
    return textureLod(s_light3, uv, lod).rgb;
}

// GGX specular BRDF (without Fresnel) times cos(theta_i).
float specularCos(vec3 n, vec3 l, vec3 v, float alpha) {
    float nDotL = dot(n, l), nDotV = dot(n, v);
    if (nDotL <= 0.0 || nDotV <= 0.0) return 0.0;
    vec3 h = normalize(l + v);
    return ggxD(max(dot(n, h), 0.0), alpha) * smithG1(nDotL, alpha) * smithG1(nDotV, alpha) / (4.0 * nDotV);
}

vec3 origin;

vec3 sampleTerm(vec3 x, vec3 n, vec3 v, float alpha, AreaLightGpu L, vec3 y, vec3 radiance, float area,
                inout uint raysCast, bool march) {
    vec3 d = y - x;
    float r2 = max(dot(d, d), 1e-12);
    vec3 l = d * inversesqrt(r2);
    float cosY = emitterCosine(L, l);
    float f = specularCos(n, l, v, alpha);
    if (cosY <= 0.0 || f <= 0.0) return vec3(0.0);
    if (march && int(u_pass.march.w) != AL_VIS_NONE) {
        ++raysCast;
        if (voxelMarch(origin, rayEnd(L, y, x), int(u_pass.march.x), int(u_pass.march.y)) < 1.0) return vec3(0.0);
    }
    return radiance * (f * area * cosY / alNearFieldR2(r2, area));  // the bound of area_common.glsl
}

void main() {
    ivec2 cell = ivec2(gl_FragCoord.xy) - u_levelOrigin;
    vec4 g = texelFetch(s_geometry, ivec3(cell, 0), u_level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, ivec3(cell, 0), u_level).xyz + vec3(0.0, 0.0, 1e-12));
    float roughness = texelFetch(s_lobe, ivec3(cell, 0), u_level).x;
    float alpha = max(roughness * roughness, 1e-3);
    vec3 v = normalize(u_frame.eyePosition.xyz - x);
    vec3 R = reflect(-v, n);
    float theta = lobeHalfAngle(roughness, u_pass.lobe.x);
    origin = x + n * u_pass.march.z;
    vec3 radiance = vec3(0.0);
    uint raysCast = 0u, lobeSampled = 0u;
    for (int i = 0; i < int(u_pass.counts.x); ++i) {
        AreaLightGpu L = u_pass.lights[i];
        int side = int(L.texture.w);
        uint firstVpl = uint(L.texture.z), endVpl = firstVpl + uint(side * side);
        LobeFootprint f = lobeFootprint(L, x, R, theta);
        if (f.vplsInLobe >= u_pass.lobe.y) {
            uint a = max(firstVpl, u_vplFirst), b = min(endVpl, u_vplEnd);
            for (uint j = a; j < b; ++j) {
                AreaVplGpu p = u_vpls[j];
                radiance += sampleTerm(x, n, v, alpha, L, p.position.xyz, p.radiance.rgb, p.radiance.w, raysCast, true);
            }
        } else if (u_vplFirst == 0u) {
            ++lobeSampled;
            float h = 2.0 * f.radius / float(kLobeGrid);  // sample spacing (m)
            float texel = max(L.edgeU.w / L.texture.x, L.edgeV.w / L.texture.y);
            float lod = max(log2(max(h, 1e-9) / texel), 0.0);
            for (int k = 0; k < kLobeGrid * kLobeGrid; ++k) {
                vec3 y;
                vec2 uv;
                if (!lobeSamplePoint(L, x, R, f, k, y, uv)) continue;
                vec3 le = L.radiance.rgb * (L.radiance.w > 0.5 ? lightTexel(i, uv, lod) : vec3(1.0));
                if (u_variance && int(u_pass.march.w) != AL_VIS_NONE) {
                    // The corner without a query (k = 24) takes its row neighbour's visibility.
                    float vis = varianceVisibility(cell, i, min(k, kLobeQueries - 1));
                    radiance += vis * sampleTerm(x, n, v, alpha, L, y, le, h * h, raysCast, false);
                } else {
                    radiance += sampleTerm(x, n, v, alpha, L, y, le, h * h, raysCast, true);
                }
            }
        }
    }
    atomicAdd(u_stats[AL_STAT_RAYS_CAST], raysCast);
    atomicAdd(u_stats[AL_STAT_LOBE_SAMPLED], lobeSampled);
    o_radiance = vec4(radiance, 1.0);
}
