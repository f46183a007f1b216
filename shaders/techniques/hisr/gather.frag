// hisr's gather as a stencilled draw (Nichols 2010 §4.2.4, gatherPass=stencil): one fragment per
// stencilled atlas texel; the walk is hisr/gather.glsl's. Output: atlas irradiance (alpha 1).
#include "techniques/hisr/gather.glsl"
// The stencil set-up chose which cells of this level rectangle gather; gatherCell's atomics are side
// effects, and without this qualifier GL runs the stencil test after the shader (GL 4.5, "Early
// Per-Fragment Tests"), so every fragment of the rectangle would walk the tree and the stencil would
// only mask its colour (HisrGpuTest.StencilCullsTheGather). Safe: the shader neither discards nor
// writes gl_FragDepth, and the gather's stencil op is KEEP.
layout(early_fragment_tests) in;
layout(location = 0) out vec4 o_irradiance;

void main() {
    uvec2 rays = uvec2(0u);
    vec3 irradiance = gatherCell(ivec2(gl_FragCoord.xy) - u_levelOrigin, u_level, rays);
    countVplRays(rays);
    o_irradiance = vec4(irradiance, 1.0);
}
