// Eq. 3.2 for one subsplat and one VPL (Nichols 2010 §3.2.4; formFactor=disk, the default, puts Eq. 4.1's
// pi r^2 + A_l in the denominator instead, subsplat.glsl):
//   E = Phi_l <V_ls, N_l> <V_sl, N_s> / (pi max(|V_ls|^2, r_min^2))
// at the subsplat's patch (mean position and normal of its covered pixels), added into the atlas
// (blend ONE, ONE; alpha counts the VPLs, so alpha > 0 marks a rendered texel for upsampling). The
// Lambert part of the receiver's BRDF is applied per pixel after upsampling (combine.frag).
// Mode A with glossy shading (u_glossy) also writes the glossy radiance f_spec(V_sl, V_eye) * E at the
// patch (common/brdf.glsl's GGX lobe, material of the cell's central pixel) to a second atlas.
// With VPL_VISIBILITY (beyond the thesis) E is multiplied by the pair's visibility v_visibility, which
// splat.vert computes (0 or 1; 1 when visibility is off).
// Host uniforms: u_minDistance2 (m^2), u_diskForm, u_glossy. Inputs: see subsplat.glsl, v_visibility.
// Outputs: location 0 irradiance W/m^2; location 1 (u_glossy) glossy radiance W/(m^2 sr).
#include "techniques/multires_splat/subsplat.glsl"
uniform bool u_glossy;
#ifdef SPLAT_QUADS  // splatPrimitive=quads: the flats come through splat_quad.geom
flat in ivec4 g_subsplat;
flat in int g_vpl;
flat in float g_visibility;
#define v_subsplat g_subsplat
#define v_vpl g_vpl
#define v_visibility g_visibility
#else
flat in ivec4 v_subsplat;
flat in int v_vpl;
flat in float v_visibility;
#endif
layout(location = 0) out vec4 o_irradiance;
layout(location = 1) out vec4 o_glossy;
void main() {
    Patch p = subsplatPatch(v_subsplat.x, v_subsplat.yz);
    Vpl v = u_vpls[v_vpl];
    vec3 e = patchIrradiance(p, v) * v_visibility;
    o_irradiance = vec4(e, 1.0);
    o_glossy = vec4(u_glossy ? patchGlossyRadiance(p, v, e) : vec3(0.0), 1.0);
}
