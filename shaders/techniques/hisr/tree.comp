// The VPL tree of hierarchical image-space radiosity (Nichols 2010 §4.2.4: "we reorganize the full
// resolution RSM data into a VPL tree ... clustering VPLs representing coarser mipmap levels", similar to
// the layout of Haar wavelet coefficients), built each frame from the light-space min-max pyramid
// (techniques/nichols/MinMaxPyramid). One record of four vec4 per node, levels one after another from
// the RSM (level 0) to the roots, each level's nodes per layer in Morton (Z) order: node m's children at
// the next finer level are 4m .. 4m + 3 and its parent is m / 4, so a depth-first walk touches
// neighbouring records (the thesis's cache coherence) and needs no 2D index arithmetic.
// Record: [0] the node's mean position xyz and max light distance ||V_j|| (w < 0: empty node); [1..3]
// the node's VPL (vpl.glsl's patchVpl: position, normal + area, flux + texels).
// Host uniforms: u_level, u_levelOffset (records before this level), u_side (the level's side).
// Inputs: light pyramid geometry/normal/normalMax/flux (BINDING_TEX_INPUT0..3). Output: BINDING_SSBO_TECH1.
#include "techniques/nichols/vpl.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_INPUT0) uniform sampler2DArray s_lightGeometry;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2DArray s_lightNormal;
layout(binding = BINDING_TEX_INPUT2) uniform sampler2DArray s_lightNormalMax;
layout(binding = BINDING_TEX_INPUT3) uniform sampler2DArray s_lightFlux;
layout(std430, binding = BINDING_SSBO_TECH1) writeonly buffer TreeBlock { vec4 u_tree[]; };
uniform int u_level;
uniform int u_levelOffset;
uniform int u_side;

// Interleaves the bits of x (even) and y (odd): the Morton index of a cell of a 2^k x 2^k level.
uint morton(uvec2 p) {
    uvec2 v = p & 0xFFFFu;
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    v = (v | (v << 1)) & 0x55555555u;
    return v.x | (v.y << 1);
}

void main() {
    ivec3 node = ivec3(gl_GlobalInvocationID.xy, gl_GlobalInvocationID.z);
    if (node.x >= u_side || node.y >= u_side) return;
    int index = (u_levelOffset + node.z * u_side * u_side + int(morton(uvec2(node.xy)))) * 4;
    vec4 g = texelFetch(s_lightGeometry, node, u_level);
    if (g.w <= 0.0) {
        u_tree[index] = vec4(0.0, 0.0, 0.0, -1.0);
        u_tree[index + 1] = vec4(0.0);
        u_tree[index + 2] = vec4(0.0);
        u_tree[index + 3] = vec4(0.0);
        return;
    }
    Vpl v = patchVpl(s_lightGeometry, s_lightNormal, node, u_level, g, texelFetch(s_lightFlux, node, u_level));
    u_tree[index] = vec4(g.xyz / g.w, texelFetch(s_lightNormalMax, node, u_level).w);
    u_tree[index + 1] = v.position;
    u_tree[index + 2] = v.normal;
    u_tree[index + 3] = v.flux;
}
