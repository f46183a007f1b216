// Subsplat splatting (Nichols 2010 §3.2.4): every subsplat of the shared list is drawn as a GL point
// once per VPL (instance; mode A: each subsplat once, its VPL in w), at its texel of the flattened
// multiresolution buffer.
// Host uniforms: u_origins[level] (atlas texel of each level's origin), u_atlasSize, u_perVpl.
// Inputs: attribute 0 = ivec4 (level, x, y, VPL in mode A), gl_InstanceID = VPL index (mode B). Outputs: point, level, cell, VPL.
layout(location = 0) in ivec4 a_subsplat;
uniform ivec2 u_origins[16];
uniform ivec2 u_atlasSize;
uniform bool u_perVpl;
flat out ivec4 v_subsplat;
flat out int v_vpl;
void main() {
    v_subsplat = a_subsplat;
    v_vpl = u_perVpl ? a_subsplat.w : gl_InstanceID;
    vec2 texel = vec2(u_origins[a_subsplat.x] + a_subsplat.yz) + 0.5;
    gl_Position = vec4(texel / vec2(u_atlasSize) * 2.0 - 1.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
