#pragma once
// Base-colour texture lookup, the convention every renderer in bounce shares (docs/reference.md):
// uv (0, 0) is the top-left corner of the image as stored in TextureImage (row 0, the first row of
// the file); u grows to the right, v grows down the rows. Texel (i, j) has its centre at
// ((i + 0.5) / width, (j + 0.5) / height). Filtering is bilinear with repeat wrapping on both axes,
// which is what OpenGL does for an image uploaded first row first with GL_REPEAT and GL_LINEAR.
#include "core/Image.h"

#include <glm/vec2.hpp>

namespace bounce {

glm::vec3 lookupBilinearRepeat(const Image& image, glm::vec2 uv) noexcept;

}  // namespace bounce
