#pragma once
// The Delaunay triangulation (and, through it, the Voronoi diagram) of the sampling points in their
// domain, kept under insertion and deletion (Laine et al. 2007 §4.1). Two implementations, both on
// CGAL (kept out of this header because CGAL is slow to compile):
//   DiscTriangulation   unit disc, CGAL::Delaunay_triangulation_2
//   SphereTriangulation unit sphere, CGAL::Delaunay_triangulation_on_sphere_2
// Points are glm::dvec3: (x, y, 0) on the disc, unit vectors on the sphere. Each point belongs to a
// slot (the VPL's index) in [0, slotCapacity()). Distances are Euclidean in R^2 / R^3 (chordal on the
// sphere), as §4.3 allows.
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace bounce {

using SlotId = uint32_t;

class DomainTriangulation {
public:
    struct Site {
        SlotId slot = 0;
        glm::dvec3 point{0.0};
    };
    struct Edge {
        SlotId a = 0;
        SlotId b = 0;
        double length = 0.0;
    };
    struct EmptyCircle {
        glm::dvec3 centre{0.0};  // in the domain
        double radius = 0.0;     // distance to the nearest site; kEmptyDomainRadius with no sites
    };
    // Reported radius of the largest empty circle (and so the dispersion) of an empty point set.
    // Eq. (1) would give +infinity; the domain's diameter (2 for both domains) is the bound any
    // non-empty set obeys, and it keeps the statistics finite.
    static constexpr double kEmptyDomainRadius = 2.0;

    virtual ~DomainTriangulation() = default;

    virtual size_t slotCapacity() const = 0;
    virtual double domainArea() const = 0;  // pi (disc) or 4 pi (sphere)
    virtual size_t size() const = 0;
    virtual bool contains(SlotId slot) const = 0;
    virtual glm::dvec3 point(SlotId slot) const = 0;

    virtual void clear() = 0;
    // Replaces the contents by `sites` (bulk insertion in a spatially sorted order). Returns the slots
    // that were not inserted because their point coincides with (or, on the sphere, is closer than
    // CGAL's 2^-23 to) an earlier site.
    virtual std::vector<SlotId> rebuild(std::span<const Site> sites) = 0;
    // False, and nothing changes, when the point coincides with a present site (or cannot be placed).
    virtual bool insert(const Site& site) = 0;
    virtual void remove(SlotId slot) = 0;

    // Delaunay neighbours of a present slot.
    virtual void neighbours(SlotId slot, std::vector<SlotId>& out) const = 0;
    // The shortest Delaunay edge (the closest pair of sites); empty with fewer than two sites.
    virtual std::optional<Edge> shortestEdge() const = 0;
    // Centre of the largest empty circle centred in the domain and its radius, i.e. the dispersion of
    // the sites, Eq. (1) (§4.6). Ties go to the first candidate found, in slot / face order.
    virtual EmptyCircle largestEmptyCircle() = 0;
    // Area of each site's Voronoi cell within the domain, indexed by slot; areas.size() must equal
    // slotCapacity(). Entries of absent slots are set to 0.
    virtual void cellAreas(std::span<double> areas) = 0;

    // For tests and debug views: the Delaunay triangles (finite ones on the disc, all hull facets on
    // the sphere), and the edges.
    virtual void triangles(std::vector<std::array<SlotId, 3>>& out) const = 0;
    virtual void edges(std::vector<Edge>& out) const = 0;

    // §4.5: of the two ends of the shortest Delaunay edge, the one whose second-closest Delaunay
    // neighbour is nearer (ties: the lower slot). Empty with fewer than two sites.
    std::optional<SlotId> shortestEdgeVictim() const;
    // Distance from a present slot to its second-closest Delaunay neighbour (+infinity with fewer than
    // two neighbours).
    double secondClosestNeighbourDistance(SlotId slot) const;
};

}  // namespace bounce
