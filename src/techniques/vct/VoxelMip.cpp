// Rauwendaal 2013 section 5.3.1 / 5.3.2 mip filters and Fig. B.1's RGBA8 running average, on the CPU.
#include "techniques/vct/VoxelMip.h"

namespace bounce::vct {

namespace {
float clamp255(float x) { return x >= 0.0f ? (x <= 255.0f ? x : 255.0f) : 0.0f; }
}  // namespace

glm::vec4 isotropicMipParent(const std::array<glm::vec4, 8>& children) {
    glm::vec4 sum(0.0f);
    for (const glm::vec4& c : children) sum += c;
    return sum / 8.0f;
}

int anisoNearChild(int face, int pairBits) {
    int bit = 1 << (face / 2);
    bool positiveFace = face % 2 == 0;
    // Looking along +axis the ray meets the -axis half first.
    return positiveFace ? (pairBits & ~bit) : (pairBits | bit);
}

AnisoVoxel anisotropicMipParent(const std::array<AnisoVoxel, 8>& children) {
    AnisoVoxel parent;
    for (int face = 0; face < 6; ++face) {
        int bit = 1 << (face / 2);
        glm::vec4 sum(0.0f);
        for (int pair = 0; pair < 8; ++pair) {
            if (pair & bit) continue;  // one representative per pair: the face-axis bit clear
            glm::vec4 n = children[anisoNearChild(face, pair)][face];
            glm::vec4 f = children[anisoNearChild(face, pair) ^ bit][face];
            sum += n + (1.0f - n.a) * f;
        }
        parent[face] = sum / 4.0f;
    }
    return parent;
}

AnisoVoxel anisoFromIsotropic(glm::vec4 v) { return AnisoVoxel{v, v, v, v, v, v}; }

uint32_t packRgbCount(glm::vec4 v) {
    uint32_t r = uint32_t(clamp255(v.r) + 0.5f), g = uint32_t(clamp255(v.g) + 0.5f), b = uint32_t(clamp255(v.b) + 0.5f);
    uint32_t a = uint32_t(clamp255(v.a));
    // Rounding 255 + 0.5 gives 255 (uint conversion truncates 255.5).
    return r | (g << 8) | (b << 16) | (a << 24);
}

glm::vec4 unpackRgbCount(uint32_t v) {
    return glm::vec4(float(v & 0xFFu), float((v >> 8) & 0xFFu), float((v >> 16) & 0xFFu), float((v >> 24) & 0xFFu));
}

uint32_t averageRgba8(uint32_t prev, glm::vec3 next) {
    // Fig. B.1's loop body. prev == 0 is the first write: count 0, so the average is `next`.
    glm::vec4 c = unpackRgbCount(prev);
    float count = c.a;
    glm::vec3 average = (glm::vec3(c) / 255.0f * count + next) / (count + 1.0f);
    float nextCount = count + 1.0f < 255.0f ? count + 1.0f : 255.0f;
    return packRgbCount(glm::vec4(average * 255.0f, nextCount));
}

}  // namespace bounce::vct
