#pragma once
// What the iir core's unit tests share (IirDistributionTest.cpp: mappings, cells, triangulations;
// IirVplDistributionTest.cpp: the per-frame VPL maintenance, Voronoi weights, tiles, determinism).
#include <glm/gtc/constants.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <random>

namespace bounce::iirtest {

inline constexpr double kPi = glm::pi<double>();

// Sums of up to ~1000 cell areas, each exact up to a few rounding errors of O(1) quantities.
inline constexpr double kAreaSumTolerance = 1e-9;

inline double random01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

inline glm::dvec3 randomOnSphere(std::mt19937_64& rng) {
    const double z = 2.0 * random01(rng) - 1.0;
    const double phi = 2.0 * kPi * random01(rng);
    const double s = std::sqrt(1.0 - z * z);
    return glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
}

}  // namespace bounce::iirtest
