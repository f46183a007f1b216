// The specular lobe as Nichols 2010 §5.3.2.1 uses it for culling, refinement and the choice between
// VPLs and lobe-centred texture samples. The thesis shades pure Phong, (R.L)^n; bounce's BRDF is GGX
// (docs/scene.md), so its lobe is described by the Phong exponent of the same width: GGX alpha^2 ~
// 2 / (s + 2) for the Blinn-Phong exponent s of the half vector (Walter et al. 2007, Eq. 33's
// Beckmann-Phong correspondence), and the reflection-vector lobe is about 4x narrower in exponent,
// n = s / 4 (the half angle doubles). An assumption: the thesis gives no exponent or lobe-width formula.
#include "common/constants.glsl"

float phongExponent(float roughness) {
    float alpha = max(roughness * roughness, 1e-3);
    return max((2.0 / (alpha * alpha) - 2.0) / 4.0, 1e-3);
}

// Half-angle (radians) of the reflection lobe where (R.L)^n falls to `threshold` of its peak.
float lobeHalfAngle(float roughness, float threshold) {
    return acos(clamp(pow(threshold, 1.0 / phongExponent(roughness)), 0.0, 1.0));
}

// §5.3.2.1's lobe-miss test: the lobe around R (half-angle with cosine cosLobe) misses light L when R
// does not hit the rectangle and no point of it lies inside the lobe. The thesis tests the corners;
// bounce also tests the rectangle point nearest to where R meets the light's plane, which catches a
// lobe crossing an edge between two corners.
bool lobeMissesLight(AreaLightGpu L, vec3 x, vec3 R, float cosLobe) {
    vec3 u = L.edgeU.xyz / L.edgeU.w, v = L.edgeV.xyz / L.edgeV.w;
    float denom = dot(R, L.normal.xyz);
    if (abs(denom) > 1e-6) {
        float t = dot(L.centre.xyz - x, L.normal.xyz) / denom;
        if (t > 0.0) {
            vec3 d = x + t * R - L.centre.xyz;
            vec2 uv = vec2(dot(d, u), dot(d, v));
            vec2 half_ = 0.5 * vec2(L.edgeU.w, L.edgeV.w);
            if (all(lessThanEqual(abs(uv), half_))) return false;
            vec2 q = clamp(uv, -half_, half_);
            vec3 p = L.centre.xyz + q.x * u + q.y * v;
            if (dot(normalize(p - x), R) >= cosLobe) return false;
        }
    }
    for (int k = 0; k < 4; ++k)
        if (dot(normalize(lightCorner(L, k) - x), R) >= cosLobe) return false;
    return true;
}
