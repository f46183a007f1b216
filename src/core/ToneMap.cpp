#include "core/ToneMap.h"

#include <glm/common.hpp>

#include <cmath>

namespace bounce {

Expected<ToneCurve> parseToneCurve(std::string_view name) {
    if (name == "clamp") return ToneCurve::Clamp;
    if (name == "reinhard") return ToneCurve::Reinhard;
    if (name == "aces") return ToneCurve::Aces;
    return makeError("unknown tone curve '{}' (known: clamp, reinhard, aces)", name);
}

std::string_view toneCurveName(ToneCurve curve) {
    switch (curve) {
        case ToneCurve::Clamp: return "clamp";
        case ToneCurve::Reinhard: return "reinhard";
        case ToneCurve::Aces: return "aces";
    }
    return "?";
}

float srgbEncode(float x) {
    x = glm::clamp(x, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float x) {
    x = glm::clamp(x, 0.0f, 1.0f);
    return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
}

static glm::vec3 applyCurve(glm::vec3 c, ToneCurve curve) {
    switch (curve) {
        case ToneCurve::Clamp: return glm::clamp(c, 0.0f, 1.0f);
        case ToneCurve::Reinhard: return c / (1.0f + c);
        case ToneCurve::Aces: {
            // Narkowicz 2015 fit of the ACES filmic curve (same constants in tonemap.glsl).
            constexpr float a = 2.51f, b = 0.03f, cc = 2.43f, d = 0.59f, e = 0.14f;
            return glm::clamp((c * (a * c + b)) / (c * (cc * c + d) + e), 0.0f, 1.0f);
        }
    }
    return c;
}

glm::vec3 toDisplay(glm::vec3 radiance, const ToneMap& toneMap) {
    glm::vec3 c = glm::max(radiance, glm::vec3(0.0f)) * std::exp2(toneMap.exposureEv);
    c = applyCurve(c, toneMap.curve);
    return {srgbEncode(c.r), srgbEncode(c.g), srgbEncode(c.b)};
}

Image toDisplay(const Image& radiance, const ToneMap& toneMap) {
    Image out(radiance.width(), radiance.height());
    for (size_t i = 0; i < radiance.pixelCount(); ++i) out.data()[i] = toDisplay(radiance.data()[i], toneMap);
    return out;
}

}  // namespace bounce
