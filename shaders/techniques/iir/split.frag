// Interleaved-sampling split (Laine et al. 2007 §5.1, Keller and Heidrich 2001): atlas pixel (a, b)
// of tile (i, j) holds G-buffer pixel (a*n + i, b*m + j). Tiles are ceil(W/n) x ceil(H/m); atlas
// pixels whose source lies outside the image are marked uncovered (w = 0).
// Inputs: G-buffer, u_tiles = (n, m), u_tileSize, u_imageSize. Outputs: position (w: covered), normal.
#include "common/gbuffer.glsl"
uniform ivec2 u_tiles;
uniform ivec2 u_tileSize;
uniform ivec2 u_imageSize;
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
void main() {
    ivec2 atlas = ivec2(gl_FragCoord.xy);
    ivec2 tile = atlas / u_tileSize;
    ivec2 inTile = atlas - tile * u_tileSize;
    ivec2 source = inTile * u_tiles + tile;
    o_position = vec4(0.0);
    o_normal = vec4(0.0);
    if (any(greaterThanEqual(source, u_imageSize))) return;
    Surface s = readSurface(source);
    if (!s.covered) return;
    o_position = vec4(s.position, 1.0);
    o_normal = vec4(s.normal, 0.0);
}
