// Rauwendaal 2013, Eq. 7.1: direct light "injected" at voxelization time, C_voxel = C_light C_diffuse
// (n . l) S, with S from the light's shadow map. In radiometric form the voxel stores the radiance a
// Lambertian surface reflects, L = rho / pi * sum_k E_k(x, n) V_k(x) in W/(m^2 sr), for up to
// VCT_MAX_LIGHTS lights (the light set's maps bound at BINDING_TEX_VCT_SHADOW2D0 + k and
// BINDING_TEX_VCT_SHADOWCUBE0 + k). Specular and ambient terms are omitted, as in the thesis. Area
// lights use the exact polygon irradiance with visibility from their centre (docs/rendering.md).
#ifndef BOUNCE_VCT_INJECT_GLSL
#define BOUNCE_VCT_INJECT_GLSL
#include "common/lighting.glsl"

// Separate samplers, not arrays: llvmpipe (Mesa 22.3, LLVM 15) crashes compiling a sampler array
// indexed by the loop counter and passed to a function.
layout(binding = BINDING_TEX_VCT_SHADOW2D0 + 0) uniform sampler2DShadow s_vctShadow2D0;
layout(binding = BINDING_TEX_VCT_SHADOW2D0 + 1) uniform sampler2DShadow s_vctShadow2D1;
layout(binding = BINDING_TEX_VCT_SHADOW2D0 + 2) uniform sampler2DShadow s_vctShadow2D2;
layout(binding = BINDING_TEX_VCT_SHADOW2D0 + 3) uniform sampler2DShadow s_vctShadow2D3;
layout(binding = BINDING_TEX_VCT_SHADOWCUBE0 + 0) uniform samplerCube s_vctShadowCube0;
layout(binding = BINDING_TEX_VCT_SHADOWCUBE0 + 1) uniform samplerCube s_vctShadowCube1;
layout(binding = BINDING_TEX_VCT_SHADOWCUBE0 + 2) uniform samplerCube s_vctShadowCube2;
layout(binding = BINDING_TEX_VCT_SHADOWCUBE0 + 3) uniform samplerCube s_vctShadowCube3;

float injectedVisibility(int k, LightGpu L, vec3 x, vec3 n) {
    if (k == 0) return shadowVisibilityFrom(L, s_vctShadow2D0, s_vctShadowCube0, x, n);
    if (k == 1) return shadowVisibilityFrom(L, s_vctShadow2D1, s_vctShadowCube1, x, n);
    if (k == 2) return shadowVisibilityFrom(L, s_vctShadow2D2, s_vctShadowCube2, x, n);
    return shadowVisibilityFrom(L, s_vctShadow2D3, s_vctShadowCube3, x, n);
}

// Radiance reflected by a Lambertian surface at x (unit normal n, albedo rho) under the injected
// lights. twoSided: the surface reflects on both sides (the normal is turned towards each light).
vec3 injectedRadiance(vec3 x, vec3 n, vec3 rho, bool twoSided) {
    vec3 irradiance = vec3(0.0);
    int count = int(u_vct.range.z + 0.5);
    for (int k = 0; k < VCT_MAX_LIGHTS; ++k) {
        if (k >= count) break;
        LightGpu L = u_vct.lights[k];
        vec3 nk = n;
        vec3 e;
        if (lightType(L) == LIGHT_AREA) {
            if (twoSided && dot(L.position.xyz - x, n) < 0.0) nk = -n;
            e = areaIrradiance(L, x, nk);
        } else {
            vec3 l;
            e = punctualIrradiance(L, x, l);
            float c = dot(nk, l);
            if (twoSided && c < 0.0) { nk = -n; c = -c; }
            e *= max(c, 0.0);
        }
        if (max(e.r, max(e.g, e.b)) <= 0.0) continue;
        irradiance += e * injectedVisibility(k, L, x, nk);
    }
    return rho * kInvPi * irradiance;
}

#endif
