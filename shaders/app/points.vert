// Viewer debug view "points" (techniques/Technique.h DebugEncoding::Points): one point per texel of a
// 2D-array texture of world positions (xyz, w > 0 where valid; the VPL cache of nichols/RegularVpls),
// projected with the viewer's camera over the image. Inputs: s_points (BINDING_TEX_INPUT1), u_gridSize
// (texels per layer), u_clipFromWorld, u_pointSize (pixels). Invalid texels are moved outside the clip volume.
layout(binding = BINDING_TEX_INPUT1) uniform sampler2DArray s_points;
uniform ivec2 u_gridSize;
uniform mat4 u_clipFromWorld;
uniform float u_pointSize;
void main() {
    const int perLayer = u_gridSize.x * u_gridSize.y;
    const int layer = gl_VertexID / perLayer, i = gl_VertexID % perLayer;
    const vec4 p = texelFetch(s_points, ivec3(i % u_gridSize.x, i / u_gridSize.x, layer), 0);
    gl_Position = p.w > 0.0 ? u_clipFromWorld * vec4(p.xyz, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
    gl_PointSize = u_pointSize;
}
