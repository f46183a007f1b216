#pragma once
// Elementary spherical geometry for Voronoi cells of sampling points on the unit sphere
// (Laine et al. 2007 §4.7: "areas ... using elementary geometry both on unit disc and unit sphere").
#include <glm/vec3.hpp>

#include <span>

namespace bounce {

// Signed area (solid angle, sr) of the spherical triangle a, b, c on the unit sphere: positive when
// counter-clockwise seen from outside. Van Oosterom & Strackee, "The solid angle of a plane
// triangle", IEEE Trans. Biomed. Eng. 30(2), 1983: tan(E/2) = a.(b x c) / (1 + a.b + b.c + c.a),
// valid for triangles whose sides are shorter than pi.
double signedSphericalTriangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// Voronoi cell areas of unit-sphere sites that all lie in one plane perpendicular to `axis` (unit):
// at most three sites, or all on one circle. The bisector planes then all contain the axis, so each
// cell is a lune between the bisectors with its angular neighbours, of area 2 * (dihedral angle) =
// (gap to previous + gap to next) in azimuth about the axis. One site gets 4 pi. Distinct sites must
// have distinct azimuths (true for distinct points on one circle about the axis).
void planarSphereCellAreas(const glm::dvec3& axis, std::span<const glm::dvec3> sites, std::span<double> areas);

}  // namespace bounce
