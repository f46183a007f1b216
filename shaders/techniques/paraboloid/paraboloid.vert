// Paraboloid shadow map of one VPL (Laine et al. 2007 §5.1; Brabec et al. 2002; shared by iir and
// area-light's shadow-map baseline): the hemisphere
// around the VPL's normal maps to the unit disc by uv = d.xy / (1 + d.z), d the unit direction in the
// VPL frame. Host sets u_vplFromWorld (rows: tangent, bitangent, normal) and u_vplPosition (world).
// Inputs: ATTR_* vertex attributes, ATTR_OBJECT_INDEX. Outputs: v_local (position in the VPL frame), v_uv, v_object;
// gl_ClipDistance[0] = d.z removes the back hemisphere.
#include "common/scene.glsl"

layout(location = ATTR_POSITION) in vec3 a_position;
layout(location = ATTR_NORMAL) in vec3 a_normal;
layout(location = ATTR_UV) in vec2 a_uv;
layout(location = ATTR_OBJECT_INDEX) in uint a_object;

uniform mat4 u_vplFromWorld;
uniform vec3 u_vplPosition;

out vec3 v_local;
out vec2 v_uv;          // alpha mask lookup (paraboloid.frag); interpolated in paraboloid space
flat out uint v_object;
out gl_PerVertex {
    vec4 gl_Position;
    float gl_ClipDistance[1];
};

void main() {
    vec4 p = u_objects[a_object].worldFromObject * vec4(a_position, 1.0);
    vec3 local = mat3(u_vplFromWorld) * (p.xyz - u_vplPosition);
    vec3 d = local / max(length(local), 1e-12);
    v_local = local;
    v_uv = a_uv;
    v_object = a_object;
    gl_ClipDistance[0] = d.z;
    // Vertices behind the hemisphere are clipped away; the floor keeps their projection finite.
    gl_Position = vec4(d.xy / max(1.0 + d.z, 1e-3), 0.0, 1.0);
}
