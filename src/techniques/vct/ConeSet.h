#pragma once
// Cone parameters of Rauwendaal 2013 chapter 6, GL-free: the six 60-degree diffuse / AO cones of
// Eq. 6.8 with their cosine weights (Eq. 6.9), the cone ratio of section 6.1, the self-intersection
// start distance of Eq. 6.2 and the voxel extent |v| it uses.
#include "techniques/vct/VoxelOverlap.h"

#include <glm/vec3.hpp>

#include <array>

namespace bounce::vct {

// Eq. 6.8, in a frame whose normal is +Y: the central cone along the normal, five cones 60 degrees
// from it (cos = 0.5) at azimuths 0, 72, ..., 288 degrees measured from +Z towards +X. Computed
// exactly (sin 60 * sin / cos of 72k degrees); the thesis prints the same values to 6 decimals.
inline constexpr float kSin60 = 0.86602540378443865f;
inline constexpr std::array<glm::vec3, 6> kDiffuseConeDirections = {
    glm::vec3(0.0f, 1.0f, 0.0f),
    glm::vec3(0.0f, 0.5f, kSin60),
    glm::vec3(kSin60 * 0.95105651629515357f, 0.5f, kSin60 * 0.30901699437494742f),
    glm::vec3(kSin60 * 0.58778525229247313f, 0.5f, kSin60 * -0.80901699437494742f),
    glm::vec3(kSin60 * -0.58778525229247313f, 0.5f, kSin60 * -0.80901699437494742f),
    glm::vec3(kSin60 * -0.95105651629515357f, 0.5f, kSin60 * 0.30901699437494742f),
};
// Eq. 6.9: W_k = integral over the cone's cell of (n . w) dw: pi/4 for the central cap
// (theta < 30 degrees), 3 pi / 20 for each 72-degree wedge of 30..90 degrees. They sum to pi
// (Eq. 6.10; section 6.4's "sum to 2 pi" is an erratum), so L = rho/pi sum W_k L_k and
// AO = 1/pi sum W_k V_k.
inline constexpr float kDiffuseConeCentralWeight = 0.78539816339744831f;  // pi / 4
inline constexpr float kDiffuseConeRingWeight = 0.47123889803846897f;     // 3 pi / 20
inline constexpr std::array<float, 6> kDiffuseConeWeights = {kDiffuseConeCentralWeight, kDiffuseConeRingWeight,
                                                             kDiffuseConeRingWeight,    kDiffuseConeRingWeight,
                                                             kDiffuseConeRingWeight,    kDiffuseConeRingWeight};
inline constexpr float kDiffuseConeAperture = 1.04719755119659775f;  // 60 degrees, full aperture

// Section 6.1: successive sample spheres touch when r_{i+1} = (d_i + r_i) * coneRatio with
// coneRatio = sin(theta/2) / (1 - sin(theta/2)), theta the full aperture (1 at 60 degrees).
float coneRatio(float apertureRadians);

// Eq. 6.2 as intended (spec 2.12 inference): d_s = clamp(fMin |v| / (n . w), fMin |v|, fMax |v|),
// with n the geometric normal and w the cone direction; n . w <= fMin / fMax (including grazing and
// back-facing cones) gives fMax |v|. Requires 0 < fMin <= fMax.
float coneStartDistance(float nDotOmega, float voxelExtent, float fMin, float fMax);

// |v| of section 6.1.1: the voxel diagonal for conservative (26-separating) voxelization, the
// longest side for thin (6-separating) voxelization (the distance needed to leave the diamond).
float voxelExtent(Separability s, glm::vec3 voxelSize);

}  // namespace bounce::vct
