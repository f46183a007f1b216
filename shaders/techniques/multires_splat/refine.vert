// Subsplat refinement input (Nichols 2010 §3.2.3): one point per subsplat (level, x, y).
// Inputs: attribute 0 = ivec4 (level, x, y, 0). Output: the subsplat to the geometry stage.
layout(location = 0) in ivec4 a_subsplat;
flat out ivec4 v_subsplat;
void main() {
    v_subsplat = a_subsplat;
    gl_Position = vec4(0.0);
}
