// van de Hoef 2013 sec. 4.1: quads, elements and the radiosity atlas (the records of
// radiosity_shared.h, the surface map of PatchModel.cpp). Host defines: none.
#include "techniques/radiosity/radiosity_shared.h"

layout(std430, binding = BINDING_SSBO_RAD_QUADS) readonly buffer RadQuadBlock { RadQuadGpu u_quads[]; };
layout(std430, binding = BINDING_SSBO_RAD_TRIANGLES) readonly buffer RadTriangleBlock {
    uvec4 u_triangleHeader;  // x: object count
    uvec4 u_triangleData[];  // [0, objects): x = first triangle of object k; then per triangle: x quad, y corner codes
};
layout(std430, binding = BINDING_SSBO_RAD_BODIES) readonly buffer RadBodyBlock { RadBodyGpu u_bodies[]; };
layout(std430, binding = BINDING_SSBO_RAD_BODIES_OLD) readonly buffer RadBodyOldBlock { RadBodyGpu u_bodiesOld[]; };

// The light-quad draws tag their object index with this bit (light.vert).
const uint RAD_LIGHT_OBJECT_BIT = 0x80000000u;
const uint RAD_SKIP_OBJECT = 0xFFFFFFFFu;
const uint RAD_NO_MATERIAL = 0xFFFFFFFFu;  // g_material of light quads: never masked  // a light quad the draw's filter excludes

// The surface point of quad q at (s, t), object space (PatchModel::pointAt).
vec3 radPointAt(RadQuadGpu q, vec2 st) {
    if (floatBitsToUint(q.p0.w) == uint(RAD_MAP_TRIANGLE) || st.x + st.y <= 1.0)
        return q.p0.xyz + st.x * (q.p1.xyz - q.p0.xyz) + st.y * (q.p3.xyz - q.p0.xyz);
    return q.p2.xyz + (1.0 - st.x) * (q.p3.xyz - q.p2.xyz) + (1.0 - st.y) * (q.p1.xyz - q.p2.xyz);
}

// Texture coordinate of (s, t) in the atlas: the region's outer texel centres lie on the edges.
vec2 radAtlasUv(RadQuadGpu q, vec2 st, vec2 atlasSize) {
    return (vec2(q.atlas.xy) + 0.5 + st * vec2(q.atlas.zw - 1u)) / atlasSize;
}

// Quad and (s, t) corners of scene triangle `prim` of object `object` (or of a light quad).
uint radTriangleQuad(uint object, uint prim, out vec2 st[3]) {
    uint quad, corners;
    if ((object & RAD_LIGHT_OBJECT_BIT) != 0u) {
        quad = object & ~RAD_LIGHT_OBJECT_BIT;
        corners = (prim & 1u) == 0u ? (0u | 1u << 2 | 2u << 4) : (1u | 3u << 2 | 2u << 4);
    } else {
        uvec4 t = u_triangleData[u_triangleHeader.x + u_triangleData[object].x + prim];
        quad = t.x;
        corners = t.y;
    }
    for (int k = 0; k < 3; ++k) {
        uint c = (corners >> (2 * k)) & 3u;
        st[k] = vec2(float(c & 1u), float(c >> 1));
    }
    return quad;
}

mat4 radWorldFromObject(uint body, bool old) {
    return old ? u_bodiesOld[body].worldFromObject : u_bodies[body].worldFromObject;
}
vec3 radNormalToWorld(uint body, bool old, vec3 n) {
    return normalize(mat3(old ? u_bodiesOld[body].normalFromObject : u_bodies[body].normalFromObject) * n);
}
bool radBodyMoving(uint body) { return u_bodies[body].info.x != 0u; }
