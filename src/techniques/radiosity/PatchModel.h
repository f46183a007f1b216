#pragma once
// The patches and elements of van de Hoef 2013 sec. 4.1, GL-free: every surface of the scene becomes
// planar quads, each owning an nu x nv region of one radiosity texture atlas whose outer ring of texel
// centres lies on the quad's edges (thesis Fig. 4.1.2), so coplanar neighbours sample the same points
// and bilinear display is continuous across quads without communication.
//
// Quads come from the meshes: two triangles that share an edge, lie in one plane and form a convex
// quadrilateral become one quad (the built-in scenes are quads already); a triangle with no such
// partner gets a triangular region (the lower-left half of its texel square; the texels beyond the
// hypotenuse sample the hypotenuse, so about half of its texels are wasted: the cost of supporting
// meshes the thesis cannot load). Area lights become emitter quads of their own "body".
//
// Element areas: a texel's cell is the square around its centre clipped to the quad, so edge texels
// own half a cell and corner texels a quarter (the "reduced areas" of sec. 4.1); the integral runs
// over the exact piecewise-linear surface map and the areas sum to the quad's area. Border texels
// sit at distance 0 from the neighbouring quads. Where a quad edge continues into a coplanar
// neighbour (same two corners) the samples coincide with the neighbour's, as the thesis intends;
// on every other edge (a junction with a wall, a free edge) the sample position (not the display
// position) moves inward by borderInset texel pitches. The thesis offsets corner texels only ("a
// small offset", value not given); an edge texel on a concave junction (floor meets wall) has the
// same singularity: its hemicube straddles the other wall's plane and integrates half a hemisphere
// (measured 0.500 against 1.000 in the furnace).
#include "core/Error.h"
#include "scene/Scene.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace bounce::radiosity {

struct PatchOptions {
    float elementSize = 0.05f;         // metres between texel centres on static bodies
    float dynamicElementSize = 0.05f;  // the same on animated bodies
    float borderInset = 0.25f;         // texel pitches
    size_t maxElements = size_t(1) << 20;
};

enum class QuadMap { Quad = 0, Triangle = 1 };  // RAD_MAP_QUAD, RAD_MAP_TRIANGLE

struct Quad {
    glm::vec3 p[4];          // object-space corners at (s,t) = (0,0) (1,0) (1,1) (0,1)
    QuadMap map = QuadMap::Quad;
    glm::vec3 normal{0.0f};  // object space, unit, the front side
    float area = 0.0f;       // m^2
    glm::vec3 emission{0.0f};  // W/(m^2 sr)
    uint32_t body = 0;       // object index, or objects + light index
    int nu = 2, nv = 2;      // texels per side
    int atlasX = 0, atlasY = 0;
    uint32_t firstElement = 0;
    uint32_t flags = 0;      // RAD_QUAD_*
    uint32_t surface = 0;    // the coplanar surface (quads of one body joined at shared edges) it is part of
};

struct Element {
    glm::vec3 position{0.0f};  // object space
    float area = 0.0f;         // m^2
    glm::vec3 albedo{0.0f};
    glm::vec3 emission{0.0f};  // W/(m^2 sr)
    uint32_t quad = 0;
    int i = 0, j = 0;          // texel within the quad
};

// Which quad a mesh triangle belongs to, and the (s,t) corner of each of its vertices
// (2 bits per vertex: bit 0 = s, bit 1 = t), for the passes that draw the scene.
struct TriangleRef {
    uint32_t quad = 0xFFFFFFFFu;  // RAD_NO_QUAD for degenerate triangles
    uint32_t corners = 0;
};

class PatchModel {
public:
    // Errors: a textured or two-sided area light, no light and no emitter at all, degenerate-only
    // geometry, more than maxElements elements (naming the element size to raise). Point, spot and
    // directional lights make no quads (RadiositySystem shoots their direct light into the elements).
    static Expected<PatchModel> build(const Scene& scene, const PatchOptions& options);

    const std::vector<Quad>& quads() const { return m_quads; }
    const std::vector<Element>& elements() const { return m_elements; }
    const std::vector<TriangleRef>& triangles() const { return m_triangles; }
    // First entry of object k's triangles in triangles().
    const std::vector<uint32_t>& objectTriangleBase() const { return m_objectTriangleBase; }
    glm::ivec2 atlasSize() const { return m_atlasSize; }
    uint32_t bodyCount() const { return m_bodyCount; }
    uint32_t objectCount() const { return m_objectCount; }
    // World transform of body b at time t (lights: the rest rectangle carried to the light at t).
    glm::mat4 bodyTransform(const Scene& scene, uint32_t body, float t) const;
    bool bodyAnimated(const Scene& scene, uint32_t body) const;
    size_t lightQuadCount() const { return m_lightQuads; }
    uint32_t firstLightQuad() const { return static_cast<uint32_t>(m_quads.size() - m_lightQuads); }

    // The surface point of quad q at (s,t) (object space), the map RAD_MAP_* of patch.glsl.
    static glm::vec3 pointAt(const Quad& q, glm::vec2 st);
    // (s,t) of texel (i, j): texel centres on the edges.
    static glm::vec2 texelParam(const Quad& q, int i, int j) {
        return {static_cast<float>(i) / static_cast<float>(q.nu - 1), static_cast<float>(j) / static_cast<float>(q.nv - 1)};
    }

private:
    // Appends quad q's nu x nv elements (q is in m_quads), albedo at each texel's (s, t).
    void addElements(Quad& q, const std::function<glm::vec3(glm::vec2)>& albedo);

    std::vector<Quad> m_quads;
    std::vector<Element> m_elements;
    std::vector<TriangleRef> m_triangles;
    std::vector<uint32_t> m_objectTriangleBase;
    glm::ivec2 m_atlasSize{0};
    uint32_t m_bodyCount = 0, m_objectCount = 0;
    size_t m_lightQuads = 0;
};

// Light body frame: columns edgeU, edgeV, normal, position of the light at time t.
glm::mat4 lightFrame(const Light& light);

// The radiance rho E cos / pi that a surface point p (unit normal n, world space) of diffuse albedo rho
// reflects of a point, spot or directional light's direct light, unshadowed (common/lighting.glsl's
// punctualIrradiance, the GPU's version); zero for an area light. The CPU side uses it to scale the
// shooting thresholds; the GPU evaluates it with shadow-map visibility.
glm::vec3 punctualDirectRadiance(const Light& light, glm::vec3 p, glm::vec3 n, glm::vec3 albedo);

}  // namespace bounce::radiosity
