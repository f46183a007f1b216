#include "metrics/PixelMask.h"

#include <algorithm>

namespace bounce {

size_t PixelMask::count() const {
    return static_cast<size_t>(std::count_if(m_inside.begin(), m_inside.end(), [](std::uint8_t v) { return v != 0; }));
}

}  // namespace bounce
