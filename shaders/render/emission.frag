// Emitted radiance seen by the camera (emissive materials and area-light quads): the first,
// unblended write of the direct-light target. Inputs: G-buffer. Output: radiance, RGBA32F.
#include "common/gbuffer.glsl"
layout(location = 0) out vec4 o_radiance;
void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    o_radiance = vec4(s.covered ? s.emission : vec3(0.0), 1.0);
}
