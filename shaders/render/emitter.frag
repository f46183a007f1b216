// Area-light emitter in the G-buffer: radiance (times the light's emission texture, Nichols 2010
// ch. 5's video screens; scene model in src/scene/Scene.h AreaTexture) on the emitting side; a one-
// sided light seen from behind is not there at all (as in the reference, whose rays pass through an
// area light's back), a two-sided one shows the same texels from both sides.
// Same outputs as render/gbuffer.frag.
#include "common/shared.h"
layout(std140, binding = BINDING_UBO_LIGHT) uniform LightBlock { LightGpu u_light; };
layout(std140, binding = BINDING_UBO_VIEW) uniform ViewBlock { ViewUniforms u_view; };
layout(binding = BINDING_TEX_AREA_LIGHT) uniform sampler2D s_areaTexture;
in vec3 v_posWorld;
in vec2 v_uv;
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out vec4 o_emission;
void main() {
    vec3 n = normalize(cross(u_light.edgeU.xyz, u_light.edgeV.xyz));
    bool twoSided = (int(u_light.area.w) & AREA_TWO_SIDED) != 0;
    bool textured = (int(u_light.area.w) & AREA_TEXTURED) != 0;
    float facing = dot(u_view.eyePosition.xyz - v_posWorld, n);
    // Implicit-LOD sampling before the discard (derivatives after one are undefined; issue 29 #4's rule).
    vec3 texel = textured ? texture(s_areaTexture, v_uv).rgb : vec3(1.0);
    if (facing <= 0.0 && !twoSided) discard;
    o_position = vec4(v_posWorld, 1.0);
    o_normal = vec4(facing > 0.0 ? n : -n, 1.0);
    o_albedo = vec4(0.0);
    o_emission = vec4(textured ? u_light.area.rgb * texel : u_light.emission.rgb, 0.0);
}
