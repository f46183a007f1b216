#pragma once
// A scalar value per pixel (an error, a similarity, a mask weight), row-major with row 0 at the
// top like Image. The metrics layer returns these so heat maps and pooled numbers share one source.
#include <cstddef>
#include <vector>

namespace bounce {

class ErrorMap {
public:
    ErrorMap() = default;
    ErrorMap(int width, int height, float fill = 0.0f)
        : m_width(width), m_height(height), m_values(static_cast<size_t>(width) * height, fill) {}

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }
    size_t pixelCount() const noexcept { return m_values.size(); }
    bool empty() const noexcept { return m_values.empty(); }

    float& at(int x, int y) { return m_values[static_cast<size_t>(y) * m_width + x]; }
    float at(int x, int y) const { return m_values[static_cast<size_t>(y) * m_width + x]; }
    std::vector<float>& values() noexcept { return m_values; }
    const std::vector<float>& values() const noexcept { return m_values; }

    // Pooled statistics, accumulated in double. All of them are 0 for an empty map.
    double mean() const;
    float minValue() const;
    float maxValue() const;
    // Linearly interpolated percentile, fraction in [0, 1] (0.5 is the median).
    float percentile(double fraction) const;

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<float> m_values;
};

}  // namespace bounce
