// Photon splatting (seed 004, §3.3/§4.3): one screen-space rectangle per bundle, the projected
// bounding rectangle of the bundle's box (the "light volume" the document suggests to limit the
// fragments of its full-screen pass per splat). A box with a corner behind the camera covers the
// whole screen. Instanced: gl_InstanceID + u_first is the bundle, 6 vertices per rectangle.
#include "common/frame.glsl"
#include "techniques/photon_splat/splat_shared.h"

layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer Bundles { BundleGpu b_bundles[]; };
uniform int u_first;
flat out int v_bundle;

void main() {
    int k = u_first + gl_InstanceID;
    BundleGpu b = b_bundles[k];
    float h = b.origin.w, depth = b.direction.w, back = b.right.w;
    vec2 lo = vec2(1e9), hi = vec2(-1e9);
    bool behind = false;
    for (int c = 0; c < 8; ++c) {
        vec3 local = vec3((c & 1) != 0 ? h : -h, (c & 2) != 0 ? h : -h, (c & 4) != 0 ? depth : -back);
        vec3 p = b.origin.xyz + local.x * b.right.xyz + local.y * b.up.xyz + local.z * b.direction.xyz;
        vec4 clip = u_frame.clipFromWorld * vec4(p, 1.0);
        if (clip.w <= 1e-6) { behind = true; break; }
        vec2 ndc = clip.xy / clip.w;
        lo = min(lo, ndc);
        hi = max(hi, ndc);
    }
    if (behind) { lo = vec2(-1.0); hi = vec2(1.0); }
    lo = clamp(lo, vec2(-1.0), vec2(1.0));
    hi = clamp(hi, vec2(-1.0), vec2(1.0));
    const ivec2 corners[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
    ivec2 q = corners[gl_VertexID % 6];
    gl_Position = vec4(q.x == 0 ? lo.x : hi.x, q.y == 0 ? lo.y : hi.y, 0.0, 1.0);
    v_bundle = k;
}
