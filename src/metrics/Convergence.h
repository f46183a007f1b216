#pragma once
// Convergence latency of an incremental technique after an event (docs/metrics.md "Temporal metrics"):
// how many frames after a light or object moved the technique's image needs to come within a
// threshold of the image it settles on, and stay there.
#include "core/Image.h"

#include <optional>
#include <vector>

namespace bounce {

struct ConvergenceLatency {
    // relativeRmsError(frames[i], settled) for i >= event; NaN before the event (not measured there).
    std::vector<double> errorToSettled;
    // The frame before the last is within the threshold of the last: the sequence has settled, and
    // its last frame is the settled image S. False when there are fewer than two frames from the event on.
    bool settled = false;
    // The smallest k >= 0 with errorToSettled < threshold on every frame from event + k to the end;
    // empty when not settled.
    std::optional<int> frames;
};

// `frames` are consecutive frames of one run, `event` the index of the first frame that shows the
// scene after the move; S is the last frame. Requires event < frames.size() and equal sizes.
ConvergenceLatency convergenceLatency(const std::vector<Image>& frames, size_t event, double threshold);

}  // namespace bounce
