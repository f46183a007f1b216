#include "reference/TextureLookup.h"

#include <cmath>

namespace bounce {

namespace {
int wrap(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
}
}  // namespace

glm::vec3 lookupBilinearRepeat(const Image& image, glm::vec2 uv) noexcept {
    const int w = image.width(), h = image.height();
    // Reduce to one period first so that large uv keep their fractional precision.
    const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
    const float x = u * static_cast<float>(w) - 0.5f;
    const float y = v * static_cast<float>(h) - 0.5f;
    const float x0f = std::floor(x), y0f = std::floor(y);
    const float fx = x - x0f, fy = y - y0f;
    const int x0 = wrap(static_cast<int>(x0f), w), x1 = wrap(static_cast<int>(x0f) + 1, w);
    const int y0 = wrap(static_cast<int>(y0f), h), y1 = wrap(static_cast<int>(y0f) + 1, h);
    const glm::vec3 top = (1.0f - fx) * image.at(x0, y0) + fx * image.at(x1, y0);
    const glm::vec3 bottom = (1.0f - fx) * image.at(x0, y1) + fx * image.at(x1, y1);
    return (1.0f - fy) * top + fy * bottom;
}

}  // namespace bounce
