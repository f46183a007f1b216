// Viewer debug views "points" (techniques/Technique.h DebugEncoding::Points, ClusterPoints): one point
// per texel of mip level u_level of a 2D-array texture, projected with the viewer's camera over the
// image. Points: texels are world positions (xyz, w > 0 where valid; the VPL cache of nichols/RegularVpls,
// photon-splat's bundles). ClusterPoints (u_mean = 1): texels are sums of positions with their count in
// w (a min-max pyramid level, hisr's VPL tree), drawn at the mean xyz / w. Inputs: s_points
// (BINDING_TEX_INPUT1), u_gridSize (texels per layer at u_level), u_clipFromWorld, u_pointSize (pixels).
// Invalid texels are moved outside the clip volume.
layout(binding = BINDING_TEX_INPUT1) uniform sampler2DArray s_points;
uniform ivec2 u_gridSize;
uniform int u_level;
uniform int u_mean;
uniform mat4 u_clipFromWorld;
uniform float u_pointSize;
void main() {
    const int perLayer = u_gridSize.x * u_gridSize.y;
    const int layer = gl_VertexID / perLayer, i = gl_VertexID % perLayer;
    vec4 p = texelFetch(s_points, ivec3(i % u_gridSize.x, i / u_gridSize.x, layer), u_level);
    if (u_mean != 0 && p.w > 0.0) p.xyz /= p.w;
    gl_Position = p.w > 0.0 ? u_clipFromWorld * vec4(p.xyz, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
    gl_PointSize = u_pointSize;
}
