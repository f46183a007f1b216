#include "metrics/Convergence.h"

#include "core/Check.h"
#include "metrics/ErrorMetrics.h"

#include <cmath>
#include <limits>

namespace bounce {

ConvergenceLatency convergenceLatency(const std::vector<Image>& frames, size_t event, double threshold) {
    BOUNCE_CHECK(event < frames.size(), "event frame {} of a run of {} frames", event, frames.size());
    ConvergenceLatency out;
    out.errorToSettled.assign(frames.size(), std::numeric_limits<double>::quiet_NaN());
    const Image& settled = frames.back();
    // Backwards from the last frame: the latency ends where the error first rises to the threshold.
    std::optional<int> latency;
    bool below = true;
    for (size_t i = frames.size(); i-- > event;) {
        const double e = relativeRmsError(frames[i], settled);
        out.errorToSettled[i] = e;
        below = below && e < threshold;  // NaN and +inf (black S, frame not black) are not below
        if (below) latency = static_cast<int>(i - event);
    }
    // The last frame is S itself (error 0); whether the run settled is decided by the one before.
    out.settled = frames.size() - event >= 2 && out.errorToSettled[frames.size() - 2] < threshold;
    if (out.settled) out.frames = latency;
    return out;
}

}  // namespace bounce
