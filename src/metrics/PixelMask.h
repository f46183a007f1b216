#pragma once
// A per-pixel selection (e.g. "pixels that see the dark room" in the two-rooms light-leak scene).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bounce {

class PixelMask {
public:
    PixelMask() = default;
    PixelMask(int width, int height, bool fill = false)
        : m_width(width), m_height(height), m_inside(static_cast<size_t>(width) * height, fill ? 1 : 0) {}

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }
    bool inside(int x, int y) const { return m_inside[static_cast<size_t>(y) * m_width + x] != 0; }
    bool inside(size_t index) const { return m_inside[index] != 0; }
    void set(int x, int y, bool value) { m_inside[static_cast<size_t>(y) * m_width + x] = value ? 1 : 0; }
    size_t count() const;

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<std::uint8_t> m_inside;  // not vector<bool>: plain bytes index and copy predictably
};

}  // namespace bounce
