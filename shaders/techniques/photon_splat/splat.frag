// Photon splatting (seed 004, §3.3/§4.3, Figs. 4 and 6): a G-buffer pixel inside bundle k's volume
// (BundleGpu) is tested against the bundle's orthographic depth map and shaded with the Lambert splat
// S = max(0, -w.N) C A weighted by the box, tent or Gaussian filter of its offset from the bundle's
// axis. The depth test is the document's "tolerant" one, made exact for planar receivers: the stored
// depth is compared with the depth the receiver's own plane has at the texel's centre (where the
// map sampled it), less u_tolerance. Occluded pixels add the weight but no colour, so the shadow
// survives the normalisation. Output 0 (blended ONE, ONE):
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
layout(binding = BINDING_TEX_TECH0) uniform sampler2D s_maps;  // depth atlas: [0, 1] over [zNear, zFar]
uniform int u_first;        // bundle of tile 0 of s_maps
uniform ivec2 u_tiles;      // tiles per row, rows
uniform int u_resolution;   // texels per tile side
uniform int u_filter;       // SPLAT_FILTER_*
uniform int u_estimate;     // SPLAT_ESTIMATE_*
uniform float u_tolerance;  // metres
flat in int v_bundle;
layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_stats;

// Smallest |w.N| the receiver-plane depth is solved with (a receiver seen edge-on has cosine ~0).
const float kMinReceiverCosine = 1e-3;

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
    float h = b.origin.w;
    vec3 w = b.direction.xyz;
    vec3 d = s.position - b.origin.xyz;
    vec2 st = vec2(dot(d, b.right.xyz), dot(d, b.up.xyz)) / h;
    if (abs(st.x) > 1.0 || abs(st.y) > 1.0) discard;
    float m = dot(s.position, b.nearPlane.xyz);
    if (m > b.nearPlane.w || m < b.nearPlane.w + b.direction.w * dot(w, b.nearPlane.xyz)) discard;
    if (b.emitter.w > -1e29 && dot(s.position, b.emitter.xyz) < b.emitter.w) discard;
    float ix, iy;
    float weight = kernel1(st.x, ix) * kernel1(st.y, iy);
    if (weight <= 0.0) discard;
    // The map's texel under the receiver, and the receiver plane's depth at that texel's centre.
    ivec2 texel = clamp(ivec2(floor((0.5 * st + 0.5) * float(u_resolution))), ivec2(0), ivec2(u_resolution - 1));
    int tile = v_bundle - u_first;
    ivec2 atlas = ivec2(tile % u_tiles.x, tile / u_tiles.x) * u_resolution + texel;
    float zNear = b.right.w, zFar = b.up.w;
    float stored = zNear + texelFetch(s_maps, atlas, 0).r * (zFar - zNear);
    vec2 offset = ((vec2(texel) + 0.5) / float(u_resolution) * 2.0 - 1.0 - st) * h;  // metres, to the texel's centre
    float nw = dot(s.normal, w);
    nw = nw < 0.0 ? min(nw, -kMinReceiverCosine) : max(nw, kMinReceiverCosine);
    float planeDepth = dot(d, w) - (dot(s.normal, b.right.xyz) * offset.x + dot(s.normal, b.up.xyz) * offset.y) / nw;
    float lit = stored >= planeDepth - u_tolerance ? 1.0 : 0.0;
    float cosine = max(0.0, -dot(w, s.normal));
    vec3 albedo = (1.0 - s.metallic) * s.albedo;
    vec3 colour;
    if (u_estimate == SPLAT_ESTIMATE_FLUX) {
        float wn = weight / (ix * iy * h * h);  // per m^2 of cross-section
        colour = albedo * kInvPi * b.power.rgb * wn * cosine * lit;
    } else {
        vec3 c = b.power.rgb / (kPi * 4.0 * h * h);
        colour = weight * cosine * c * albedo * lit;
    }
    o_accum = vec4(colour, weight);
    o_stats = vec4(1.0, weight, 0.0, 0.0);
}
