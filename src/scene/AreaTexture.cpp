#include "scene/AreaTexture.h"

#include "core/Check.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace bounce {

size_t areaTextureFrame(const AreaTexture& texture, float t) {
    const size_t n = texture.frames.size();
    if (n <= 1 || !(t > 0.0f)) return 0;
    const double index = std::floor(static_cast<double>(t) * texture.frameRate);
    return static_cast<size_t>(std::fmod(index, static_cast<double>(n)));
}

glm::vec2 bouncingSquareCentre(const AreaTexture& texture, float t) {
    const float half = 0.5f * texture.squareSize;
    const float span = 1.0f - texture.squareSize;  // range of the centre
    glm::vec2 c;
    for (int a = 0; a < 2; ++a) {
        if (!(span > 0.0f)) {
            c[a] = 0.5f;
            continue;
        }
        // Unfold the reflections: position along a line of period 2 * span, folded back.
        const double x = (texture.squareStart[a] - half) + static_cast<double>(texture.squareVelocity[a]) * t;
        double m = std::fmod(x, 2.0 * span);
        if (m < 0.0) m += 2.0 * span;
        if (m > span) m = 2.0 * span - m;
        c[a] = half + static_cast<float>(m);
    }
    return c;
}

Image renderBouncingSquare(const AreaTexture& texture, float t) {
    const int n = texture.resolution;
    BOUNCE_CHECK(n > 0, "bouncing square resolution is positive");
    const glm::vec2 c = bouncingSquareCentre(texture, t);
    const float half = 0.5f * texture.squareSize;
    Image image(n, n);
    for (int y = 0; y < n; ++y) {
        // Row 0 is v = 1 (Scene.h).
        const float v0 = 1.0f - static_cast<float>(y + 1) / n, v1 = 1.0f - static_cast<float>(y) / n;
        const float cv = std::max(0.0f, std::min(v1, c.y + half) - std::max(v0, c.y - half));
        for (int x = 0; x < n; ++x) {
            const float u0 = static_cast<float>(x) / n, u1 = static_cast<float>(x + 1) / n;
            const float cu = std::max(0.0f, std::min(u1, c.x + half) - std::max(u0, c.x - half));
            image.at(x, y) = glm::vec3(cu * cv * static_cast<float>(n) * static_cast<float>(n));
        }
    }
    return image;
}

const Image* areaTextureAt(const Scene& scene, const Light& light, float t, Image& scratch) {
    switch (light.texture.kind) {
        case AreaTexture::Kind::None: return nullptr;
        case AreaTexture::Kind::Images: {
            BOUNCE_CHECK(!light.texture.frames.empty(), "textured area light has frames");
            const uint32_t index = light.texture.frames[areaTextureFrame(light.texture, t)];
            BOUNCE_CHECK(index < scene.textures.size(), "area light texture index in range");
            return &scene.textures[index].image;
        }
        case AreaTexture::Kind::BouncingSquare:
            scratch = renderBouncingSquare(light.texture, t);
            return &scratch;
    }
    return nullptr;
}

Expected<void> checkAreaTexture(const Scene& scene, const Light& light, const std::string& where) {
    const AreaTexture& t = light.texture;
    if (!t.textured()) return {};
    if (light.type != LightType::Area) return makeError("{}: only area lights have an emission texture", where);
    switch (t.kind) {
        case AreaTexture::Kind::None: break;
        case AreaTexture::Kind::Images: {
            if (t.frames.empty()) return makeError("{}: texture has no frames", where);
            if (!std::isfinite(t.frameRate) || !(t.frameRate > 0.0f))
                return makeError("{}: texture frame rate {} is not positive", where, t.frameRate);
            for (size_t f = 0; f < t.frames.size(); ++f) {
                if (t.frames[f] >= scene.textures.size())
                    return makeError("{}: texture frame {} is texture index {}, out of range ({} textures)", where, f,
                                     t.frames[f], scene.textures.size());
                const Image& image = scene.textures[t.frames[f]].image;
                if (image.empty()) return makeError("{}: texture frame {} ('{}') is empty", where, f, scene.textures[t.frames[f]].name);
                const Image& first = scene.textures[t.frames.front()].image;
                if (image.width() != first.width() || image.height() != first.height())
                    return makeError("{}: texture frame {} is {}x{}, frame 0 is {}x{}: frames must be the same size",
                                     where, f, image.width(), image.height(), first.width(), first.height());
                for (const glm::vec3& texel : image.pixels())
                    if (!(texel.r >= 0.0f && texel.g >= 0.0f && texel.b >= 0.0f && std::isfinite(texel.r) &&
                          std::isfinite(texel.g) && std::isfinite(texel.b)))
                        return makeError("{}: texture frame {} ('{}') has a negative or non-finite texel", where, f,
                                         scene.textures[t.frames[f]].name);
            }
            break;
        }
        case AreaTexture::Kind::BouncingSquare:
            if (t.resolution < 1 || t.resolution > kMaxAreaTextureResolution)
                return makeError("{}: bouncing-square resolution {} is outside [1, {}]", where, t.resolution,
                                 kMaxAreaTextureResolution);
            if (!std::isfinite(t.squareSize) || !(t.squareSize > 0.0f) || t.squareSize > 1.0f)
                return makeError("{}: bouncing-square size {} is outside (0, 1]", where, t.squareSize);
            if (!std::isfinite(t.squareVelocity.x) || !std::isfinite(t.squareVelocity.y) ||
                !std::isfinite(t.squareStart.x) || !std::isfinite(t.squareStart.y))
                return makeError("{}: bouncing-square velocity or start is not finite", where);
            break;
    }
    return {};
}

glm::vec3 imageMean(const Image& image) {
    if (image.empty()) return glm::vec3(0.0f);
    glm::dvec3 sum(0.0);
    for (const glm::vec3& p : image.pixels()) sum += glm::dvec3(p);
    return glm::vec3(sum / static_cast<double>(image.pixelCount()));
}

glm::vec3 areaTextureMean(const Scene& scene, const Light& light, float t) {
    Image scratch;
    const Image* image = areaTextureAt(scene, light, t, scratch);
    return image ? imageMean(*image) : glm::vec3(1.0f);
}

}  // namespace bounce
