#pragma once
// Builds indexed triangle meshes for the procedural built-in scenes. Faces are given with an explicit
// outward direction so winding (counter-clockwise seen from the front, the OpenGL default) never
// depends on the order in which the caller lists corners.
#include "scene/Scene.h"

#include <glm/vec3.hpp>

#include <string>

namespace bounce {

class MeshBuilder {
public:
    explicit MeshBuilder(std::string name) { m_mesh.name = std::move(name); }

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
    // A semicircular arch in the plane spanned by `along` (unit, the span direction) and +y, centred
    // at `centre`, between radii `innerRadius` and `outerRadius`, extruded `depth` along `across`
    // (unit, perpendicular to `along`) symmetric about the centre: intrados, extrados and both faces.
    void arch(glm::vec3 centre, glm::vec3 along, glm::vec3 across, float innerRadius, float outerRadius,
              float depth, int segments);

    size_t triangleCount() const { return m_mesh.indices.size() / 3; }
    Mesh take() { return std::move(m_mesh); }

private:
    uint32_t vertex(glm::vec3 p, glm::vec3 n, glm::vec2 uv);

    Mesh m_mesh;
};

}  // namespace bounce
