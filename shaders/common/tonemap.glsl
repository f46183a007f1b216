// Display transform, identical to core/ToneMap.cpp: exposure 2^EV, tone curve, sRGB encoding.
// Curves: 0 clamp, 1 Reinhard x/(1+x), 2 ACES fit (Narkowicz 2015).
vec3 toneCurve(vec3 c, int curve) {
    if (curve == 1) return c / (1.0 + c);
    if (curve == 2) return clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
    return clamp(c, 0.0, 1.0);
}
vec3 srgbEncode(vec3 x) {
    x = clamp(x, 0.0, 1.0);
    return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, greaterThan(x, vec3(0.0031308)));
}
vec3 toDisplay(vec3 radiance, float exposureEv, int curve) {
    return srgbEncode(toneCurve(max(radiance, vec3(0.0)) * exp2(exposureEv), curve));
}
