// Full-resolution RSM gather (the baseline of Nichols 2010 §4.3 / Fig. 4.8; Dachsbacher & Stamminger
// 2005): every pixel sums every VPL of the cache, without visibility.
//   L_indirect = rho_s / pi * sum_j E_j,   E_j = Phi_j <N_j, -l> <N_s, l> / D_j
// with D_j = pi * max(r^2, r_min^2) (Eq. 3.2) or pi * r^2 + A_j (Eq. 4.1, disk-to-point).
// u_glossy (bounce's extension, the limit of multires-splat's mode A): the receiver's full BRDF,
// L_indirect += sum_j f_spec(l_j, e) E_j with f_spec the GGX lobe of common/brdf.glsl
// (rsm/glossy.glsl); the thesis's gather is Lambertian.
// One draw sums the VPLs [u_vplFirst, u_vplEnd) of the cache; the host adds the batches by blending
// (RsmTechnique.cpp). The cache is read through a uniform-block window (nichols/vpl_window.glsl): on
// llvmpipe an SSBO index or a texelFetch per VPL costs more than the VPL's arithmetic (measured in
// docs/techniques/rsm.md).
// VPL_VISIBILITY (host define; bounce's extension beyond the thesis, off by default): each VPL's E_j times the
// voxel-march visibility of the segment from the pixel to the VPL (screen_voxels/vpl_visibility.glsl).
// Host uniforms: u_vplFirst, u_vplEnd, u_windowFirst, u_diskForm, u_minDistance2 (m^2), u_glossy, and
// vpl_visibility.glsl's. Inputs: G-buffer, u_frame, the VPL window (BINDING_UBO_VPL_WINDOW), the voxel grid when visibility is on. Output: indirect radiance
// W/(m^2 sr), RGBA32F; ray counters.
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "techniques/rsm/glossy.glsl"
#include "techniques/nichols/vpl.glsl"
#include "techniques/nichols/vpl_window.glsl"
#include "techniques/screen_voxels/vpl_visibility.glsl"
uniform uint u_vplFirst;     // this draw's VPLs: [u_vplFirst, u_vplEnd)
uniform uint u_vplEnd;
uniform uint u_windowFirst;  // the record u_vplWindow[0] holds (vpl_window.glsl)
uniform bool u_diskForm;
uniform float u_minDistance2;
uniform bool u_glossy;
layout(location = 0) out vec4 o_radiance;

void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    if (!s.covered) {
        o_radiance = vec4(0.0);
        return;
    }
    vec3 e = normalize(u_frame.eyePosition.xyz - s.position);
    vec3 irradiance = vec3(0.0), glossy = vec3(0.0);
    uvec2 rays = uvec2(0u);
    for (uint j = u_vplFirst; j < u_vplEnd; ++j) {
        Vpl v = u_vplWindow[j - u_windowFirst];
        if (v.position.w < 0.5) continue;
        vec3 ej = vplIrradiance(v, s.position, s.normal, u_diskForm, u_minDistance2);
        // Only VPLs that contribute are marched: the test costs up to u_raySteps loop iterations.
        if (kVplVisibility && any(greaterThan(ej, vec3(0.0))))
            ej *= vplVisible(s.position, s.normal, v.position.xyz, v.normal.xyz, rays);
        irradiance += ej;
        if (u_glossy)
            glossy += glossyBrdf(s.normal, normalize(v.position.xyz - s.position), e, s.albedo, s.roughness,
                                 s.metallic, s.specularF0) * ej;
    }
    countVplRays(rays);
    o_radiance = vec4((1.0 - s.metallic) * s.albedo * kInvPi * irradiance + glossy, 1.0);
}
