// The area-light technique's direct radiance (Nichols 2010 ch. 5): emitted radiance (emitters and
// emissive surfaces from the G-buffer) plus, at pixels no light culls (§5.3.2's per-corner and
// one-sided tests, repeated per pixel so that no coarse cell's light leaks onto a pixel that faces
// away), the diffuse part (1 - metallic) albedo / pi * E and the specular part F_Schlick(N.V) * S
// from the upsampled multiresolution buffers.
// Inputs: G-buffer, u_frame, u_pass, diffuse and specular level-0 results (BINDING_TEX_TECH0, TECH1).
// Output: direct radiance W/(m^2 sr).
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "common/constants.glsl"
#include "techniques/area_light/area_common.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_diffuse;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_specular;
uniform bool u_hasSpecular;
layout(location = 0) out vec4 o_radiance;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    Surface s = readSurface(p);
    vec3 radiance = s.covered ? s.emission : vec3(0.0);
    if (s.covered && !culledByAllLights(s.position, s.normal)) {
        vec3 e = texelFetch(s_diffuse, ivec3(p, 0), 0).rgb;
        radiance += (1.0 - s.metallic) * s.albedo * kInvPi * e;
        if (u_hasSpecular) {
            vec3 f0 = mix(vec3(s.specularF0), s.albedo, s.metallic);
            float nDotV = max(dot(s.normal, normalize(u_frame.eyePosition.xyz - s.position)), 0.0);
            vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - nDotV, 5.0);
            if (max(f0.r, max(f0.g, f0.b)) > 0.0) radiance += fresnel * texelFetch(s_specular, ivec3(p, 0), 0).rgb;
        }
    }
    o_radiance = vec4(radiance, 1.0);
}
