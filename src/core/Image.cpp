#include "core/Image.h"

#include <algorithm>

namespace bounce {
void Image::flipVertical() {
    for (int y = 0; y < m_height / 2; ++y) {
        auto top = m_pixels.begin() + static_cast<ptrdiff_t>(y) * m_width;
        auto bottom = m_pixels.begin() + static_cast<ptrdiff_t>(m_height - 1 - y) * m_width;
        std::swap_ranges(top, top + m_width, bottom);
    }
}
}  // namespace bounce
