// One iterative refinement step of multiresolution splatting (Nichols 2010 §3.2.3, Fig. 3.3), shared by
// the thesis's geometry-shader pass (refine.geom, refinePass=geometry) and the compute pass
// (refine.comp, refinePass=compute), so both keep exactly the same subsplats.
// Mode B (shared list): a subsplat whose cell must be refined (a depth, normal or, optionally,
// curvature discontinuity in the cell or a diagonal neighbour, or in a descendant: the eye pyramid's
// refine flag) emits its four children one level finer (TL, TR, BR, BL; children outside the level or
// over uncovered pixels are dropped); any other subsplat passes through.
// Mode A (u_perVpl, §3.2.3.1: one list per VPL, the VPL index in the subsplat's w): additionally the
// light toward that VPL is evaluated at the four children (quadrant points, subsplat.glsl) and the
// subsplat splits if SamplesDiffer, made relative: in any of r, g, b,
//   max_i G_i - min_i G_i > T * max(mean_i L_i, mean_i B_i)
// with G_i the glossy radiance toward the eye (the only part mode B's geometric criterion misses),
// L_i the total (Lambert + glossy) radiance toward the eye from this VPL, and B_i the black floor:
// kBlackFraction of the radiance a white Lambertian patch facing the VPL at that distance reflects,
// Phi / (pi D) with D the form factor's denominator (subsplat.glsl: pi r^2 + A_l, or
// pi max(r^2, r_min^2)). Every term is linear in the VPL's flux, so the test does not depend on the
// light's intensity; B keeps grazing, nearly black regions from refining on noise.
// Host uniforms: u_perVpl, u_relativeThreshold (T, unitless), u_minDistance2 (m^2), u_diskForm, u_levelSize[level]
// (each eye-pyramid level's size: textureSize with a level that differs between SIMD lanes returns the
// first lane's size on llvmpipe, and one pass holds subsplats of several levels).
// Inputs: eye pyramid geometry, refine, normal (BINDING_TEX_TECH0..2), G-buffer (material), Vpl[]
// (BINDING_SSBO_TECH0), u_frame (eye position).
#include "techniques/multires_splat/subsplat.glsl"
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_refine;
uniform bool u_perVpl;
uniform float u_relativeThreshold;
uniform ivec2 u_levelSize[16];

// Bounce's choice (the thesis's T is absolute and unstated): a VPL's light below 0.1 % of what a white
// patch facing it would reflect counts as black.
const float kBlackFraction = 1e-3;

// Children in emission order: TL, TR, BR, BL with GL's bottom-up rows.
const ivec2 kOrder[4] = ivec2[4](ivec2(0, 1), ivec2(1, 1), ivec2(1, 0), ivec2(0, 0));

bool covered(int level, ivec2 cell) {
    return all(lessThan(cell, u_levelSize[level])) && texelFetch(s_geometry, ivec3(cell, 0), level).w > 0.0;
}

bool glossyLightVaries(int level, ivec2 cell, int vpl) {
    Vpl v = u_vpls[vpl];
    if (v.position.w < 0.5) return false;
    vec3 lo = vec3(1e30), hi = vec3(-1e30), total = vec3(0.0), black = vec3(0.0);
    int samples = 0;
    for (int i = 0; i < 4; ++i) {
        ivec2 child = 2 * cell + kOrder[i];
        if (!covered(level - 1, child)) continue;
        Patch p = subsplatPatch(level - 1, child);
        vec3 irradiance = patchIrradiance(p, v);
        vec3 glossy = patchGlossyRadiance(p, v, irradiance);
        lo = min(lo, glossy);
        hi = max(hi, glossy);
        total += glossy + (p.material.covered ? (1.0 - p.material.metallic) * p.material.albedo * kInvPi : vec3(0.0)) * irradiance;
        vec3 d = v.position.xyz - p.position;
        black += kBlackFraction * v.flux.rgb / (kPi * formFactorDenominator(v, dot(d, d)));
        ++samples;
    }
    if (samples < 2) return false;
    vec3 scale = max(total, black) / float(samples);
    return any(greaterThan(hi - lo, u_relativeThreshold * scale));
}

// What subsplat s becomes one pass later: bit i (0..3) set = child kOrder[i] is kept; bit 4 set = s
// itself is kept (not split, covered); no bit = dropped.
const int kKeepSelf = 16;
int refineStep(ivec4 s) {
    int level = s.x;
    ivec2 cell = s.yz;
    bool split = level > 0 && texelFetch(s_refine, ivec3(cell, 0), level).r > 0.5;
    if (!split && u_perVpl && level > 0) split = glossyLightVaries(level, cell, s.w);
    if (!split) return covered(level, cell) ? kKeepSelf : 0;
    int keep = 0;
    for (int i = 0; i < 4; ++i)
        if (covered(level - 1, 2 * cell + kOrder[i])) keep |= 1 << i;
    return keep;
}

ivec4 refineChild(ivec4 s, int i) {
    return ivec4(s.x - 1, 2 * s.yz + kOrder[i], s.w);
}
