// Rectangular area lights as visible emitters in the G-buffer: 4 vertices (triangle strip) per
// light from LightGpu data. Inputs: u_light (BINDING_UBO_LIGHT). Outputs: world position, (u, v).
#include "common/shared.h"
layout(std140, binding = BINDING_UBO_LIGHT) uniform LightBlock { LightGpu u_light; };
layout(std140, binding = BINDING_UBO_VIEW) uniform ViewBlock { ViewUniforms u_view; };
out vec3 v_posWorld;
out vec2 v_uv;  // (u, v) of the scene model's AreaTexture
void main() {
    vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1) - 0.5;
    vec3 p = u_light.position.xyz + corner.x * u_light.edgeU.xyz + corner.y * u_light.edgeV.xyz;
    v_posWorld = p;
    v_uv = corner + 0.5;
    gl_Position = u_view.clipFromWorld * vec4(p, 1.0);
}
