// The light of one VPL at one subsplat of multiresolution splatting (Nichols 2010 §3.2.3.1, §3.2.4),
// shared by the refinement test (refine.geom) and the splat (splat.frag) so that mode A refines on
// exactly the quantity it splats.
// A subsplat's patch is the mean position and normal of its covered pixels (eye pyramid); its
// material is the G-buffer's at the cell's central pixel (the pyramid stores no material).
// With the indirect-resolution cap, a base cell covers u_gbufferScale^2 G-buffer pixels.
// Form factor (host uniform u_diskForm, setting formFactor): Eq. 4.1's disk-to-point form factor
// Phi <N_l,-l> <N_s,l> / (pi r^2 + A_l) with A_l the VPL's patch area (bounce's default, as the `rsm`
// gather this technique approximates, so full refinement gives that gather's image), or Eq. 3.2's point
// form factor with the r^2 clamp, Phi <..> <..> / (pi max(r^2, r_min^2)) (the thesis's ch. 3).
// Host uniforms: u_minDistance2 (m^2), u_diskForm, u_gbufferScale. Inputs: eye pyramid geometry (BINDING_TEX_TECH0) and normal
// (BINDING_TEX_TECH2), G-buffer, Vpl[] (BINDING_SSBO_TECH0), u_frame (eye position).
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "techniques/rsm/glossy.glsl"
#include "techniques/nichols/vpl.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_normal;
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { Vpl u_vpls[]; };
uniform float u_minDistance2;
uniform bool u_diskForm;
uniform int u_gbufferScale;  // G-buffer pixels per base cell side (setting indirectSize; 1 = full size)

struct Patch {
    vec3 position;
    vec3 normal;
    Surface material;  // central pixel; material.covered is false if that pixel is uncovered
};

// The patch's position and normal only (mode B's splats, which need no material).
Patch subsplatGeometry(int level, ivec2 cell) {
    vec4 g = texelFetch(s_geometry, ivec3(cell, 0), level);
    Patch p;
    p.position = g.xyz / max(g.w, 1.0);
    p.normal = normalize(texelFetch(s_normal, ivec3(cell, 0), level).xyz + vec3(0.0, 0.0, 1e-12));
    p.material.covered = false;
    return p;
}

Patch subsplatPatch(int level, ivec2 cell) {
    int side = (1 << level) * u_gbufferScale;
    ivec2 pixel = min(cell * side + side / 2, ivec2(u_frame.viewport.xy) - 1);
    Patch p = subsplatGeometry(level, cell);
    p.material = readSurface(pixel);
    return p;
}

// The denominator D of the form factor in use: E = Phi <N_l,-l> <N_s,l> / D (vpl.glsl vplIrradiance).
float formFactorDenominator(Vpl v, float r2) {
    return u_diskForm ? kPi * r2 + v.normal.w : kPi * max(r2, u_minDistance2);
}

vec3 patchIrradiance(Patch p, Vpl v) {
    return v.position.w > 0.5 ? vplIrradiance(v, p.position, p.normal, u_diskForm, u_minDistance2) : vec3(0.0);
}

// Glossy radiance toward the eye reflected at the patch from VPL v: f_spec(l, e) * E, W/(m^2 sr);
// zero where the central pixel is uncovered or Lambertian.
vec3 patchGlossyRadiance(Patch p, Vpl v, vec3 irradiance) {
    if (!p.material.covered) return vec3(0.0);
    vec3 l = normalize(v.position.xyz - p.position);
    vec3 e = normalize(u_frame.eyePosition.xyz - p.position);
    Surface m = p.material;
    return glossyBrdf(p.normal, l, e, m.albedo, m.roughness, m.metallic, m.specularF0) * irradiance;
}
