// Regular VPL extraction (Nichols 2010 §3.2.1: "the same fixed grid of RSM sampling locations"):
// the RSM is cut into grid^2 blocks per layer; each block becomes one VPL at the block's centre texel
// (or, if that texel saw nothing, the first covered texel in scan order), carrying the summed flux and
// area of the whole block, so the VPL set reflects exactly the power of the RSM.
// Host uniforms: u_grid (VPLs per side), u_block (texels per block side).
// Inputs: RSM position/normal/flux arrays (BINDING_TEX_TECH0..2). Outputs: Vpl[] (BINDING_SSBO_TECH0)
// and the same records as grid^2 x layers images (BINDING_IMG0..2: position, normal, flux).
#include "techniques/nichols/vpl.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_rsmPosition;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_rsmNormal;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_rsmFlux;
layout(std430, binding = BINDING_SSBO_TECH0) writeonly buffer VplBlock { Vpl u_vpls[]; };
layout(rgba32f, binding = BINDING_IMG0) writeonly uniform image2DArray i_position;
layout(rgba32f, binding = BINDING_IMG1) writeonly uniform image2DArray i_normal;
layout(rgba32f, binding = BINDING_IMG2) writeonly uniform image2DArray i_flux;
uniform int u_grid;
uniform int u_block;

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID.xy, gl_GlobalInvocationID.z);
    if (cell.x >= u_grid || cell.y >= u_grid) return;
    ivec2 origin = cell.xy * u_block;
    ivec3 rep = ivec3(origin + ivec2(u_block / 2), cell.z);
    bool found = texelFetch(s_rsmFlux, rep, 0).a > 0.5;
    vec3 flux = vec3(0.0);
    float area = 0.0;
    for (int y = 0; y < u_block; ++y)
        for (int x = 0; x < u_block; ++x) {
            ivec3 t = ivec3(origin + ivec2(x, y), cell.z);
            vec4 f = texelFetch(s_rsmFlux, t, 0);
            if (f.a < 0.5) continue;
            flux += f.rgb;
            area += texelFetch(s_rsmNormal, t, 0).w;
            if (!found) {
                rep = t;
                found = true;
            }
        }
    Vpl v;
    v.position = vec4(texelFetch(s_rsmPosition, rep, 0).xyz, found && any(greaterThan(flux, vec3(0.0))) ? 1.0 : 0.0);
    v.normal = vec4(texelFetch(s_rsmNormal, rep, 0).xyz, area);
    v.flux = vec4(flux, float(u_block * u_block));
    u_vpls[(cell.z * u_grid + cell.y) * u_grid + cell.x] = v;
    imageStore(i_position, cell, v.position);
    imageStore(i_normal, cell, v.normal);
    imageStore(i_flux, cell, v.flux);
}
