// Photon splatting (seed 004, §3.3/§4.3): the bundles' orthographic depth maps, all of a batch in one
// multi-draw: each draw is one (bundle, cluster) pair the CPU kept (its box meets the bundle's
// volume); its instance attribute, read at the draw's baseInstance, names the bundle and the object.
// The vertex is pulled from the scene's vertex buffer by its index (gl_VertexID), placed in the
// bundle's tile of the depth atlas (the bundle's square -> the tile, local depth [zNear, zFar] ->
// [0, 1]), and clipped to the tile and to the bundle's volume: past its tilted near plane, before its
// far plane, in front of the photon's own surface. Back faces are drawn too (no culling, 4.3).
#include "common/scene.glsl"
#include "techniques/photon_splat/splat_shared.h"

struct SceneVertex { float px, py, pz, nx, ny, nz, u, v; };  // render/SceneGpu.cpp's Vertex (32 bytes)
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer Bundles { BundleGpu b_bundles[]; };
layout(std430, binding = BINDING_SSBO_TECH1) readonly buffer SceneVertices { SceneVertex s_vertices[]; };
layout(location = 0) in uvec2 a_draw;  // (bundle, object), per instance
uniform int u_first;     // bundle of tile 0
uniform ivec2 u_tiles;   // tiles per row, rows

out float gl_ClipDistance[7];
out vec2 v_uv;         // for render/shadow_depth.frag's alpha mask
flat out uint v_object;

void main() {
    SceneVertex sv = s_vertices[gl_VertexID];
    v_uv = vec2(sv.u, sv.v);
    v_object = a_draw.y;
    vec3 p = (u_objects[a_draw.y].worldFromObject * vec4(sv.px, sv.py, sv.pz, 1.0)).xyz;
    BundleGpu b = b_bundles[a_draw.x];
    float h = b.origin.w;
    vec3 d = p - b.origin.xyz;
    vec2 st = vec2(dot(d, b.right.xyz), dot(d, b.up.xyz)) / h;  // [-1, 1] over the square
    float z = dot(d, b.direction.xyz);
    int tile = int(a_draw.x) - u_first;
    vec2 corner = vec2(tile % u_tiles.x, tile / u_tiles.x);
    gl_Position = vec4((corner + 0.5 * (st + 1.0)) / vec2(u_tiles) * 2.0 - 1.0,
                       2.0 * (z - b.right.w) / (b.up.w - b.right.w) - 1.0, 1.0);
    gl_ClipDistance[0] = 1.0 + st.x;
    gl_ClipDistance[1] = 1.0 - st.x;
    gl_ClipDistance[2] = 1.0 + st.y;
    gl_ClipDistance[3] = 1.0 - st.y;
    float m = dot(p, b.nearPlane.xyz);
    gl_ClipDistance[4] = b.nearPlane.w - m;                                                   // past the near plane
    gl_ClipDistance[5] = m - (b.nearPlane.w + b.direction.w * dot(b.direction.xyz, b.nearPlane.xyz));  // before the far plane
    gl_ClipDistance[6] = b.emitter.w < -1e29 ? 1.0 : dot(p, b.emitter.xyz) - b.emitter.w;     // in front of the photon's surface
}
