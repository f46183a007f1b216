// Direct lighting of the camera G-buffer by one light (additively blended, one pass per light).
// Reflected radiance L_o = brdf * cos * E for punctual lights (common/lighting.glsl), and for area
// lights the diffuse lobe times the exact polygon irradiance plus the specular lobe evaluated
// towards the centre with the rectangle as a point of intensity L*A*cos(theta_light).
// Inputs: G-buffer, u_frame, u_light + shadow map. Output: radiance W/(m^2 sr), RGBA32F.
#include "common/frame.glsl"
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"
#include "common/brdf.glsl"

layout(location = 0) out vec4 o_radiance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    Surface s = readSurface(pixel);
    if (!s.covered) discard;
    vec3 v = normalize(u_frame.eyePosition.xyz - s.position);
    vec3 radiance = vec3(0.0);
    if (lightType(u_light) == LIGHT_AREA) {
        vec3 diffuse = (1.0 - s.metallic) * s.albedo * kInvPi;
        radiance = diffuse * areaIrradiance(u_light, s.position, s.normal);
        vec3 f0 = mix(vec3(s.specularF0), s.albedo, s.metallic);
        if (max(f0.r, max(f0.g, f0.b)) > 0.0) {
            vec3 d = u_light.position.xyz - s.position;
            float r2 = max(dot(d, d), 1e-12);
            vec3 l = d * inversesqrt(r2);
            vec3 nl = normalize(cross(u_light.edgeU.xyz, u_light.edgeV.xyz));
            float area = length(cross(u_light.edgeU.xyz, u_light.edgeV.xyz));
            vec3 intensity = u_light.emission.rgb * area * max(dot(-l, nl), 0.0);
            vec3 specularOnly = brdfCos(s.normal, l, v, s.albedo, s.roughness, s.metallic, s.specularF0) -
                                diffuse * max(dot(s.normal, l), 0.0);
            radiance += max(specularOnly, vec3(0.0)) * intensity / r2;
        }
    } else {
        vec3 l;
        vec3 e = punctualIrradiance(u_light, s.position, l);
        radiance = brdfCos(s.normal, l, v, s.albedo, s.roughness, s.metallic, s.specularF0) * e;
    }
    if (max(radiance.r, max(radiance.g, radiance.b)) <= 0.0) discard;
    radiance *= shadowVisibility(u_light, s.position, s.normal);
    o_radiance = vec4(radiance, 1.0);
}
