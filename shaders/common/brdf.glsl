// The BRDF of docs/scene.md "Materials", identical to the reference path tracer's:
//   f = (1 - metallic) * albedo / pi + D_GGX * G_Smith * F_Schlick / (4 cos_i cos_o)
// with F0 = mix(specularF0, albedo, metallic) and alpha = roughness^2 (Walter et al. 2007, GGX;
// height-uncorrelated Smith G1 products; Schlick 1994 Fresnel).
#include "common/constants.glsl"

float ggxD(float nDotH, float alpha) {
    float a2 = alpha * alpha;
    float d = nDotH * nDotH * (a2 - 1.0) + 1.0;
    return a2 / max(kPi * d * d, 1e-12);
}

float smithG1(float nDotX, float alpha) {
    float a2 = alpha * alpha;
    return 2.0 * nDotX / (nDotX + sqrt(a2 + (1.0 - a2) * nDotX * nDotX));
}

// BRDF value times cos(theta_i) for unit normal n, direction to light l, direction to eye v.
vec3 brdfCos(vec3 n, vec3 l, vec3 v, vec3 albedo, float roughness, float metallic, float specularF0) {
    float nDotL = dot(n, l);
    float nDotV = dot(n, v);
    if (nDotL <= 0.0 || nDotV <= 0.0) return vec3(0.0);
    vec3 result = (1.0 - metallic) * albedo * kInvPi;
    vec3 f0 = mix(vec3(specularF0), albedo, metallic);
    if (max(f0.r, max(f0.g, f0.b)) > 0.0) {
        float alpha = max(roughness * roughness, 1e-3);
        vec3 h = normalize(l + v);
        float nDotH = max(dot(n, h), 0.0);
        float vDotH = max(dot(v, h), 0.0);
        vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vDotH, 5.0);
        float g = smithG1(nDotL, alpha) * smithG1(nDotV, alpha);
        result += ggxD(nDotH, alpha) * g * fresnel / (4.0 * nDotL * nDotV);
    }
    return result * nDotL;
}
