// Subsplat splatting as quads (Nichols 2010 §3.4.1: points against quads, R5 "points vs quads ~ +5 %"):
// splatPrimitive=quads expands each point of splat.vert into a one-texel quad (two triangles) covering
// the same atlas texel, so the fragments, and the image, are the same; only the primitive differs.
// Host uniforms: u_atlasSize (shared with splat.vert). Inputs and outputs: splat.vert's flats.
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
uniform ivec2 u_atlasSize;
flat in ivec4 v_subsplat[];
flat in int v_vpl[];
flat in float v_visibility[];
flat out ivec4 g_subsplat;
flat out int g_vpl;
flat out float g_visibility;
void main() {
    vec2 half_ = 1.0 / vec2(u_atlasSize);  // half a texel in NDC (a texel spans 2 / size)
    vec4 c = gl_in[0].gl_Position;
    for (int i = 0; i < 4; ++i) {
        g_subsplat = v_subsplat[0];
        g_vpl = v_vpl[0];
        g_visibility = v_visibility[0];
        gl_Position = vec4(c.xy + half_ * vec2((i & 1) == 0 ? -1.0 : 1.0, (i & 2) == 0 ? -1.0 : 1.0), c.zw);
        EmitVertex();
    }
    EndPrimitive();
}
