#include "metrics/FlickerMeter.h"

#include "core/ImageIo.h"

#include <cmath>

namespace bounce {

Expected<void> FlickerMeter::addFrame(const Image& frame) {
    if (frame.empty()) return makeError("flicker: frame {} is empty", m_frames);
    if (m_frames > 0 && (frame.width() != m_width || frame.height() != m_height))
        return makeError("flicker: frame {} is {}x{}, earlier frames are {}x{}", m_frames, frame.width(), frame.height(),
                         m_width, m_height);
    BOUNCE_TRY_VOID(checkFinite(frame, fmt::format("flicker: frame {}", m_frames)));
    if (m_frames == 0) {
        m_width = frame.width();
        m_height = frame.height();
        m_previousLuminance.resize(frame.pixelCount());
    }
    for (size_t i = 0; i < frame.pixelCount(); ++i) {
        const float y = luminance(frame.data()[i]);
        if (m_frames > 0) m_absDifferenceSum += std::abs(static_cast<double>(y) - m_previousLuminance[i]);
        m_luminanceSum += y;
        m_previousLuminance[i] = y;
    }
    ++m_frames;
    return {};
}

Expected<double> FlickerMeter::flicker() const {
    if (m_frames < 2) return makeError("flicker: needs at least 2 frames, got {}", m_frames);
    const double pixels = static_cast<double>(m_previousLuminance.size());
    const double meanAbsDifference = m_absDifferenceSum / (pixels * (m_frames - 1));
    const double meanLuminance = m_luminanceSum / (pixels * m_frames);
    if (meanAbsDifference == 0.0) return 0.0;
    if (!(meanLuminance > 0.0))
        return makeError("flicker: frames change but their mean luminance is {} (not positive)", meanLuminance);
    return meanAbsDifference / meanLuminance;
}

Expected<double> flicker(std::span<const Image> frames) {
    FlickerMeter meter;
    for (const Image& frame : frames) BOUNCE_TRY_VOID(meter.addFrame(frame));
    return meter.flicker();
}

}  // namespace bounce
