// RSM splatting (Dachsbacher & Stamminger 2005; the baselines of Nichols 2010 §4.3, Fig. 4.8): one
// instance per VPL of the cache. u_radius = 0: a full-screen splat (every pixel, as the gather);
// otherwise the screen rectangle bounding the sphere of radius u_radius around the VPL ("reduced
// overdraw"), or full screen when the sphere reaches behind the near plane.
// Host uniforms: u_radius (m). Inputs: Vpl[] (BINDING_SSBO_TECH0), u_frame.
// Outputs: clip-space quad corners, the VPL index (flat).
#include "common/frame.glsl"
#include "techniques/nichols/vpl.glsl"
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { Vpl u_vpls[]; };
uniform float u_radius;
uniform int u_vplFirst;  // instance i splats VPL u_vplFirst + i (one VPL window per draw)
flat out int v_vpl;

void main() {
    const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    v_vpl = u_vplFirst + gl_InstanceID;
    Vpl v = u_vpls[v_vpl];
    vec2 lo = vec2(-1.0), hi = vec2(1.0);
    if (v.position.w < 0.5) {
        lo = hi = vec2(2.0);  // degenerate quad outside the viewport: nothing to splat
    } else if (u_radius > 0.0) {
        vec2 bmin = vec2(1e30), bmax = vec2(-1e30);
        bool behind = false;
        for (int i = 0; i < 8; ++i) {
            vec3 corner = v.position.xyz + u_radius * vec3((i & 1) == 0 ? -1.0 : 1.0, (i & 2) == 0 ? -1.0 : 1.0, (i & 4) == 0 ? -1.0 : 1.0);
            vec4 c = u_frame.clipFromWorld * vec4(corner, 1.0);
            if (c.w <= 1e-6) behind = true;
            vec2 ndc = c.xy / max(c.w, 1e-6);
            bmin = min(bmin, ndc);
            bmax = max(bmax, ndc);
        }
        if (!behind) {
            lo = clamp(bmin, vec2(-1.0), vec2(1.0));
            hi = clamp(bmax, vec2(-1.0), vec2(1.0));
        }
    }
    gl_Position = vec4(mix(lo, hi, corners[gl_VertexID]), 0.0, 1.0);
}
