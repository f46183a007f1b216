#include "metrics/ErrorMap.h"

#include "core/Check.h"

#include <algorithm>
#include <cmath>

namespace bounce {

double ErrorMap::mean() const {
    if (m_values.empty()) return 0.0;
    double sum = 0.0;
    for (float v : m_values) sum += v;
    return sum / static_cast<double>(m_values.size());
}

float ErrorMap::minValue() const {
    if (m_values.empty()) return 0.0f;
    return *std::min_element(m_values.begin(), m_values.end());
}

float ErrorMap::maxValue() const {
    if (m_values.empty()) return 0.0f;
    return *std::max_element(m_values.begin(), m_values.end());
}

float ErrorMap::percentile(double fraction) const {
    BOUNCE_CHECK(fraction >= 0.0 && fraction <= 1.0, "percentile fraction {} outside [0, 1]", fraction);
    if (m_values.empty()) return 0.0f;
    std::vector<float> sorted = m_values;
    const double position = fraction * static_cast<double>(sorted.size() - 1);
    const size_t below = static_cast<size_t>(std::floor(position));
    const size_t above = std::min(below + 1, sorted.size() - 1);
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(below), sorted.end());
    const float low = sorted[below];
    // After nth_element everything past `below` is >= low; the next order statistic is their minimum.
    const float high = above == below ? low
                                      : *std::min_element(sorted.begin() + static_cast<std::ptrdiff_t>(above), sorted.end());
    const double t = position - static_cast<double>(below);
    return static_cast<float>(low + t * (high - low));
}

}  // namespace bounce
