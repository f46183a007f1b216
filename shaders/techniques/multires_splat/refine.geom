// One iterative refinement pass of multiresolution splatting (Nichols 2010 §3.2.3, Fig. 3.3, mode B):
// a subsplat whose cell must be refined (a depth or normal discontinuity in the cell or a diagonal
// neighbour, or in a descendant: the eye pyramid's refine flag) emits its four children one level
// finer (TL, TR, BR, BL; children outside the level or over uncovered pixels are dropped); any other
// subsplat passes through. Output is captured by transform feedback into the next list.
// Inputs: eye pyramid geometry and refine (BINDING_TEX_TECH0, TECH1). Output: g_subsplat (feedback).
layout(points, invocations = 4) in;
layout(points, max_vertices = 1) out;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_refine;
flat in ivec4 v_subsplat[];
flat out ivec4 g_subsplat;

bool covered(int level, ivec2 cell) {
    ivec2 size = textureSize(s_geometry, level).xy;
    return all(lessThan(cell, size)) && texelFetch(s_geometry, ivec3(cell, 0), level).w > 0.0;
}

void emit(ivec4 subsplat) {
    g_subsplat = subsplat;
    gl_Position = vec4(0.0);
    EmitVertex();
}

// Four geometry-shader invocations per subsplat, each emitting at most one point (invocation i the
// i-th child: TL, TR, BR, BL with GL's bottom-up rows), which keeps every emission independent.
void main() {
    ivec4 s = v_subsplat[0];
    int level = s.x;
    ivec2 cell = s.yz;
    if (level > 0 && texelFetch(s_refine, ivec3(cell, 0), level).r > 0.5) {
        const ivec2 order[4] = ivec2[4](ivec2(0, 1), ivec2(1, 1), ivec2(1, 0), ivec2(0, 0));
        ivec2 child = 2 * cell + order[gl_InvocationID];
        if (covered(level - 1, child)) emit(ivec4(level - 1, child, 0));
    } else if (gl_InvocationID == 0 && covered(level, cell)) {
        emit(s);
    }
}
