#pragma once
// Two-band spherical harmonics as Rauwendaal 2013 stores radiance per voxel (section 5.1.3) and the
// SH mipmap of section 5.3.3 (Eq. 5.9), GL-free. The basis is the thesis *code's* (Fig. B.3), real
// SH with the Condon-Shortley phase, coefficient order i = l(l+1)+m:
//   (Y00, Y1-1, Y10, Y11)(d) = (0.2820947918, -0.488602512 d.y, 0.488602512 d.z, -0.488602512 d.x).
// It is orthonormal, so projecting f gives c_i = integral f Y_i and evaluating is dot(c, Y(d)). The
// printed Eqs. 5.1 / 5.7 use 1 for the DC basis value instead; we do not (spec 2.8 erratum).
//
// What a voxel's SH function means: V(w) = the radiance the voxel emits in direction w (the sampler
// evaluates it at minus the cone direction, Fig. B.3).
#include <glm/vec3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <optional>

namespace bounce::vct {

inline constexpr float kShY00 = 0.2820947918f;  // 1 / (2 sqrt(pi))
inline constexpr float kShY1 = 0.488602512f;    // sqrt(3) / (2 sqrt(pi))
// Solid angle of a parent face seen from a child centre (Eqs. 5.2-5.3). Near = the parent face
// coplanar with the child's outer face (distance 1 in the thesis's units), far = the opposite one
// (distance 3). The printed Eq. 5.3 swaps the names; these values follow Eq. 5.2 (spec 2.9 erratum).
inline constexpr float kShNearFaceSolidAngle = 3.113997196f;
inline constexpr float kShFarFaceSolidAngle = 1.074793009f;

// shBasis(d) for a unit direction d.
glm::vec4 shBasis(glm::vec3 d);
// sum_i c_i Y_i(d).
float shEvaluate(glm::vec4 c, glm::vec3 d);
// The projection of the clamped cosine max(0, d . w) (d unit) onto shBasis, Eq. 5.8:
// (sqrt(pi)/2, -sqrt(pi/3) d.y, sqrt(pi/3) d.z, -sqrt(pi/3) d.x).
glm::vec4 shCosineLobe(glm::vec3 d);
// The projection of the isotropic radiance L: (L / Y00, 0, 0, 0), which evaluates to L everywhere.
glm::vec4 shProjectConstant(float L);

// The thesis's face integral, integral of <n_face, p> / |p|^3 over the 4 x 4 parent face (child
// centre at the origin, child edge 2, parent edge 4), by the midpoint rule with samplesPerSide^2
// cells: near face at distance 1, far face at distance 3. For the tests.
double faceSolidAngleNumerical(bool nearFace, int samplesPerSide);

// Parent faces 0..5 = +X, -X, +Y, -Y, +Z, -Z; children 0..7 with bit 0 = the +x half, bit 1 = +y,
// bit 2 = +z. In a parent of edge 4 centred at the origin, child c is centred at (+-1, +-1, +-1).
glm::vec3 faceNormal(int face);
// The unit vector from the centre of child `child` to the centre of parent face `face` (d_face of
// Fig. 5.9), e.g. (-1, 1, 1)/sqrt(3) for face -X of child 0 and (3, 1, 1)/sqrt(11) for face +X.
glm::vec3 childFaceDirection(int child, int face);
// True when the face lies on the child's side of the parent (the child's outer face is part of it).
bool isNearFace(int child, int face);

struct ShRgb {
    glm::vec4 r{0.0f}, g{0.0f}, b{0.0f};
};
glm::vec3 shEvaluateRgb(const ShRgb& c, glm::vec3 d);
ShRgb shProjectConstantRgb(glm::vec3 radiance);

// Eq. 5.9: each child's function is projected onto the parent's 6 faces (flux through face f
// ~ Omega_f * V_child(d_f)), each face re-emits as a clamped-cosine lobe around d_f, the lobes are
// summed and the sum is divided by 8. The coefficients are premultiplied by opacity, as the GPU stores
// them (passes.glsl): an empty optional is an empty child (zero); the thesis averages straight
// coefficients over the active children instead, which equals this times 8 / #active at level 1.
// With divideByPi (default) the result is divided by pi, the clamped-cosine integral, which makes 8
// identical isotropic children of radiance L give a parent of radiance L; without it (the literal
// Eq. 5.9) every level multiplies radiance by pi (spec 2.9 inference).
ShRgb shMipParent(const std::array<std::optional<ShRgb>, 8>& children, bool divideByPi = true);

// Eq. 5.9's per-child term is linear in the child's coefficients V: sum over the six faces of
// Omega_f <SH(d_f), V> SH_cos(d_f) = M_child V with M_child = sum_f Omega_f SH_cos(d_f) SH(d_f)^T
// (glm column-major). The GPU mip multiplies by these eight matrices.
glm::mat4 shMipChildMatrix(int child);

}  // namespace bounce::vct
