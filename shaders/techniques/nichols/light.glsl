// Radiant intensity of bounce's lights towards a direction, for reflective shadow maps (Nichols 2010
// §3.2.1; intensities of docs/scene.md "Lights"): spot I0 cos^n(alpha) inside the cutoff, point I,
// area (seen from its centre, one-sided Lambertian) L * A * max(cos(theta), 0).
// Inputs: a LightGpu (common/shared.h). dir: unit direction from the light to the surface.
#include "common/shared.h"

vec3 lightIntensity(LightGpu L, vec3 dir) {
    int type = int(L.position.w + 0.5);
    if (type == LIGHT_SPOT) {
        float cosAlpha = dot(dir, normalize(L.direction.xyz));
        if (cosAlpha < L.direction.w || cosAlpha <= 0.0) return vec3(0.0);
        return L.emission.rgb * pow(cosAlpha, L.emission.w);
    }
    if (type == LIGHT_AREA) {
        vec3 n = cross(L.edgeU.xyz, L.edgeV.xyz);
        float area = length(n);
        return L.emission.rgb * area * max(dot(dir, n / area), 0.0);
    }
    return L.emission.rgb;  // point (directional lights use irradiance, handled by the caller)
}
