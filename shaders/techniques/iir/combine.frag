// Combine (Laine et al. 2007 §5.1): the inverse of the split; image pixel (a*n + i, b*m + j) reads
// atlas pixel (i*tileW + a, j*tileH + b). Inputs: tile irradiance atlas (INPUT0), u_tiles,
// u_tileSize. Output: irradiance W/m^2 at full size.
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_tileIrradiance;
uniform ivec2 u_tiles;
uniform ivec2 u_tileSize;
layout(location = 0) out vec4 o_irradiance;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 residue = pixel % u_tiles;
    ivec2 inTile = pixel / u_tiles;
    o_irradiance = texelFetch(s_tileIrradiance, residue * u_tileSize + inTile, 0);
}
