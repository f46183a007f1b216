#pragma once
// Display transform: exposure (photographic stops), a tone curve, then the sRGB transfer function.
// Shared by PNG output, the viewer (same formulas in shaders/common/tonemap.glsl) and LDR metrics.
#include "core/Error.h"
#include "core/Image.h"

#include <string>
#include <string_view>

namespace bounce {

enum class ToneCurve { Clamp, Reinhard, Aces };

struct ToneMap {
    float exposureEv = 0.0f;  // radiance is multiplied by 2^exposureEv before the curve
    ToneCurve curve = ToneCurve::Aces;
};

Expected<ToneCurve> parseToneCurve(std::string_view name);
std::string_view toneCurveName(ToneCurve curve);

// Linear radiance -> display value in [0, 1] (sRGB encoded).
glm::vec3 toDisplay(glm::vec3 radiance, const ToneMap& toneMap);
Image toDisplay(const Image& radiance, const ToneMap& toneMap);

float srgbEncode(float linear);
float srgbDecode(float encoded);

}  // namespace bounce
