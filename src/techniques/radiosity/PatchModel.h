#pragma once
// The patches and elements of van de Hoef 2013 sec. 4.1, GL-free: every surface of the scene becomes
// planar rectangles ("quads", the thesis's patches), each owning an nu x nv region of one radiosity
// texture atlas whose outer ring of texel centres lies on the rectangle's edges (thesis Fig. 4.1.2).
//
// Quads are charts, decoupled from the mesh's triangulation (issue 30; radiosity.md "Charts, not the
// mesh's faces"): the connected triangles of one object whose normals lie within kChartConeDegrees of the chart's first
// triangle are one chart, parametrized on the tightest oriented bounding rectangle of their
// projection onto the chart's plane (area-weighted mean normal). Every triangle vertex gets its (s,t)
// in that rectangle, so thousands of small triangles share one texel region and the element count
// follows elementSize and the surface area, not the triangle count; a curved surface is cut into
// charts of at most the cone's normal spread. Area lights become emitter quads of their own "body".
//
// Element areas: a texel's cell is the square around its centre clipped to the rectangle and to the
// chart's triangles (each triangle clipped against the cells exactly, in the plane, and scaled by its
// true area over its projected area), so the areas sum to the chart's surface area; a cell no
// triangle covers is a ghost (area 0: it receives, for the bilinear display, and never shoots).
// Sample positions: the area-weighted centroid of the covered part of the cell, on the triangles
// (a full interior cell: its centre; a straight border: a quarter pitch inward, so no hemicube sits
// on a junction with the next wall, where it would integrate half a hemisphere: 0.500 against
// 1.000 in the furnace); a ghost takes the position of the nearest covered cell of its chart.
#include "core/Error.h"
#include "scene/Scene.h"

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace bounce::radiosity {

// Elements per scene when elementSize is automatic (0): the pitch is sqrt(surface area / this). Chosen
// so the Cornell boxes keep about the 0.05 m elements they had (cornell-box-area: 2.0 m^2 of surface,
// 1,217 elements at 0.05 m on the former per-face quads, 1,424 at the derived 0.044 m) while the
// 1,900 m^2 courtyard and atrium get 1.36-1.39 m (radiosity.md "Charts and element size: measurements").
constexpr double kAutoTargetElements = 1000.0;

// The element pitch elementSize = 0 ("auto") stands for: sqrt(A / kAutoTargetElements), A the summed
// area of the scene's triangles in world space (the objects' transforms at t = 0), metres.
float autoElementSize(const Scene& scene);

struct PatchOptions {
    float elementSize = 0.0f;         // world metres between texel centres on static bodies; 0 = autoElementSize
    float dynamicElementSize = 0.0f;  // the same on animated bodies; 0 = autoElementSize
    size_t maxElements = size_t(1) << 20;
};

struct Quad {
    glm::vec3 p[4];          // object-space corners at (s,t) = (0,0) (1,0) (1,1) (0,1): a rectangle
    glm::vec3 normal{0.0f};  // object space, unit, the front side
    float area = 0.0f;       // world m^2 of surface the chart covers (not the rectangle's)
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
    float area = 0.0f;         // world m^2 (the object's transform applied: scaled objects)
    glm::vec3 albedo{0.0f};
    glm::vec3 emission{0.0f};  // W/(m^2 sr)
    uint32_t quad = 0;
    int i = 0, j = 0;          // texel within the quad
};

// Which quad (chart) a mesh triangle belongs to, and the (s,t) of each of its vertices in the chart's
// rectangle, for the passes that draw the scene.
struct TriangleRef {
    uint32_t quad = 0xFFFFFFFFu;  // RAD_NO_QUAD for degenerate triangles
    glm::vec2 st[3]{};
};

class PatchModel {
public:
    // options.elementSize / dynamicElementSize 0 are replaced by autoElementSize(scene) (elementSize()
    // and dynamicElementSize() return what was used).
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
    float elementSize() const { return m_elementSize; }
    float dynamicElementSize() const { return m_dynamicElementSize; }
    // Elements with a non-zero area (the rest are ghosts: texels of a chart's rectangle no triangle covers).
    size_t activeElementCount() const { return m_activeElements; }
    uint32_t bodyCount() const { return m_bodyCount; }
    uint32_t objectCount() const { return m_objectCount; }
    // World transform of body b at time t (lights: the rest rectangle carried to the light at t).
    glm::mat4 bodyTransform(const Scene& scene, uint32_t body, float t) const;
    bool bodyAnimated(const Scene& scene, uint32_t body) const;
    size_t lightQuadCount() const { return m_lightQuads; }
    uint32_t firstLightQuad() const { return static_cast<uint32_t>(m_quads.size() - m_lightQuads); }

    // The point of quad q's rectangle at (s,t) (object space; patch.glsl radPointAt). On a curved chart
    // it lies on the chart's plane, not on its triangles.
    static glm::vec3 pointAt(const Quad& q, glm::vec2 st);
    // (s,t) of texel (i, j): texel centres on the edges.
    static glm::vec2 texelParam(const Quad& q, int i, int j) {
        return {static_cast<float>(i) / static_cast<float>(q.nu - 1), static_cast<float>(j) / static_cast<float>(q.nv - 1)};
    }

private:
    struct ChartTriangle {
        glm::vec3 p[3];     // object space
        glm::vec2 uv[3];    // material texture coordinates
        size_t ref = SIZE_MAX;  // entry in m_triangles that gets the vertices' (s, t), or none (light quads)
    };
    // Appends chart q (corners, normal, nu, nv, body, flags, emission set) made of `tris`: its elements
    // (cells clipped to the triangles, areas, centroids, albedo(uv) averaged over the covered part,
    // ghosts), its area, and the triangles' (s, t). areaMap: the cofactor matrix of the body's linear
    // transform (object to world area vectors), so areas are world m^2 on scaled objects.
    void addChart(Quad q, const std::vector<ChartTriangle>& tris, const std::function<glm::vec3(glm::vec2)>& albedo,
                  const glm::dmat3& areaMap = glm::dmat3(1.0));

    std::vector<Quad> m_quads;
    std::vector<Element> m_elements;
    std::vector<TriangleRef> m_triangles;
    std::vector<uint32_t> m_objectTriangleBase;
    glm::ivec2 m_atlasSize{0};
    float m_elementSize = 0.0f, m_dynamicElementSize = 0.0f;
    size_t m_activeElements = 0;
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
