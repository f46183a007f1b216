// Cube distance maps (point lights, area lights, wide spots): distance from the view's eye to the
// surface over the far distance (u_view.eyePosition.w). Inputs: render/scene.vert. Output: R32F.
#include "common/scene.glsl"
in vec3 v_posWorld;
in vec2 v_uv;
flat in uint v_object;
layout(location = 0) out float o_distance;
void main() {
    if (materialMasked(u_objects[v_object].info.x, v_uv)) discard;  // masked texels occlude nothing
    o_distance = length(v_posWorld - u_view.eyePosition.xyz) / u_view.eyePosition.w;
}
