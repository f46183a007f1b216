#pragma once
// Maps the directions of a cosine-power spot light to the unit disc so that a uniform density of
// sampling points on the disc is a density of directions proportional to the spot's radiant
// intensity: equal disc area = equal flux.
//
// Laine et al. 2007 §4.1 use the Nusselt analog for the 180-degree cosine spot (drop z of the unit
// direction in the spot's frame) and note that other falloffs "can be easily mapped to the unit disc
// by a radial stretch" without giving it. bounce's spot is I(alpha) = I0 cos^n(alpha) for
// alpha < c (scene/Scene.h). The flux inside the cone of half-angle alpha is
//     Phi(alpha) = 2 pi I0 (1 - cos^(n+1) alpha) / (n + 1),
// and the fraction of the unit disc's area inside radius r is r^2, so the stretch that keeps the
// azimuth and matches the two cumulative distributions is
//     r(alpha)^2 = (1 - cos^(n+1) alpha) / (1 - cos^(n+1) c).
// For n = 1, c = 90 degrees this is r = sin(alpha): the Nusselt analog, i.e. (x, y) of the direction.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>

namespace bounce {

class SpotDiscMap {
public:
    // falloffExponent n >= 0; cutoffAngle c in radians, clamped to (0, pi/2] as Light::flux does
    // (cosines past 90 degrees would be negative).
    SpotDiscMap(double falloffExponent, double cutoffAngle);

    // The disc point of a direction given in the spot's frame (z = spot axis); it need not be unit
    // length. Empty when the direction is outside the closed cone (alpha > c) or zero: such a VPL is
    // outside the illumination region (§4.4 validity condition 2).
    std::optional<glm::dvec2> toDisc(const glm::dvec3& directionLocal) const;
    // The unit direction (spot frame) of a point of the closed unit disc; points outside are
    // projected onto the rim.
    glm::dvec3 toDirection(const glm::dvec2& disc) const;

    // Fraction of the spot's flux emitted within angle alpha of the axis, in [0, 1].
    double fluxFractionWithin(double alpha) const;

    double falloffExponent() const { return m_exponentPlusOne - 1.0; }
    double cutoffAngle() const { return m_cutoffAngle; }

private:
    // 1 - cos^(n+1)(alpha) from t = 1 - cos(alpha), accurate for small alpha (no cancellation).
    double fluxBelow(double oneMinusCos) const;

    double m_exponentPlusOne = 2.0;
    double m_cutoffAngle = 0.0;
    double m_cutoffOneMinusCos = 1.0;  // 1 - cos(c)
    double m_coneFlux = 1.0;           // fluxBelow(1 - cos c), the disc's rim
};

}  // namespace bounce
