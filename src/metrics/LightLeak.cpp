#include "metrics/LightLeak.h"

namespace bounce {
namespace {

Expected<double> meanLuminance(const Image& radiance, const PixelMask& mask, const char* name) {
    if (mask.width() != radiance.width() || mask.height() != radiance.height())
        return makeError("light leak: {} mask is {}x{} but the image is {}x{}", name, mask.width(), mask.height(),
                         radiance.width(), radiance.height());
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < radiance.pixelCount(); ++i)
        if (mask.inside(i)) {
            sum += luminance(radiance.data()[i]);
            ++count;
        }
    if (count == 0) return makeError("light leak: {} mask selects no pixel", name);
    return sum / static_cast<double>(count);
}

}  // namespace

Expected<double> lightLeakScore(const Image& radiance, const PixelMask& darkRoom, const PixelMask& litRoom) {
    BOUNCE_TRY(const double dark, meanLuminance(radiance, darkRoom, "dark-room"));
    BOUNCE_TRY(const double lit, meanLuminance(radiance, litRoom, "lit-room"));
    if (!(lit > 0.0)) return makeError("light leak: the lit room's mean luminance is {} (must be positive)", lit);
    return dark / lit;
}

}  // namespace bounce
