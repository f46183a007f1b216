#pragma once
// Sampling points on the unit disc (spot lights, Laine et al. 2007 §4.1) in a CGAL 2D Delaunay
// triangulation. Cells are clipped to the disc exactly (DiscCell) and cached per slot: an insertion
// or deletion only changes the cells of the affected site's Delaunay neighbours, so the repeated
// largest-empty-circle searches of one frame recompute a handful of cells each.
#include "techniques/iir/DomainTriangulation.h"

#include <memory>

namespace bounce {

class DiscTriangulation final : public DomainTriangulation {
public:
    // `seed` only breaks the one exact tie of the disc: with a single site at the centre every rim
    // point is an equally large empty circle.
    DiscTriangulation(size_t slotCapacity, uint64_t seed);
    ~DiscTriangulation() override;
    DiscTriangulation(const DiscTriangulation&) = delete;
    DiscTriangulation& operator=(const DiscTriangulation&) = delete;

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
