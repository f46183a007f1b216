// Viewer debug view "points": a round yellow dot with a dark rim per point (see points.vert).
layout(location = 0) out vec4 o_color;
void main() {
    const float r = length(gl_PointCoord - 0.5) * 2.0;
    if (r > 1.0) discard;
    o_color = vec4(r > 0.6 ? vec3(0.1) : vec3(1.0, 0.85, 0.1), 1.0);
}
