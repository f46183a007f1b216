// Shared vertex stage of every scene-drawing pass: object -> world -> clip through the current
// view (SceneDrawer). Inputs: ATTR_* vertex attributes, ATTR_OBJECT_INDEX per instance.
// Outputs: world position and normal, uv, tangent, object index (flat).
#include "common/scene.glsl"

layout(location = ATTR_POSITION) in vec3 a_position;
layout(location = ATTR_NORMAL) in vec3 a_normal;
layout(location = ATTR_UV) in vec2 a_uv;
layout(location = ATTR_OBJECT_INDEX) in uint a_object;
layout(location = ATTR_TANGENT) in vec4 a_tangent;

out vec3 v_posWorld;
out vec3 v_normalWorld;
out vec2 v_uv;
out vec4 v_tangentWorld;  // xyz: world tangent (unnormalised), w: bitangent sign, 0 without tangents
flat out uint v_object;

void main() {
    ObjectGpu o = u_objects[a_object];
    vec4 p = o.worldFromObject * vec4(a_position, 1.0);
    v_posWorld = p.xyz;
    v_normalWorld = mat3(o.normalFromObject) * a_normal;
    v_uv = a_uv;
    v_tangentWorld = vec4(mat3(o.worldFromObject) * a_tangent.xyz, a_tangent.w);
    v_object = a_object;
    gl_Position = u_view.clipFromWorld * p;
}
