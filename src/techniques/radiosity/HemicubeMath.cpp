#include "techniques/radiosity/HemicubeMath.h"

#include "core/Check.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>

namespace bounce::radiosity {

glm::vec3 HemicubeFrame::axis(int face) const {
    switch (face) {
        case 0: return normal;
        case 1: return tangent;
        case 2: return -tangent;
        case 3: return bitangent;
        default: return -bitangent;
    }
}
glm::vec3 HemicubeFrame::up(int face) const { return face == 0 ? bitangent : normal; }
glm::vec3 HemicubeFrame::right(int face) const { return glm::cross(axis(face), up(face)); }

HemicubeFrame hemicubeFrame(glm::vec3 n, float angle) {
    // Any perpendicular (Frisvad-style branch on the dominant axis), then the rotation about n.
    const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 t0 = glm::normalize(glm::cross(helper, n));
    const glm::vec3 b0 = glm::cross(n, t0);
    HemicubeFrame f;
    f.normal = n;
    f.tangent = std::cos(angle) * t0 + std::sin(angle) * b0;
    f.bitangent = glm::cross(f.tangent, n);
    return f;
}

float rotationAngle(glm::vec3 p) {
    // The GLSL twin (hemicube.glsl) hashes the same millimetre-quantised coordinates.
    uint32_t h = 2166136261u;
    for (int k = 0; k < 3; ++k) {
        const auto q = static_cast<uint32_t>(static_cast<int32_t>(std::floor(p[k] * 1000.0f)));
        h = (h ^ q) * 16777619u;
        h ^= h >> 15;
    }
    return static_cast<float>(h & 0xFFFFu) / 65536.0f * glm::two_pi<float>();
}

std::vector<float> deltaFormFactors(int r) {
    BOUNCE_CHECK(r >= 2 && r % 2 == 0, "hemicube resolution {} must be even", r);
    std::vector<float> ff(static_cast<size_t>(kHemicubeFaces) * r * r, 0.0f);
    const double pixel = 2.0 / r, dA = pixel * pixel, pi = glm::pi<double>();
    for (int y = 0; y < r; ++y)
        for (int x = 0; x < r; ++x) {
            const double u = -1.0 + (x + 0.5) * pixel, v = -1.0 + (y + 0.5) * pixel;
            const double d = u * u + v * v + 1.0;
            ff[static_cast<size_t>(y) * r + x] = static_cast<float>(dA / (pi * d * d));
        }
    for (int face = 1; face < kHemicubeFaces; ++face)
        for (int y = 0; y < r / 2; ++y)
            for (int x = 0; x < r; ++x) {
                const double u = -1.0 + (x + 0.5) * pixel, v = (y + 0.5) * pixel;
                const double d = u * u + v * v + 1.0;
                ff[(static_cast<size_t>(face) * r + y) * r + x] = static_cast<float>(v * dA / (pi * d * d));
            }
    return ff;
}

bool projectToHemicube(const HemicubeFrame& f, glm::vec3 d, int r, int& face, glm::vec2& pixel) {
    const float x = glm::dot(d, f.tangent), y = glm::dot(d, f.bitangent), z = glm::dot(d, f.normal);
    if (z <= 0.0f) return false;
    if (z >= std::abs(x) && z >= std::abs(y)) face = 0;
    else if (std::abs(x) >= std::abs(y)) face = x > 0.0f ? 1 : 2;
    else face = y > 0.0f ? 3 : 4;
    const float a = glm::dot(d, f.axis(face));
    const float u = glm::dot(d, f.right(face)) / a, v = glm::dot(d, f.up(face)) / a;
    pixel.x = (0.5f * u + 0.5f) * r;
    pixel.y = face == 0 ? (0.5f * v + 0.5f) * r : v * 0.5f * r;
    return true;
}

float diskFormFactor(glm::vec3 e, glm::vec3 ne, const std::vector<glm::vec3>& samples, glm::vec3 ns, float area) {
    const float m = static_cast<float>(samples.size()), pi = glm::pi<float>();
    float sum = 0.0f;
    for (const glm::vec3& y : samples) {
        const glm::vec3 d = e - y;
        const float r2 = glm::dot(d, d);
        const glm::vec3 w = d / std::sqrt(r2);
        const float cs = glm::dot(ns, w), ce = -glm::dot(ne, w);
        if (cs <= 0.0f || ce <= 0.0f) continue;
        sum += cs * ce / (pi * r2 + area / m);
    }
    return area * sum / m;
}

float pointToDiskFormFactor(float radius, float distance) { return radius * radius / (distance * distance + radius * radius); }

float diskToDiskFormFactor(float r1, float r2, float h) {
    const double R1 = r1 / h, R2 = r2 / h;
    const double X = 1.0 + (1.0 + R2 * R2) / (R1 * R1);
    return static_cast<float>(0.5 * (X - std::sqrt(X * X - 4.0 * (R2 / R1) * (R2 / R1))));
}

}  // namespace bounce::radiosity
