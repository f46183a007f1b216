#pragma once
// Temporal flicker of a frame sequence from a still camera (shared/specs/analytic-tests.md):
//   flicker = mean over frame pairs and pixels of |Y_t - Y_(t-1)|  /  mean luminance over all frames,
// with Y the Rec. 709 luminance of the linear frame. 0 for a static deterministic renderer; frames
// are fed one at a time so a renderer need not keep the sequence.
#include "core/Error.h"
#include "core/Image.h"

#include <span>
#include <vector>

namespace bounce {

class FlickerMeter {
public:
    // Fails if the frame's size differs from the first frame's or it holds non-finite values.
    Expected<void> addFrame(const Image& frame);

    int frameCount() const noexcept { return m_frames; }
    // Fails with fewer than two frames, or when the frames are black but still change (a
    // negative-valued input; a black static sequence gives 0).
    Expected<double> flicker() const;

private:
    std::vector<float> m_previousLuminance;
    int m_width = 0, m_height = 0, m_frames = 0;
    double m_absDifferenceSum = 0.0;  // over pairs and pixels
    double m_luminanceSum = 0.0;      // over frames and pixels
};

// Convenience over a whole sequence.
Expected<double> flicker(std::span<const Image> frames);

}  // namespace bounce
