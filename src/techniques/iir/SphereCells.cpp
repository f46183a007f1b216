#include "techniques/iir/SphereCells.h"

#include "core/Check.h"
#include "techniques/iir/LightBasis.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace bounce {

double signedSphericalTriangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double triple = glm::dot(a, glm::cross(b, c));
    const double denominator = 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a);
    return 2.0 * std::atan2(triple, denominator);
}

void planarSphereCellAreas(const glm::dvec3& axis, std::span<const glm::dvec3> sites, std::span<double> areas) {
    BOUNCE_CHECK(areas.size() == sites.size(), "{} areas for {} sites", areas.size(), sites.size());
    const size_t count = sites.size();
    if (count == 0) return;
    if (count == 1) {
        areas[0] = 4.0 * glm::pi<double>();
        return;
    }
    const LightBasis frame = LightBasis::fromAxis(axis);
    std::vector<double> azimuth(count);
    for (size_t i = 0; i < count; ++i)
        azimuth[i] = std::atan2(glm::dot(sites[i], frame.bitangent), glm::dot(sites[i], frame.tangent));
    std::vector<size_t> order(count);
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return azimuth[i] < azimuth[j]; });
    for (size_t k = 0; k < count; ++k) {
        const size_t previous = order[(k + count - 1) % count];
        const size_t next = order[(k + 1) % count];
        const size_t self = order[k];
        double gapBefore = azimuth[self] - azimuth[previous];
        double gapAfter = azimuth[next] - azimuth[self];
        if (gapBefore <= 0.0) gapBefore += glm::two_pi<double>();
        if (gapAfter <= 0.0) gapAfter += glm::two_pi<double>();
        areas[self] = gapBefore + gapAfter;
    }
}

}  // namespace bounce
