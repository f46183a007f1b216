#pragma once
// Sampling points on the unit sphere (omni lights, Laine et al. 2007 §4.1) in CGAL's
// Delaunay_triangulation_on_sphere_2, whose faces are the facets of the points' convex hull: the
// spherical Delaunay triangulation. The paper built a 3D tetrahedralisation and used its surface; a
// triangulation on the sphere is what its §7 asks for, and it avoids the fully degenerate in-sphere
// tests a 3D Delaunay triangulation of co-spherical points runs into (see docs/techniques/iir.md).
// Voronoi vertices are the hull facets' outward normals; cell areas are fans of spherical triangles.
#include "techniques/iir/DomainTriangulation.h"

#include <memory>

namespace bounce {

class SphereTriangulation final : public DomainTriangulation {
public:
    // `seed` breaks the exact ties of tiny point sets: the first point (no sites: every point is
    // equally far) and a point on the great circle between two antipodal sites.
    SphereTriangulation(size_t slotCapacity, uint64_t seed);
    ~SphereTriangulation() override;
    SphereTriangulation(const SphereTriangulation&) = delete;
    SphereTriangulation& operator=(const SphereTriangulation&) = delete;

    size_t slotCapacity() const override;
    double domainArea() const override;
    size_t size() const override;
    bool contains(SlotId slot) const override;
    glm::dvec3 point(SlotId slot) const override;
    void clear() override;
    std::vector<SlotId> rebuild(std::span<const Site> sites) override;
    bool insert(const Site& site) override;
    void remove(SlotId slot) override;
    void neighbours(SlotId slot, std::vector<SlotId>& out) const override;
    std::optional<Edge> shortestEdge() const override;
    EmptyCircle largestEmptyCircle() override;
    void cellAreas(std::span<double> areas) override;
    void triangles(std::vector<std::array<SlotId, 3>>& out) const override;
    void edges(std::vector<Edge>& out) const override;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace bounce
