#pragma once
// Small sampling and geometry helpers of the reference path tracer, inline because they sit in its
// inner loop.
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <bit>
#include <cmath>
#include <cstdint>

namespace bounce {

inline constexpr float kPi = glm::pi<float>();
inline constexpr float kInvPi = glm::one_over_pi<float>();

// Orthonormal frame around a unit normal (Duff et al., "Building an Orthonormal Basis, Revisited",
// JCGT 2017): branch-free and continuous except at n.z = -1 exactly.
struct Frame {
    glm::vec3 t, b, n;

    explicit Frame(glm::vec3 normal) noexcept : n(normal) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float c = n.x * n.y * a;
        t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
        b = {c, sign + n.y * n.y * a, -n.y};
    }
    glm::vec3 toLocal(glm::vec3 v) const noexcept { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
    glm::vec3 toWorld(glm::vec3 v) const noexcept { return v.x * t + v.y * b + v.z * n; }
};

// Uniform point on the unit disc by rejection from the enclosing square: about 1.27 tries, and no
// trigonometry, which is cheaper than the polar or concentric maps. Draws its numbers from `rng`.
template <class Rng>
glm::vec2 uniformDiscRejection(Rng& rng) noexcept {
    for (;;) {
        const float x = 2.0f * rng.next() - 1.0f, y = 2.0f * rng.next() - 1.0f;
        if (x * x + y * y < 1.0f) return {x, y};
    }
}

// Cosine-distributed direction in the local frame (z up), pdf = z / pi: a uniform point on the disc
// lifted to the hemisphere (Malley's method). z > 0 always since the disc point is strictly inside.
template <class Rng>
glm::vec3 cosineHemisphere(Rng& rng) noexcept {
    const glm::vec2 d = uniformDiscRejection(rng);
    return {d.x, d.y, std::sqrt(1.0f - d.x * d.x - d.y * d.y)};
}

// The same from two given numbers (polar map r = sqrt(u1), phi = 2 pi u2), where the caller owns
// the sample dimensions.
inline glm::vec3 cosineHemisphere(float u1, float u2) noexcept {
    const float r = std::sqrt(u1);
    const float phi = 2.0f * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0f - u1)};
}

// Uniform barycentrics (b1, b2) on a triangle; the point is (1-b1-b2) p0 + b1 p1 + b2 p2.
inline glm::vec2 uniformTriangle(float u1, float u2) noexcept {
    const float s = std::sqrt(u1);
    return {1.0f - s, u2 * s};
}

// Veach's power heuristic with exponent 2 for one sample from each of two strategies.
inline float powerHeuristic(float pdfA, float pdfB) noexcept {
    const float a = pdfA * pdfA, b = pdfB * pdfB;
    return a > 0.0f ? a / (a + b) : 0.0f;
}

inline float maxComponent(glm::vec3 v) noexcept { return std::max(v.x, std::max(v.y, v.z)); }

// Moves a surface point off its surface along n, by an amount that grows with the coordinates'
// magnitude so that the new origin is outside the surface's floating-point error interval
// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems
// 2019, ch. 6). Rays then start at t = 0 and no distance epsilon is needed.
inline glm::vec3 offsetRayOrigin(glm::vec3 p, glm::vec3 n) noexcept {
    constexpr float kOrigin = 1.0f / 32.0f;         // below this magnitude use a fixed offset
    constexpr float kFloatScale = 1.0f / 65536.0f;  // fixed offset near the origin, metres
    constexpr float kIntScale = 256.0f;             // offset in units in the last place elsewhere
    const auto shift = [&](float pi, float ni) {
        const auto ulps = static_cast<int32_t>(kIntScale * ni);
        const float moved = std::bit_cast<float>(std::bit_cast<int32_t>(pi) + (pi < 0.0f ? -ulps : ulps));
        return std::abs(pi) < kOrigin ? pi + kFloatScale * ni : moved;
    };
    return {shift(p.x, n.x), shift(p.y, n.y), shift(p.z, n.z)};
}

}  // namespace bounce
