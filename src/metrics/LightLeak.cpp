#include "metrics/LightLeak.h"

#include "core/Check.h"

#include <glm/vector_relational.hpp>

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

TwoRoomsMasks twoRoomsMasks(const Image& worldPositions, float wallHalfThickness) {
    TwoRoomsMasks m{PixelMask(worldPositions.width(), worldPositions.height()), PixelMask(worldPositions.width(), worldPositions.height())};
    for (int y = 0; y < worldPositions.height(); ++y)
        for (int x = 0; x < worldPositions.width(); ++x) {
            const float px = worldPositions.at(x, y).r;
            m.dark.set(x, y, px > wallHalfThickness);
            m.lit.set(x, y, px < -wallHalfThickness);
        }
    return m;
}

PixelMask boxMask(const Image& worldPositions, const glm::vec3& lo, const glm::vec3& hi, const PixelMask* covered) {
    PixelMask m(worldPositions.width(), worldPositions.height());
    BOUNCE_CHECK(!covered || (covered->width() == m.width() && covered->height() == m.height()), "coverage mask of another size");
    for (int y = 0; y < worldPositions.height(); ++y)
        for (int x = 0; x < worldPositions.width(); ++x) {
            const auto p = worldPositions.at(x, y);
            m.set(x, y, (!covered || covered->inside(x, y)) && glm::all(glm::greaterThan(p, lo)) && glm::all(glm::lessThan(p, hi)));
        }
    return m;
}

}  // namespace bounce
