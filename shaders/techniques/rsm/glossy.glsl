// The glossy (GGX specular) part of bounce's BRDF, common/brdf.glsl's brdfCos without its Lambert
// term, divided by cos(theta_i): f_spec(l, e) in 1/sr. Shared by the rsm gather's `glossy` option and
// multires-splat's mode A, so that mode A with every subsplat at full resolution sums exactly what the
// glossy rsm gather sums.
// Inputs: unit normal n, unit direction to the light l, unit direction to the eye e, the material.
#include "common/brdf.glsl"

vec3 glossyBrdf(vec3 n, vec3 l, vec3 e, vec3 albedo, float roughness, float metallic, float specularF0) {
    vec3 f0 = mix(vec3(specularF0), albedo, metallic);
    float nDotL = dot(n, l);
    if (max(f0.r, max(f0.g, f0.b)) <= 0.0 || nDotL <= 0.0 || dot(n, e) <= 0.0) return vec3(0.0);
    vec3 lambertCos = (1.0 - metallic) * albedo * kInvPi * nDotL;
    return max(brdfCos(n, l, e, albedo, roughness, metallic, specularF0) - lambertCos, vec3(0.0)) / nDotL;
}
