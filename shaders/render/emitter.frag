// Area-light emitter in the G-buffer: radiance on the emitting side; from behind the rectangle is
// not there at all (as in the reference, whose rays pass through an area light's back).
// Same outputs as render/gbuffer.frag.
#include "common/shared.h"
layout(std140, binding = BINDING_UBO_LIGHT) uniform LightBlock { LightGpu u_light; };
layout(std140, binding = BINDING_UBO_VIEW) uniform ViewBlock { ViewUniforms u_view; };
in vec3 v_posWorld;
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out vec4 o_emission;
void main() {
    vec3 n = normalize(cross(u_light.edgeU.xyz, u_light.edgeV.xyz));
    if (dot(u_view.eyePosition.xyz - v_posWorld, n) <= 0.0) discard;
    o_position = vec4(v_posWorld, 1.0);
    o_normal = vec4(n, 1.0);
    o_albedo = vec4(0.0);
    o_emission = vec4(u_light.emission.rgb, 0.0);
}
