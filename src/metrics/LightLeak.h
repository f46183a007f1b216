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

}  // namespace bounce
