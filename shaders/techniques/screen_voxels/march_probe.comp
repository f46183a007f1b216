// Probe of the voxel march (Nichols 2010 §5.3.3.1, march.glsl) for tests: evaluates voxelMarch (or,
// with u_trace, voxelTrace) on a list of world-space segments against the grid ScreenVoxels::build made, so the march can be checked
// segment by segment without a technique around it (tests/gpu/ScreenVoxelsGpuTest.cpp).
// Host uniforms: u_count (segments), u_trace. Inputs: grid (march.glsl), segments (BINDING_SSBO_TECH0: two vec4
// per segment, a.xyz with steps in a.w, b.xyz with thickness in b.w). Outputs: the march's fraction per
// segment (BINDING_SSBO_TECH1).
layout(local_size_x = 64) in;
#include "techniques/screen_voxels/march.glsl"
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer SegmentBlock { vec4 u_segments[]; };
layout(std430, binding = BINDING_SSBO_TECH1) writeonly buffer ResultBlock { float u_fractions[]; };
uniform int u_count;
uniform bool u_trace;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count) return;
    vec4 a = u_segments[2 * i], b = u_segments[2 * i + 1];
    u_fractions[i] = u_trace ? voxelTrace(a.xyz, b.xyz, int(b.w), false) : voxelMarch(a.xyz, b.xyz, int(a.w), int(b.w));
}
