#pragma once
// The Voronoi cell of one sampling point clipped to the unit disc, computed exactly: straight edges
// are bisectors of Delaunay neighbours, curved ones are arcs of the unit circle (no polygonal
// approximation of the rim). Gives the two things Laine et al. 2007 need per cell:
//  - its area (the VPL's share of the light's flux, §4.7), and
//  - the point of the cell farthest from its site. The largest of these over all cells is the centre
//    of the largest empty circle centred in the disc, i.e. the dispersion of Eq. (1) (§4.6). The
//    candidates are exactly the paper's three cases: Voronoi vertices inside the disc, points where
//    Voronoi edges cross the rim, and the rim point opposite the site (-p/|p|) when the cell reaches it.
#include <glm/vec2.hpp>

#include <span>

namespace bounce {

struct DiscCell {
    double area = 0.0;                // area of (Voronoi cell intersected with the unit disc)
    glm::dvec2 farthestPoint{0.0};    // point of that region farthest from the site
    double farthestDistance = 0.0;    // its distance to the site (Euclidean)
};

// `neighbours` are the site's Delaunay neighbours (any superset of them gives the same cell; a
// subset gives a larger one). The site must lie in the closed unit disc. `tieAngle` (radians) picks
// the rim point returned when the site is the disc's centre and its region reaches the whole rim,
// where every rim point is equally far.
DiscCell computeDiscCell(const glm::dvec2& site, std::span<const glm::dvec2> neighbours, double tieAngle);

}  // namespace bounce
