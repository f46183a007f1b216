// One iterative refinement pass of multiresolution splatting (Nichols 2010 §3.2.3, Fig. 3.3).
// Mode B (shared list): a subsplat whose cell must be refined (a depth or normal discontinuity in the
// cell or a diagonal neighbour, or in a descendant: the eye pyramid's refine flag) emits its four
// children one level finer (TL, TR, BR, BL; children outside the level or over uncovered pixels are
// dropped); any other subsplat passes through.
// Mode A (u_perVpl, §3.2.3.1: one list per VPL, the VPL index in the subsplat's w): additionally the
// glossy light toward that VPL is evaluated at the four children (quadrant points) and the subsplat
// splits if SamplesDiffer: any of r, g, b of max - min over the covered children exceeds
// u_lobeThreshold. Glossy light = GGX specular part of common/brdf.glsl times Eq. 3.2's irradiance
// (the thesis's Phong lobe replaced by bounce's GGX lobe; docs/techniques/multires-splat.md).
// Host uniforms: u_perVpl, u_lobeThreshold (W/(m^2 sr)), u_minDistance2 (m^2).
// Inputs: eye pyramid geometry, refine, normal (BINDING_TEX_TECH0..2), G-buffer (material), Vpl[]
// (BINDING_SSBO_TECH0), u_frame (eye position). Output: g_subsplat (transform feedback).
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "common/brdf.glsl"
#include "techniques/nichols/vpl.glsl"
layout(points, invocations = 4) in;
layout(points, max_vertices = 1) out;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_refine;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_normal;
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { Vpl u_vpls[]; };
uniform bool u_perVpl;
uniform float u_lobeThreshold;
uniform float u_minDistance2;
flat in ivec4 v_subsplat[];
flat out ivec4 g_subsplat;

const ivec2 kOrder[4] = ivec2[4](ivec2(0, 1), ivec2(1, 1), ivec2(1, 0), ivec2(0, 0));

bool covered(int level, ivec2 cell) {
    ivec2 size = textureSize(s_geometry, level).xy;
    return all(lessThan(cell, size)) && texelFetch(s_geometry, ivec3(cell, 0), level).w > 0.0;
}

void emit(ivec4 subsplat) {
    g_subsplat = subsplat;
    gl_Position = vec4(0.0);
    EmitVertex();
}

// Glossy (specular-only) radiance toward the eye at a covered cell from VPL v, W/(m^2 sr); the
// material is the G-buffer's at the cell's central pixel (the pyramid stores no material).
vec3 glossyRadiance(int level, ivec2 cell, Vpl v) {
    int side = 1 << level;
    ivec2 pixel = min(cell * side + side / 2, ivec2(u_frame.viewport.xy) - 1);
    Surface s = readSurface(pixel);
    vec3 f0 = mix(vec3(s.specularF0), s.albedo, s.metallic);
    if (!s.covered || max(f0.r, max(f0.g, f0.b)) <= 0.0) return vec3(0.0);
    vec4 g = texelFetch(s_geometry, ivec3(cell, 0), level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, ivec3(cell, 0), level).xyz + vec3(0.0, 0.0, 1e-12));
    vec3 l = normalize(v.position.xyz - x);
    vec3 e = normalize(u_frame.eyePosition.xyz - x);
    float nDotL = dot(n, l);
    if (nDotL <= 0.0 || dot(n, e) <= 0.0) return vec3(0.0);
    // brdfCos minus its Lambert part: the lobe only.
    vec3 specularCos = max(brdfCos(n, l, e, s.albedo, s.roughness, s.metallic, s.specularF0) -
                               (1.0 - s.metallic) * s.albedo * kInvPi * nDotL, vec3(0.0));
    return specularCos / nDotL * vplIrradiance(v, x, n, false, u_minDistance2);
}

bool glossyLightVaries(int level, ivec2 cell, int vpl) {
    Vpl v = u_vpls[vpl];
    if (v.position.w < 0.5) return false;
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    int samples = 0;
    for (int i = 0; i < 4; ++i) {
        ivec2 child = 2 * cell + kOrder[i];
        if (!covered(level - 1, child)) continue;
        vec3 radiance = glossyRadiance(level - 1, child, v);
        lo = min(lo, radiance);
        hi = max(hi, radiance);
        ++samples;
    }
    return samples > 1 && any(greaterThan(hi - lo, vec3(u_lobeThreshold)));
}

// Four geometry-shader invocations per subsplat, each emitting at most one point (invocation i the
// i-th child: TL, TR, BR, BL with GL's bottom-up rows), which keeps every emission independent.
void main() {
    ivec4 s = v_subsplat[0];
    int level = s.x;
    ivec2 cell = s.yz;
    bool split = level > 0 && texelFetch(s_refine, ivec3(cell, 0), level).r > 0.5;
    if (!split && u_perVpl && level > 0) split = glossyLightVaries(level, cell, s.w);
    if (split) {
        ivec2 child = 2 * cell + kOrder[gl_InvocationID];
        if (covered(level - 1, child)) emit(ivec4(level - 1, child, s.w));
    } else if (gl_InvocationID == 0 && covered(level, cell)) {
        emit(s);
    }
}
