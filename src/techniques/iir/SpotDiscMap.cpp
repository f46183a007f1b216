#include "techniques/iir/SpotDiscMap.h"

#include "core/Check.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace bounce {

SpotDiscMap::SpotDiscMap(double falloffExponent, double cutoffAngle) {
    BOUNCE_CHECK(falloffExponent >= 0.0 && std::isfinite(falloffExponent), "spot falloff exponent {} is not >= 0",
                 falloffExponent);
    BOUNCE_CHECK(cutoffAngle > 0.0, "spot cutoff angle {} rad is not positive", cutoffAngle);
    m_exponentPlusOne = falloffExponent + 1.0;
    m_cutoffAngle = std::min(cutoffAngle, glm::half_pi<double>());
    // At 90 degrees 1 - cos(c) must be exactly 1 so that the horizon of the 180-degree spot is inside
    // the closed cone (cos of the double nearest pi/2 is 6e-17, not 0); 2 sin^2(c/2) keeps narrow
    // cones free of cancellation.
    const double halfSin = std::sin(0.5 * m_cutoffAngle);
    m_cutoffOneMinusCos = m_cutoffAngle >= glm::half_pi<double>() ? 1.0 : 2.0 * halfSin * halfSin;
    m_coneFlux = fluxBelow(m_cutoffOneMinusCos);
}

double SpotDiscMap::fluxBelow(double oneMinusCos) const {
    // cos^(n+1) = exp((n+1) log(1 - t)); log1p/expm1 keep full precision as t -> 0.
    return -std::expm1(m_exponentPlusOne * std::log1p(-oneMinusCos));
}

double SpotDiscMap::fluxFractionWithin(double alpha) const {
    if (alpha <= 0.0) return 0.0;
    if (alpha >= m_cutoffAngle) return 1.0;
    const double halfSin = std::sin(0.5 * alpha);
    return fluxBelow(2.0 * halfSin * halfSin) / m_coneFlux;
}

std::optional<glm::dvec2> SpotDiscMap::toDisc(const glm::dvec3& directionLocal) const {
    const double length = glm::length(directionLocal);
    if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
    const glm::dvec3 d = directionLocal / length;
    const double radial2 = d.x * d.x + d.y * d.y;  // sin^2(alpha)
    // 1 - cos(alpha) without cancellation near the axis: sin^2 / (1 + cos).
    const double oneMinusCos = d.z > 0.0 ? radial2 / (1.0 + d.z) : 1.0 - d.z;
    // The cone is closed: the largest-empty-circle search puts points on the rim (r = 1, alpha = c),
    // and they must map back.
    if (!(oneMinusCos <= m_cutoffOneMinusCos)) return std::nullopt;
    if (radial2 == 0.0) return glm::dvec2(0.0);
    const double r = std::min(1.0, std::sqrt(fluxBelow(oneMinusCos) / m_coneFlux));
    return glm::dvec2(d.x, d.y) * (r / std::sqrt(radial2));
}

glm::dvec3 SpotDiscMap::toDirection(const glm::dvec2& disc) const {
    const double r2 = std::min(1.0, disc.x * disc.x + disc.y * disc.y);
    if (r2 == 0.0) return glm::dvec3(0.0, 0.0, 1.0);
    // Invert r^2 = F(t) / F(t_c): 1 - cos(alpha) = 1 - (1 - r^2 F(t_c))^(1/(n+1)).
    const double oneMinusCos = -std::expm1(std::log1p(-r2 * m_coneFlux) / m_exponentPlusOne);
    const double sinAlpha = std::sqrt(std::max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
    const double r = std::sqrt(disc.x * disc.x + disc.y * disc.y);
    return glm::dvec3(disc.x / r * sinAlpha, disc.y / r * sinAlpha, 1.0 - oneMinusCos);
}

}  // namespace bounce
