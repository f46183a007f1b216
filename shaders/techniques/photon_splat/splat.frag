// Photon splatting (seed 004, §3.3/§4.3, Figs. 4 and 6): a G-buffer pixel inside bundle k's box is
// tested against the bundle's orthographic depth map (tolerant depth test: lit when its depth along
// w is at most the stored depth plus u_tolerance; in front of the near plane it is lit) and shaded
// with the Lambert splat S = max(0, -w.N) C A weighted by the box, tent or Gaussian filter of its
// offset from the frustum axis. Occluded pixels add the weight but no colour, so the shadow survives
// the normalisation. Output 0 (blended ONE, ONE):
//   SPLAT_ESTIMATE_NORMALIZED: (w S V, w) with C = Phi / (pi (2h)^2) and w the filter (peak 1);
//   SPLAT_ESTIMATE_FLUX: (rho / pi Phi w_n max(0, -w.N) V, w) with w_n the filter normalised to a
//     unit integral over the cross-section: a beam of flux Phi spread by w_n gives irradiance
//     Phi w_n cos on a receiver, so the sum over cosine-distributed photons estimates the one-bounce
//     irradiance (docs/techniques/photon-splat.md).
// Output 1: (1 per covering bundle, w, 0, 0) for the overlap view.
#include "common/constants.glsl"
#include "common/gbuffer.glsl"
#include "techniques/photon_splat/splat_shared.h"

layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer Bundles { BundleGpu b_bundles[]; };
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_maps;  // depth in [0, 1] over [0, D]
uniform int u_first;        // bundle of layer 0 of s_maps
uniform int u_filter;       // SPLAT_FILTER_*
uniform int u_estimate;     // SPLAT_ESTIMATE_*
uniform float u_tolerance;  // metres
flat in int v_bundle;
layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_stats;

// Filter of the offset t in [-1, 1] (in half sizes) along one axis, peak 1, and its integral over
// [-1, 1] (for the normalised kernel). Gaussian: sigma = h / 2 (not given by the document).
float kernel1(float t, out float integral) {
    float a = abs(t);
    if (u_filter == SPLAT_FILTER_BOX) { integral = 2.0; return 1.0; }
    if (u_filter == SPLAT_FILTER_TENT) { integral = 1.0; return 1.0 - a; }
    const float sigma = 0.5;
    integral = sigma * 2.5066282746 * 0.9544997361;  // sigma sqrt(2 pi) erf(1 / (sigma sqrt 2))
    return exp(-0.5 * t * t / (sigma * sigma));
}

void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    if (!s.covered) discard;
    BundleGpu b = b_bundles[v_bundle];
    float h = b.origin.w, depth = b.direction.w, back = b.right.w;
    vec3 d = s.position - b.origin.xyz;
    vec3 local = vec3(dot(d, b.right.xyz), dot(d, b.up.xyz), dot(d, b.direction.xyz));
    if (abs(local.x) > h || abs(local.y) > h || local.z < -back || local.z > depth) discard;
    float ix, iy;
    float w = kernel1(local.x / h, ix) * kernel1(local.y / h, iy);
    if (w <= 0.0) discard;
    vec3 uvw = vec3(local.xy / h * 0.5 + 0.5, float(v_bundle - u_first));
    float stored = texture(s_maps, uvw).r * depth;
    float lit = (local.z < 0.0 || local.z <= stored + u_tolerance) ? 1.0 : 0.0;
    float cosine = max(0.0, -dot(b.direction.xyz, s.normal));
    vec3 albedo = (1.0 - s.metallic) * s.albedo;
    vec3 colour;
    if (u_estimate == SPLAT_ESTIMATE_FLUX) {
        float wn = w / (ix * iy * h * h);  // per m^2 of cross-section
        colour = albedo * kInvPi * b.power.rgb * wn * cosine * lit;
    } else {
        vec3 c = b.power.rgb / (kPi * 4.0 * h * h);
        colour = w * cosine * c * albedo * lit;
    }
    o_accum = vec4(colour, w);
    o_stats = vec4(1.0, w, 0.0, 0.0);
}
