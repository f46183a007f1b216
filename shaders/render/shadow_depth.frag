// Depth-only pass for 2D shadow maps (spot: perspective, directional: orthographic), also
// photon-splat's depth maps. Inputs: render/scene.vert (or a vertex stage with the same outputs).
// Outputs: depth only; alpha-masked texels are no occluders (discarded, docs/scene.md "Materials").
#include "common/scene.glsl"
in vec2 v_uv;
flat in uint v_object;
void main() {
    if (materialMasked(u_objects[v_object].info.x, v_uv)) discard;
}
