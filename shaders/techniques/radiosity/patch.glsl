// van de Hoef 2013 sec. 4.1: quads, elements and the radiosity atlas (the records of
// radiosity_shared.h, the surface map of PatchModel.cpp). Host defines: none.
#include "techniques/radiosity/radiosity_shared.h"

layout(std430, binding = BINDING_SSBO_RAD_QUADS) readonly buffer RadQuadBlock { RadQuadGpu u_quads[]; };
layout(std430, binding = BINDING_SSBO_RAD_TRIANGLES) readonly buffer RadTriangleBlock {
    uvec4 u_triangleHeader;  // x: object count
    uvec4 u_triangleData[];  // [0, objects): x = first triangle of object k; then per triangle: x quad,
                             // y, z, w: packUnorm2x16 (s, t) of its three vertices in the quad
};
layout(std430, binding = BINDING_SSBO_RAD_BODIES) readonly buffer RadBodyBlock { RadBodyGpu u_bodies[]; };
layout(std430, binding = BINDING_SSBO_RAD_BODIES_OLD) readonly buffer RadBodyOldBlock { RadBodyGpu u_bodiesOld[]; };

// The light-quad draws tag their object index with this bit (light.vert).
const uint RAD_LIGHT_OBJECT_BIT = 0x80000000u;
const uint RAD_SKIP_OBJECT = 0xFFFFFFFFu;
const uint RAD_NO_MATERIAL = 0xFFFFFFFFu;  // g_material of light quads: never masked  // a light quad the draw's filter excludes

// The point of quad q's rectangle at (s, t), object space (PatchModel::pointAt).
vec3 radPointAt(RadQuadGpu q, vec2 st) { return q.p0.xyz + st.x * (q.p1.xyz - q.p0.xyz) + st.y * (q.p3.xyz - q.p0.xyz); }

// Texture coordinate of (s, t) in the atlas: the region's outer texel centres lie on the edges.
vec2 radAtlasUv(RadQuadGpu q, vec2 st, vec2 atlasSize) {
    return (vec2(q.atlas.xy) + 0.5 + st * vec2(q.atlas.zw - 1u)) / atlasSize;
}

// Quad and (s, t) of the vertices of scene triangle `prim` of object `object` (or of a light quad,
// drawn as the triangles p0 p1 p3 and p1 p2 p3: light.vert).
uint radTriangleQuad(uint object, uint prim, out vec2 st[3]) {
    if ((object & RAD_LIGHT_OBJECT_BIT) != 0u) {
        bool second = (prim & 1u) != 0u;
        st[0] = second ? vec2(1.0, 0.0) : vec2(0.0, 0.0);
        st[1] = second ? vec2(1.0, 1.0) : vec2(1.0, 0.0);
        st[2] = vec2(0.0, 1.0);
        return object & ~RAD_LIGHT_OBJECT_BIT;
    }
    uvec4 t = u_triangleData[u_triangleHeader.x + u_triangleData[object].x + prim];
    st[0] = unpackUnorm2x16(t.y);
    st[1] = unpackUnorm2x16(t.z);
    st[2] = unpackUnorm2x16(t.w);
    return t.x;
}

mat4 radWorldFromObject(uint body, bool old) {
    return old ? u_bodiesOld[body].worldFromObject : u_bodies[body].worldFromObject;
}
vec3 radNormalToWorld(uint body, bool old, vec3 n) {
    return normalize(mat3(old ? u_bodiesOld[body].normalFromObject : u_bodies[body].normalFromObject) * n);
}
bool radBodyMoving(uint body) { return u_bodies[body].info.x != 0u; }
