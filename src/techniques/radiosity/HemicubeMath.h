#pragma once
// Hemicube geometry and form factors (Cohen & Greenberg 1985, as used by van de Hoef 2013 sec. 2.2.2
// and 4.2), GL-free. The same conventions are written in shaders/techniques/radiosity/hemicube.glsl;
// tests/unit/RadiosityMathTest.cpp checks both against the analytic values.
//
// A unit hemicube around normal N with tangent T and B = cross(T, N): face 0 (top) looks along N,
// faces 1-4 along T, -T, B, -B with N up. Face f has axis A_f, up U_f and right R_f = cross(A_f, U_f);
// a direction d projects to (u, v) = (d.R_f, d.U_f) / (d.A_f). The top face covers u, v in [-1, 1]
// on R x R pixels, a side face u in [-1, 1], v in [0, 1] on R x R/2 pixels (rows [0, R/2) of its
// layer). Delta form factors (the precomputed "multiplier map"):
//   top:  dF = dA / (pi (u^2 + v^2 + 1)^2)        side: dF = v dA / (pi (u^2 + v^2 + 1)^2)
// with dA = (2/R)^2 the pixel's area on the unit cube; they sum to 1 over the hemicube.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace bounce::radiosity {

constexpr int kHemicubeFaces = 5;

struct HemicubeFrame {
    glm::vec3 tangent, bitangent, normal;  // T, B = cross(T, N), N
    glm::vec3 axis(int face) const;
    glm::vec3 up(int face) const;
    glm::vec3 right(int face) const;
};

// A frame around unit n; `angle` (radians) rotates the tangent about n (the thesis's random
// per-position rotation).
HemicubeFrame hemicubeFrame(glm::vec3 n, float angle);
// The per-position angle of the random rotation: a hash of the position, in [0, 2 pi).
float rotationAngle(glm::vec3 position);

// Delta form factors of every pixel, layer-major: [face][row][column] of R x R (side faces' rows
// >= R/2 are 0). R must be even.
std::vector<float> deltaFormFactors(int resolution);

// The face and continuous pixel position (x in [0, R], y in [0, R] or [0, R/2]) of direction d;
// false below the horizon (d.N <= 0).
bool projectToHemicube(const HemicubeFrame& frame, glm::vec3 d, int resolution, int& face, glm::vec2& pixel);

// Disk-approximation form factor (Wallace et al. 1989; thesis Eq. 2.2.7) from a shooter of area
// `shooterArea` sampled at `samples` points (each standing for area A/m) to a receiving point:
//   F = A (1/m) sum_k cos(phi_e,k) cos(phi_s,k) / (pi r_k^2 + A/m), back-facing samples contribute 0.
float diskFormFactor(glm::vec3 receiver, glm::vec3 receiverNormal, const std::vector<glm::vec3>& samples,
                     glm::vec3 shooterNormal, float shooterArea);

// Analytic form factors for tests (Howell's catalogue, configurations B-12 and C-41):
// a differential element to a parallel coaxial disk of radius r at distance h: r^2 / (h^2 + r^2);
float pointToDiskFormFactor(float radius, float distance);
// disk radius r1 to a parallel coaxial disk radius r2 at distance h: (X - sqrt(X^2 - 4 (r2/r1)^2)) / 2,
// X = 1 + (1 + (r2/h)^2) / (r1/h)^2.
float diskToDiskFormFactor(float r1, float r2, float distance);

}  // namespace bounce::radiosity
