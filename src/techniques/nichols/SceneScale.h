#pragma once
// Lengths of the Nichols family that the thesis leaves open and that scale with the scene (issue 30:
// "defaults that depend on scene scale derive from the scene bounds and are printed in the run record").
// A setting of 0 means "derived": a fraction of the diagonal of the scene's bounds at time 0, chosen so
// the built-in cornell-box (diagonal 0.96 m) keeps about the metric default it had before.
#include "scene/Scene.h"

#include <glm/glm.hpp>

namespace bounce::nichols {

// Eq. 3.2's r^2 clamp (formFactor=point of rsm and multires-splat): 0.05 of the diagonal (0.048 m on
// cornell-box; 0.05 m was the metric default; 1.25 m on the 25 m courtyard).
inline constexpr float kMinDistanceDiagonalFraction = 0.05f;
// rsm-splat's fixed splat radius: 0.3 of the diagonal (0.29 m on cornell-box, 0.3 m before).
inline constexpr float kSplatRadiusDiagonalFraction = 0.3f;

inline float sceneDiagonal(const Scene& scene) {
    glm::vec3 lo, hi;
    scene.bounds(0.0f, lo, hi);
    return glm::length(hi - lo);
}

// `setting` when positive, else `fraction` of the scene's diagonal.
inline float sceneLength(const Scene& scene, float setting, float fraction) {
    return setting > 0.0f ? setting : fraction * sceneDiagonal(scene);
}

}  // namespace bounce::nichols
