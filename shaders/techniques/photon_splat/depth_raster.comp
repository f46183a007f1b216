// Photon splatting (seed 004, §3.3/§4.3): the bundles' orthographic depth maps rasterised in a compute
// pass (depthMaps=compute, the llvmpipe profile's default: llvmpipe sets up every triangle clipped to an
// 8x8 tile as a general triangle, which made depth.vert's draws most of the frame). The same map as
// depth.vert + render/shadow_depth.frag: one workgroup per (bundle, cluster) pair the CPU kept, one
// invocation per triangle of the cluster; a texel is written where its centre lies in the triangle
// (edges inclusive: a depth map keeps the nearest, so a texel on a shared edge is no occluder twice),
// at the triangle's depth there, if that point lies past the volume's near plane, before its far plane,
// in front of the photon's surface, in the map's depth range and not alpha-masked. Orthographic, so
// every quantity interpolates linearly over the tile. Depths in [0, 1] are non-negative floats, whose
// bits order as unsigned integers: imageAtomicMin on the atlas's R32UI view keeps the nearest.
#include "common/scene.glsl"
#include "techniques/photon_splat/splat_shared.h"

layout(local_size_x = SPLAT_CLUSTER_TRIANGLES) in;
#include "common/dispatch.glsl"

struct SceneVertex { float px, py, pz, nx, ny, nz, u, v; };  // render/SceneGpu.cpp's Vertex (32 bytes)
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer Bundles { BundleGpu b_bundles[]; };
layout(std430, binding = BINDING_SSBO_TECH1) readonly buffer SceneVertices { SceneVertex s_vertices[]; };
// Per pair: bundle, object, first index and index count of the cluster in c_indices.
layout(std430, binding = BINDING_SSBO_TECH2) readonly buffer Pairs { uvec4 p_pairs[]; };
layout(std430, binding = BINDING_SSBO_TECH3) readonly buffer ClusterIndices { uint c_indices[]; };
layout(r32ui, binding = BINDING_IMG0) uniform uimage2D i_maps;
uniform int u_first;         // bundle of tile 0
uniform ivec2 u_tiles;       // tiles per row, rows
uniform int u_resolution;    // texels per tile side
uniform uint u_pairCount;

// A corner of the triangle in the bundle's tile: q in texels over the tile, then the attributes that
// interpolate linearly over it: depth in [0, 1], the three clip distances of depth.vert, the uv.
struct Corner { vec2 q; float depth; vec3 clip; vec2 uv; };

Corner corner(BundleGpu b, mat4 worldFromObject, uint index) {
    SceneVertex sv = s_vertices[index];
    vec3 p = (worldFromObject * vec4(sv.px, sv.py, sv.pz, 1.0)).xyz;
    vec3 d = p - b.origin.xyz;
    vec2 st = vec2(dot(d, b.right.xyz), dot(d, b.up.xyz)) / b.origin.w;  // [-1, 1] over the square
    Corner c;
    c.q = 0.5 * (st + 1.0) * float(u_resolution);
    c.depth = (dot(d, b.direction.xyz) - b.right.w) / (b.up.w - b.right.w);
    float m = dot(p, b.nearPlane.xyz);
    c.clip = vec3(b.nearPlane.w - m,                                                           // past the near plane
                  m - (b.nearPlane.w + b.direction.w * dot(b.direction.xyz, b.nearPlane.xyz)),  // before the far plane
                  b.emitter.w < -1e29 ? 1.0 : dot(p, b.emitter.xyz) - b.emitter.w);           // in front of the photon's surface
    c.uv = vec2(sv.u, sv.v);
    return c;
}

float edge(vec2 a, vec2 b, vec2 x) { return (b.x - a.x) * (x.y - a.y) - (b.y - a.y) * (x.x - a.x); }

void main() {
    uint w = linearGroup();
    if (w >= u_pairCount) return;
    uvec4 pair = p_pairs[w];
    uint t = gl_LocalInvocationID.x;
    if (3u * t + 2u >= pair.w) return;
    BundleGpu b = b_bundles[pair.x];
    mat4 worldFromObject = u_objects[pair.y].worldFromObject;
    uint first = pair.z + 3u * t;
    Corner c0 = corner(b, worldFromObject, c_indices[first]);
    Corner c1 = corner(b, worldFromObject, c_indices[first + 1u]);
    Corner c2 = corner(b, worldFromObject, c_indices[first + 2u]);
    // Whole-triangle rejections: off the tile, or all three corners outside one clip plane or depth bound.
    float r = float(u_resolution);
    vec2 lo = min(c0.q, min(c1.q, c2.q)), hi = max(c0.q, max(c1.q, c2.q));
    if (any(greaterThan(lo, vec2(r - 0.5))) || any(lessThan(hi, vec2(0.5)))) return;
    vec3 clipHi = max(c0.clip, max(c1.clip, c2.clip));
    if (any(lessThan(clipHi, vec3(0.0)))) return;
    if (min(c0.depth, min(c1.depth, c2.depth)) > 1.0 || max(c0.depth, max(c1.depth, c2.depth)) < 0.0) return;
    float area = edge(c0.q, c1.q, c2.q);
    if (area == 0.0) return;  // edge-on to the bundle: no texel centre inside, as rasterization
    ivec2 from = ivec2(max(ceil(lo - 0.5), vec2(0.0)));
    ivec2 to = ivec2(min(floor(hi - 0.5), vec2(r - 1.0)));
    int tile = int(pair.x) - u_first;
    ivec2 origin = ivec2(tile % u_tiles.x, tile / u_tiles.x) * u_resolution;
    uint material = u_objects[pair.y].info.x;
    for (int j = from.y; j <= to.y; ++j)
        for (int i = from.x; i <= to.x; ++i) {
            vec2 x = vec2(i, j) + 0.5;
            vec3 l = vec3(edge(c1.q, c2.q, x), edge(c2.q, c0.q, x), edge(c0.q, c1.q, x)) / area;
            if (any(lessThan(l, vec3(0.0)))) continue;
            float depth = l.x * c0.depth + l.y * c1.depth + l.z * c2.depth;
            if (depth < 0.0 || depth > 1.0) continue;
            vec3 clip = l.x * c0.clip + l.y * c1.clip + l.z * c2.clip;
            if (any(lessThan(clip, vec3(0.0)))) continue;
            if (materialMasked(material, l.x * c0.uv + l.y * c1.uv + l.z * c2.uv)) continue;
            imageAtomicMin(i_maps, origin + ivec2(i, j), floatBitsToUint(abs(depth)));  // abs: -0.0's bits order last
        }
}
