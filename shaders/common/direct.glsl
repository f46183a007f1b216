// Unshadowed direct radiance of one light at a G-buffer surface (docs/rendering.md): reflected
// radiance L_o = brdf * cos * E for punctual lights (common/lighting.glsl), and for area lights the
// diffuse lobe times the exact polygon irradiance plus the specular lobe evaluated towards the centre
// with the rectangle as a point of intensity L*A*cos(theta_light) (|cos| for a two-sided light). The caller multiplies by its
// visibility (shadow maps in render/direct_light.frag, a cone in techniques/vct).
#ifndef BOUNCE_DIRECT_GLSL
#define BOUNCE_DIRECT_GLSL
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"
#include "common/brdf.glsl"

vec3 unshadowedDirectRadiance(LightGpu L, Surface s, vec3 eye) {
    vec3 v = normalize(eye - s.position);
    if (lightType(L) == LIGHT_AREA) {
        vec3 diffuse = (1.0 - s.metallic) * s.albedo * kInvPi;
        vec3 radiance = diffuse * areaIrradiance(L, s.position, s.normal);
        vec3 f0 = mix(vec3(s.specularF0), s.albedo, s.metallic);
        if (max(f0.r, max(f0.g, f0.b)) > 0.0) {
            vec3 d = L.position.xyz - s.position;
            float r2 = max(dot(d, d), 1e-12);
            vec3 l = d * inversesqrt(r2);
            vec3 nl = normalize(cross(L.edgeU.xyz, L.edgeV.xyz));
            float area = length(cross(L.edgeU.xyz, L.edgeV.xyz));
            // Two-sided: the face towards the receiver emits, so the cosine at the light is |cos|.
            float cosLight = areaTwoSided(L) ? abs(dot(-l, nl)) : max(dot(-l, nl), 0.0);
            vec3 intensity = L.emission.rgb * area * cosLight;
            vec3 specularOnly = brdfCos(s.normal, l, v, s.albedo, s.roughness, s.metallic, s.specularF0) -
                                diffuse * max(dot(s.normal, l), 0.0);
            radiance += max(specularOnly, vec3(0.0)) * intensity / r2;
        }
        return radiance;
    }
    vec3 l;
    vec3 e = punctualIrradiance(L, s.position, l);
    return brdfCos(s.normal, l, v, s.albedo, s.roughness, s.metallic, s.specularF0) * e;
}

#endif
