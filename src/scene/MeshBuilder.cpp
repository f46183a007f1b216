#include "scene/MeshBuilder.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace bounce {

uint32_t MeshBuilder::vertex(glm::vec3 p, glm::vec3 n, glm::vec2 uv) {
    if (!m_countOnly) {
        m_mesh.positions.push_back(p);
        m_mesh.normals.push_back(n);
        m_mesh.uvs.push_back(uv);
    }
    return m_vertexCount++;
}

void MeshBuilder::indices(uint32_t a, uint32_t b, uint32_t c) {
    ++m_triangleCount;
    if (!m_countOnly) m_mesh.indices.insert(m_mesh.indices.end(), {a, b, c});
}

void MeshBuilder::triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 front) {
    glm::vec3 n = glm::cross(b - a, c - a);
    if (glm::dot(n, front) < 0.0f) {
        std::swap(b, c);
        n = -n;
    }
    n = glm::normalize(n);
    const uint32_t i0 = vertex(a, n, {0, 0}), i1 = vertex(b, n, {1, 0}), i2 = vertex(c, n, {0, 1});
    indices(i0, i1, i2);
}

void MeshBuilder::quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 front, int nu, int nv) {
    // The measured Cornell quads are not exactly planar or rectangular, so interpolate bilinearly.
    glm::vec3 n = glm::cross(b - a, d - a) + glm::cross(d - c, b - c);
    const bool flip = glm::dot(n, front) < 0.0f;
    n = glm::normalize(flip ? -n : n);
    const uint32_t first = m_vertexCount;
    for (int j = 0; j <= nv; ++j) {
        const float v = static_cast<float>(j) / static_cast<float>(nv);
        for (int i = 0; i <= nu; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(nu);
            const glm::vec3 p = glm::mix(glm::mix(a, b, u), glm::mix(d, c, u), v);
            vertex(p, n, {u, v});
        }
    }
    const auto at = [&](int i, int j) { return first + static_cast<uint32_t>(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            uint32_t q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            // Counter-clockwise around `n` is a->b->c->d when cross(b-a, d-a) agrees with n.
            if (flip) std::swap(q[1], q[3]);
            indices(q[0], q[1], q[2]);
            indices(q[0], q[2], q[3]);
        }
    }
}

void MeshBuilder::box(const glm::vec3 bottom[4], const glm::vec3 top[4], bool outward, int subdivisions) {
    glm::vec3 centre(0.0f);
    for (int i = 0; i < 4; ++i) centre += bottom[i] + top[i];
    centre /= 8.0f;
    const float sign = outward ? 1.0f : -1.0f;
    const auto face = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        const glm::vec3 mid = 0.25f * (a + b + c + d);
        quad(a, b, c, d, sign * (mid - centre), subdivisions, subdivisions);
    };
    face(bottom[0], bottom[1], bottom[2], bottom[3]);
    face(top[0], top[1], top[2], top[3]);
    for (int i = 0; i < 4; ++i) {
        const int k = (i + 1) % 4;
        face(bottom[i], bottom[k], top[k], top[i]);
    }
}

void MeshBuilder::axisBox(glm::vec3 lo, glm::vec3 hi, bool outward, int subdivisions) {
    const glm::vec3 bottom[4] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}};
    const glm::vec3 top[4] = {{lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    box(bottom, top, outward, subdivisions);
}

void MeshBuilder::cylinder(glm::vec3 base, float radius, float height, int segments, int rings) {
    constexpr float kTwoPi = glm::two_pi<float>();
    const uint32_t first = m_vertexCount;
    for (int j = 0; j <= rings; ++j) {
        const float v = static_cast<float>(j) / static_cast<float>(rings);
        for (int i = 0; i <= segments; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(segments);
            const glm::vec3 n(std::cos(kTwoPi * u), 0.0f, -std::sin(kTwoPi * u));
            vertex(base + radius * n + glm::vec3(0.0f, v * height, 0.0f), n, {u, v});
        }
    }
    const auto at = [&](int i, int j) { return first + static_cast<uint32_t>(j * (segments + 1) + i); };
    for (int j = 0; j < rings; ++j) {
        for (int i = 0; i < segments; ++i) {
            // With n = (cos, 0, -sin), increasing u turns counter-clockwise seen from outside.
            indices(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            indices(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
}

void MeshBuilder::surface(int nu, int nv, const std::function<glm::vec3(float, float)>& p, glm::vec3 front) {
    // Central-difference step in parameter space, small against any cell.
    constexpr float kStep = 1e-3f;
    const glm::vec3 centreNormal = glm::cross(p(0.5f + kStep, 0.5f) - p(0.5f - kStep, 0.5f),
                                              p(0.5f, 0.5f + kStep) - p(0.5f, 0.5f - kStep));
    const bool flip = glm::dot(centreNormal, front) < 0.0f;
    const uint32_t first = m_vertexCount;
    for (int j = 0; j <= nv; ++j) {
        const float v = static_cast<float>(j) / static_cast<float>(nv);
        for (int i = 0; i <= nu; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(nu);
            glm::vec3 n(0.0f);
            if (!m_countOnly) {
                n = glm::cross(p(u + kStep, v) - p(u - kStep, v), p(u, v + kStep) - p(u, v - kStep));
                n = glm::normalize(flip ? -n : n);
            }
            vertex(m_countOnly ? glm::vec3(0.0f) : p(u, v), n, {u, v});
        }
    }
    const auto at = [&](int i, int j) { return first + static_cast<uint32_t>(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            uint32_t q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            if (flip) std::swap(q[1], q[3]);
            indices(q[0], q[1], q[2]);
            indices(q[0], q[2], q[3]);
        }
    }
}

void MeshBuilder::disk(glm::vec3 centre, float radius, glm::vec3 front, int segments) {
    // Any unit vector perpendicular to `front` starts the fan.
    const glm::vec3 helper = std::abs(front.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 t = glm::normalize(glm::cross(helper, front));
    const glm::vec3 b = glm::cross(front, t);
    const uint32_t c = vertex(centre, front, {0.5f, 0.5f});
    const uint32_t first = m_vertexCount;
    for (int i = 0; i <= segments; ++i) {
        const float a = glm::two_pi<float>() * static_cast<float>(i) / static_cast<float>(segments);
        vertex(centre + radius * (std::cos(a) * t + std::sin(a) * b), front,
               {0.5f + 0.5f * std::cos(a), 0.5f + 0.5f * std::sin(a)});
    }
    // t -> b is counter-clockwise about front = cross(t, b).
    for (int i = 0; i < segments; ++i) indices(c, first + static_cast<uint32_t>(i), first + static_cast<uint32_t>(i + 1));
}

void MeshBuilder::archBay(glm::vec3 centre, glm::vec3 along, glm::vec3 across, float halfSpan, float innerRadius,
                          float depth, int segments) {
    constexpr float kPi = glm::pi<float>();
    segments = std::max(4, (segments + 3) / 4 * 4);
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 half = 0.5f * depth * across;
    for (int i = 0; i < segments; ++i) {
        const float a0 = kPi * static_cast<float>(i) / static_cast<float>(segments);
        const float a1 = kPi * static_cast<float>(i + 1) / static_cast<float>(segments);
        const glm::vec3 r0 = std::cos(a0) * along + std::sin(a0) * up;
        const glm::vec3 r1 = std::cos(a1) * along + std::sin(a1) * up;
        // The ray at angle a leaves the half-square [-1, 1] x [0, 1] (in halfSpan units) at r / max(|cos|, sin).
        const glm::vec3 s0 = r0 / std::max(std::abs(std::cos(a0)), std::sin(a0));
        const glm::vec3 s1 = r1 / std::max(std::abs(std::cos(a1)), std::sin(a1));
        const glm::vec3 in0 = centre + innerRadius * r0, in1 = centre + innerRadius * r1;
        const glm::vec3 sq0 = centre + halfSpan * s0, sq1 = centre + halfSpan * s1;
        const glm::vec3 mid = glm::normalize(r0 + r1);
        quad(in0 - half, in1 - half, in1 + half, in0 + half, -mid);  // intrados faces the opening
        quad(in0 + half, in1 + half, sq1 + half, sq0 + half, across);
        quad(in0 - half, in1 - half, sq1 - half, sq0 - half, -across);
    }
    // Soffits between the opening and the bay's ends, on the springing line: the column under each end is
    // round and does not cover the bay's square corners.
    for (float side : {-1.0f, 1.0f}) {
        const glm::vec3 in = centre + side * innerRadius * along, out = centre + side * halfSpan * along;
        quad(in - half, out - half, out + half, in + half, -up);
    }
    const glm::vec3 top = centre + halfSpan * up;
    quad(top - halfSpan * along - half, top + halfSpan * along - half, top + halfSpan * along + half,
         top - halfSpan * along + half, up);
}

}  // namespace bounce
