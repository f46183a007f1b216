#pragma once
// Light-leak score of the `two-rooms` scene (shared/specs/analytic-tests.md): the mean luminance of
// the dark room's visible pixels over the mean luminance of the lit room's. A leak-free renderer
// scores 0; the score is a ratio, so it does not depend on exposure.
#include "core/Error.h"
#include "core/Image.h"
#include "metrics/PixelMask.h"

namespace bounce {

// Fails when a mask's size differs from the image's, a mask is empty, or the lit room is black.
// Luminance is the Rec. 709 luminance of the linear image.
Expected<double> lightLeakScore(const Image& radiance, const PixelMask& darkRoom, const PixelMask& litRoom);

// The rooms of `two-rooms` from an image of world positions (a G-buffer's): the dark room is x >
// wallHalfThickness, the lit room x < -wallHalfThickness (the shared wall is x in [-h, h]); pixels at
// the origin (no surface) belong to neither.
struct TwoRoomsMasks {
    PixelMask dark, lit;
};
TwoRoomsMasks twoRoomsMasks(const Image& worldPositions, float wallHalfThickness);

// Pixels whose world position (RGB of `worldPositions`) lies strictly inside the box lo..hi: a
// scene's declared leak regions (scene/Scene.h LeakRegions) as masks. With `covered`, only its
// pixels count: a G-buffer stores position 0 where no surface is, and a box may contain the origin.
PixelMask boxMask(const Image& worldPositions, const glm::vec3& lo, const glm::vec3& hi, const PixelMask* covered = nullptr);

}  // namespace bounce
