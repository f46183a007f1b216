// Cube distance maps (point lights, area lights, wide spots): distance from the view's eye to the
// surface over the far distance (u_view.eyePosition.w). Inputs: render/scene.vert. Output: R32F.
#include "common/scene.glsl"
in vec3 v_posWorld;
layout(location = 0) out float o_distance;
void main() { o_distance = length(v_posWorld - u_view.eyePosition.xyz) / u_view.eyePosition.w; }
