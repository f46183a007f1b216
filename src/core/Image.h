#pragma once
// Linear float RGB image, row-major with row 0 at the top (as written to files).
#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace bounce {

// Largest width or height of an image bounce renders or reads, pixels: GL 4.5's guaranteed texture
// size. A file whose header claims more is refused before any pixel is allocated (a 2 KB EXR could
// otherwise claim gigabytes).
inline constexpr int kMaxImageSide = 16384;

class Image {
public:
    Image() = default;
    Image(int width, int height, glm::vec3 fill = glm::vec3(0.0f))
        : m_width(width), m_height(height), m_pixels(static_cast<size_t>(width) * height, fill) {}

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }
    size_t pixelCount() const noexcept { return m_pixels.size(); }
    bool empty() const noexcept { return m_pixels.empty(); }

    glm::vec3& at(int x, int y) { return m_pixels[static_cast<size_t>(y) * m_width + x]; }
    const glm::vec3& at(int x, int y) const { return m_pixels[static_cast<size_t>(y) * m_width + x]; }
    glm::vec3* data() noexcept { return m_pixels.data(); }
    const glm::vec3* data() const noexcept { return m_pixels.data(); }
    std::vector<glm::vec3>& pixels() noexcept { return m_pixels; }
    const std::vector<glm::vec3>& pixels() const noexcept { return m_pixels; }

    // Flips rows in place (OpenGL reads back bottom row first).
    void flipVertical();

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<glm::vec3> m_pixels;
};

// Rec. 709 / sRGB luminance of linear RGB.
inline float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace bounce
