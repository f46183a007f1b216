#pragma once
// An orthonormal frame whose z axis is a light's direction (the spot axis). Laine et al. 2007 §4.1
// build "a basis where the z axis points to the spot direction" to map VPL directions to the disc.
#include <glm/vec3.hpp>

namespace bounce {

struct LightBasis {
    glm::dvec3 tangent{1.0, 0.0, 0.0};
    glm::dvec3 bitangent{0.0, 1.0, 0.0};
    glm::dvec3 axis{0.0, 0.0, 1.0};

    // Right-handed (tangent x bitangent = axis). `axis` need not be normalised but must be non-zero.
    // Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017, listing 3: no
    // branch on a threshold, so the frame changes continuously except where axis.z changes sign.
    // Any rotation of the frame about the axis rotates every disc point rigidly, which leaves the
    // Delaunay triangulation, the cell areas and the dispersion unchanged; only continuity matters.
    static LightBasis fromAxis(const glm::dvec3& axis);

    glm::dvec3 toLocal(const glm::dvec3& world) const;
    glm::dvec3 toWorld(const glm::dvec3& local) const;
};

}  // namespace bounce
