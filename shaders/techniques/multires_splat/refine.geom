// One iterative refinement pass of multiresolution splatting as the thesis runs it (Nichols 2010
// §3.2.3, Fig. 3.3; refinePass=geometry): a geometry shader over the previous pass's list, captured by
// transform feedback. The decision is refine.glsl's (shared with refine.comp).
// Four geometry-shader invocations per subsplat, each emitting at most one point (invocation i the
// i-th child), which keeps every emission independent (deviation: on llvmpipe multi-vertex output
// captured by transform feedback lost primitives, MultiresSplatTechnique.cpp).
// Inputs: refine.glsl's. Output: g_subsplat (transform feedback).
#include "techniques/multires_splat/refine.glsl"
layout(points, invocations = 4) in;
layout(points, max_vertices = 1) out;
flat in ivec4 v_subsplat[];
flat out ivec4 g_subsplat;

void emit(ivec4 subsplat) {
    g_subsplat = subsplat;
    gl_Position = vec4(0.0);
    EmitVertex();
}

void main() {
    ivec4 s = v_subsplat[0];
    int keep = refineStep(s);
    if ((keep & kKeepSelf) != 0) {
        if (gl_InvocationID == 0) emit(s);
    } else if ((keep & (1 << gl_InvocationID)) != 0) {
        emit(refineChild(s, gl_InvocationID));
    }
}
