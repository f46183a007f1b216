#pragma once
// Builds indexed triangle meshes for the procedural built-in scenes. Faces are given with an explicit
// outward direction so winding (counter-clockwise seen from the front, the OpenGL default) never
// depends on the order in which the caller lists corners.
#include "scene/Scene.h"

#include <glm/vec3.hpp>

#include <functional>
#include <string>

namespace bounce {

class MeshBuilder {
public:
    explicit MeshBuilder(std::string name) { m_mesh.name = std::move(name); }
    // A builder that only counts triangles (for sizing tessellation to a triangle budget).
    static MeshBuilder counter() {
        MeshBuilder b("");
        b.m_countOnly = true;
        return b;
    }

    // A triangle whose front side faces `front` (winding is flipped when needed).
    void triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 front);
    // A planar quad a-b-c-d (in order around its boundary) split into `nu` x `nv` cells, each two
    // triangles, with flat normals facing `front`. u runs a->b, v runs a->d.
    void quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 front, int nu = 1, int nv = 1);
    // A closed box with faces pointing out of (outward = true) or into it, given its 8 corners:
    // bottom ring b[0..3] then top ring t[0..3], both in the same rotational order.
    void box(const glm::vec3 bottom[4], const glm::vec3 top[4], bool outward, int subdivisions = 1);
    // An axis-aligned box [lo, hi]; see box().
    void axisBox(glm::vec3 lo, glm::vec3 hi, bool outward = true, int subdivisions = 1);
    // A vertical cylinder side (no caps) of `radius` from base centre `base` up `height`, with smooth
    // outward normals, `segments` around and `rings` along the axis.
    void cylinder(glm::vec3 base, float radius, float height, int segments, int rings);
    // A parametric patch p(u, v), u, v in [0, 1], split into nu x nv cells, with normals from central
    // differences oriented toward `front` at the patch centre (one patch is assumed to face one way).
    void surface(int nu, int nv, const std::function<glm::vec3(float, float)>& p, glm::vec3 front);
    // A flat disc facing `front` (unit), as a fan of `segments` triangles.
    void disk(glm::vec3 centre, float radius, glm::vec3 front, int segments);
    // One bay of an arcade: a block `2 * halfSpan` wide along `along` (unit), `halfSpan` high above the
    // springing line through `centre`, `depth` thick along `across` (unit, horizontal), pierced by a
    // semicircular opening of `innerRadius` centred at `centre`. Emits both faces (the spandrels), the
    // intrados, the soffits beside the opening and the flat top; the bay's ends are shared with neighbours or piers and are left open.
    // `segments` is rounded up to a multiple of 4 so the square's corners fall on segment ends.
    void archBay(glm::vec3 centre, glm::vec3 along, glm::vec3 across, float halfSpan, float innerRadius,
                 float depth, int segments);

    size_t triangleCount() const { return m_triangleCount; }
    Mesh take() { return std::move(m_mesh); }

private:
    uint32_t vertex(glm::vec3 p, glm::vec3 n, glm::vec2 uv);
    void indices(uint32_t a, uint32_t b, uint32_t c);

    Mesh m_mesh;
    bool m_countOnly = false;
    uint32_t m_vertexCount = 0;
    size_t m_triangleCount = 0;
};

}  // namespace bounce
