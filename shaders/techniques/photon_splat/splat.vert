// Photon splatting (seed 004, §3.3/§4.3): the "light volume" the document suggests to limit the
// fragments of its full-screen pass per splat. Each bundle's volume is a parallelepiped (its square
// swept along w from the tilted near plane to the far plane); its 12 triangles are drawn with front
// faces culled, so every pixel whose view ray meets the volume is shaded once, and once when the
// camera is inside it. With u_useRanges (the flux estimate: only first hits receive), the box is cut
// to the depths of the bundle's first hits (tile_range.comp) widened by u_rangeMargin: no receiver
// outside it adds light. Instanced: gl_InstanceID + u_first is the bundle, 36 vertices per volume.
#include "common/frame.glsl"
#include "techniques/photon_splat/splat_shared.h"

layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer Bundles { BundleGpu b_bundles[]; };
layout(std430, binding = BINDING_SSBO_TECH2) readonly buffer Ranges { vec2 r_ranges[]; };
uniform int u_first;
uniform bool u_useRanges;
uniform float u_rangeMargin;  // metres
flat out int v_bundle;

// Corner c: right sign bit 0, up sign bit 1, far bit 2; faces wound counter-clockwise seen from
// outside (right x up = w: the volume has the orientation of the unit cube).
const int kFaces[36] = int[36](0, 4, 6, 0, 6, 2,   // -right
                               1, 3, 7, 1, 7, 5,   // +right
                               0, 1, 5, 0, 5, 4,   // -up
                               2, 6, 7, 2, 7, 3,   // +up
                               0, 2, 3, 0, 3, 1,   // near
                               4, 5, 7, 4, 7, 6);  // far

void main() {
    int k = u_first + gl_InstanceID;
    BundleGpu b = b_bundles[k];
    int c = kFaces[gl_VertexID];
    float h = b.origin.w;
    vec3 s = ((c & 1) != 0 ? h : -h) * b.right.xyz + ((c & 2) != 0 ? h : -h) * b.up.xyz;
    vec3 w = b.direction.xyz, m = b.nearPlane.xyz;
    // Depth of the near plane along w at this corner of the square, then D further for the far face.
    float z = (b.nearPlane.w - dot(b.origin.xyz + s, m)) / dot(w, m) + ((c & 4) != 0 ? b.direction.w : 0.0);
    if (u_useRanges) {
        vec2 range = r_ranges[k];
        if (range.x > range.y) { gl_Position = vec4(0.0); v_bundle = k; return; }  // no first hit: nothing to draw
        z = (c & 4) != 0 ? range.y + u_rangeMargin : range.x - u_rangeMargin;
    }
    gl_Position = u_frame.clipFromWorld * vec4(b.origin.xyz + s + z * w, 1.0);
    v_bundle = k;
}
