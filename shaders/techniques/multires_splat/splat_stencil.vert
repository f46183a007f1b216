// splatPrimitive=stencil, second pass (Nichols 2010 §4.2.1.1: "every multiresolution 'splat' can be
// accomplished by drawing a single full-screen quad with stenciling enabled"): instance i is VPL
// u_vplFirst + i, drawn as one full-screen triangle over a level's rectangle of the atlas; the stencil
// that mark.frag wrote keeps exactly the list's subsplats (common/fullscreen.vert's triangle).
uniform uint u_vplFirst;
flat out uint v_vpl;
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    v_vpl = u_vplFirst + uint(gl_InstanceID);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
