#include "metrics/Heatmap.h"

#include "core/Check.h"
#include "core/ImageIo.h"
#include "core/ToneMap.h"
#include "metrics/ColorSpaces.h"

#include <fmt/format.h>
#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace bounce {
namespace {

// Colour map design (CIELAB, D65): lightness carries the value, so order survives grey-scale
// printing and colour-vision deficiencies; hue and chroma only add separation.
constexpr float kLightnessLow = 8.0f;     // L* at t = 0 (near black)
constexpr float kLightnessHigh = 95.0f;   // L* at t = 1 (near white)
constexpr float kHueStartDeg = 300.0f;    // purple
constexpr float kHueSpanDeg = 150.0f;     // through magenta and red to yellow (90 deg)
constexpr float kChromaPeak = 80.0f;      // requested chroma scale; clipped to the sRGB gamut
constexpr float kChromaEaseOff = 0.6f;    // fraction of the chroma given up at t = 1 (pale yellow end)
constexpr int kColorTableSize = 256;      // one entry per 8-bit output level
constexpr int kGamutIterations = 24;      // bisection steps on chroma (2^-24 of kChromaPeak)

bool inGamut(glm::vec3 rgb) {
    constexpr float kSlack = 1e-5f;  // float round-off of the Lab -> RGB matrices
    return glm::all(glm::greaterThanEqual(rgb, glm::vec3(-kSlack))) && glm::all(glm::lessThanEqual(rgb, glm::vec3(1 + kSlack)));
}

glm::vec3 designColor(float t) {
    const float lightness = kLightnessLow + (kLightnessHigh - kLightnessLow) * t;
    const float hue = (kHueStartDeg + kHueSpanDeg * t) * std::numbers::pi_v<float> / 180.0f;
    // Chroma rises quickly from the black end and eases off towards the light end, where the
    // gamut is narrow for all but yellow.
    const float wanted = kChromaPeak * std::sqrt(t) * (1.0f - kChromaEaseOff * t);
    auto rgbAt = [&](float chroma) {
        return xyzToLinearRgb(cielabToXyz({lightness, chroma * std::cos(hue), chroma * std::sin(hue)}));
    };
    float lo = 0.0f, hi = wanted;
    if (!inGamut(rgbAt(hi))) {
        for (int i = 0; i < kGamutIterations; ++i) {
            const float mid = 0.5f * (lo + hi);
            (inGamut(rgbAt(mid)) ? lo : hi) = mid;
        }
        hi = lo;
    }
    const glm::vec3 rgb = glm::clamp(rgbAt(hi), 0.0f, 1.0f);
    return {srgbEncode(rgb.r), srgbEncode(rgb.g), srgbEncode(rgb.b)};
}

const std::array<glm::vec3, kColorTableSize>& colorTable() {
    static const auto kTable = [] {
        std::array<glm::vec3, kColorTableSize> table;
        for (int i = 0; i < kColorTableSize; ++i) table[i] = designColor(static_cast<float>(i) / (kColorTableSize - 1));
        return table;
    }();
    return kTable;
}

// A 3x5 pixel font for the bar labels; each row is 3 bits, most significant bit on the left.
constexpr int kGlyphWidth = 3, kGlyphHeight = 5;
struct Glyph {
    char c;
    std::array<unsigned char, kGlyphHeight> rows;
};
constexpr std::array<Glyph, 14> kGlyphs{{
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
    {'+', {0, 2, 7, 2, 0}}, {'e', {2, 5, 7, 4, 3}},
}};

const Glyph* findGlyph(char c) {
    for (const Glyph& g : kGlyphs)
        if (g.c == c) return &g;
    return nullptr;
}

int textWidth(const std::string& text, int scale) {
    return text.empty() ? 0 : static_cast<int>(text.size()) * (kGlyphWidth + 1) * scale - scale;
}

void drawText(Image& image, const std::string& text, int left, int top, int scale, glm::vec3 color) {
    int x0 = left;
    for (char c : text) {
        if (const Glyph* g = findGlyph(c))
            for (int row = 0; row < kGlyphHeight; ++row)
                for (int col = 0; col < kGlyphWidth; ++col)
                    if (g->rows[row] & (1 << (kGlyphWidth - 1 - col)))
                        for (int dy = 0; dy < scale; ++dy)
                            for (int dx = 0; dx < scale; ++dx) {
                                const int x = x0 + col * scale + dx, y = top + row * scale + dy;
                                if (x >= 0 && x < image.width() && y >= 0 && y < image.height()) image.at(x, y) = color;
                            }
        x0 += (kGlyphWidth + 1) * scale;
    }
}

std::string label(float value) { return fmt::format("{:.3g}", value); }

// Legend strip: mid grey (display value, about L* 32), so it is distinct from the map's near-black
// low end and still gives the light labels contrast.
constexpr glm::vec3 kBackground(0.3f);
constexpr glm::vec3 kLabelColor(0.95f);
constexpr int kMinLabelWidth = 32;       // narrower images get a bar without labels

}  // namespace

glm::vec3 heatmapColor(float t) {
    if (!(t > 0.0f)) t = 0.0f;  // also maps NaN to the low end
    t = std::min(t, 1.0f);
    return colorTable()[static_cast<size_t>(std::lround(t * (kColorTableSize - 1)))];
}

HeatmapLayout heatmapLayout(int width, int mapHeight) {
    HeatmapLayout l;
    l.width = width;
    l.mapHeight = mapHeight;
    // Legend proportions: bar about 1/16 of the map height, at least 6 pixels, margins 1/32 of the width.
    const int gap = std::max(2, mapHeight / 64);
    const int barHeight = std::max(6, mapHeight / 16);
    const int margin = width >= kMinLabelWidth ? std::max(2, width / 32) : 0;
    l.barTop = mapHeight + gap;
    l.barBottom = l.barTop + barHeight;
    l.barLeft = margin;
    l.barRight = width - margin;
    l.labelScale = width >= kMinLabelWidth ? std::max(1, width / 256) : 0;
    l.labelTop = l.barBottom + gap;
    l.height = l.labelScale > 0 ? l.labelTop + kGlyphHeight * l.labelScale + gap : l.barBottom + gap;
    return l;
}

Image renderHeatmap(const ErrorMap& map, float low, float high) {
    BOUNCE_CHECK(low < high && std::isfinite(low) && std::isfinite(high), "heat map range [{}, {}] is empty", low, high);
    BOUNCE_CHECK(!map.empty(), "empty error map");
    const HeatmapLayout l = heatmapLayout(map.width(), map.height());
    Image image(l.width, l.height, kBackground);
    const float scale = 1.0f / (high - low);
    for (int y = 0; y < map.height(); ++y)
        for (int x = 0; x < map.width(); ++x) image.at(x, y) = heatmapColor((map.at(x, y) - low) * scale);
    const int barWidth = l.barRight - l.barLeft;
    for (int x = l.barLeft; x < l.barRight; ++x) {
        const float t = barWidth > 1 ? static_cast<float>(x - l.barLeft) / static_cast<float>(barWidth - 1) : 0.0f;
        for (int y = l.barTop; y < l.barBottom; ++y) image.at(x, y) = heatmapColor(t);
    }
    if (l.labelScale > 0) {
        const std::string lowText = label(low), highText = label(high);
        const int highLeft = l.barRight - textWidth(highText, l.labelScale);
        // Labels only when both fit side by side with a glyph's room between them.
        if (l.barLeft + textWidth(lowText, l.labelScale) + (kGlyphWidth + 1) * l.labelScale <= highLeft) {
            drawText(image, lowText, l.barLeft, l.labelTop, l.labelScale, kLabelColor);
            drawText(image, highText, highLeft, l.labelTop, l.labelScale, kLabelColor);
        }
    }
    return image;
}

Expected<void> writeHeatmap(const std::filesystem::path& path, const ErrorMap& map, float low, float high) {
    if (map.empty()) return makeError("{}: nothing to write, the error map is empty", path.string());
    if (!(low < high)) return makeError("{}: heat map range [{}, {}] is empty", path.string(), low, high);
    return writeDisplayPng(path, renderHeatmap(map, low, high));
}

}  // namespace bounce
