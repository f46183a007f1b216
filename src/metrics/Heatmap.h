#pragma once
// Error heat maps: a per-pixel map coloured with a perceptually ordered colour map (lightness rises
// monotonically from black through purple, red and orange to pale yellow, in the spirit of magma),
// with a colour bar underneath whose two ends are labelled with the values they stand for.
#include "core/Error.h"
#include "core/Image.h"
#include "metrics/ErrorMap.h"

#include <filesystem>

namespace bounce {

// Colour of t in [0, 1] (clamped) as a display value (sRGB-encoded, [0, 1]). Built in CIELAB:
// L* = 8 + 87 t, hue 300 deg -> 90 deg through red, chroma reduced where needed to stay in gamut.
glm::vec3 heatmapColor(float t);

// Where the pieces sit in the image renderHeatmap() returns (rows are half-open ranges).
struct HeatmapLayout {
    int width = 0;
    int mapHeight = 0;                       // rows [0, mapHeight) hold the map
    int barTop = 0, barBottom = 0;           // colour bar rows
    int barLeft = 0, barRight = 0;           // colour bar columns; barLeft is `low`, barRight - 1 is `high`
    int labelTop = 0, labelScale = 0;        // end labels (0 scale: image too narrow for labels)
    int height = 0;                          // total image height
};
HeatmapLayout heatmapLayout(int width, int mapHeight);

// Maps value v to heatmapColor((v - low) / (high - low)); values outside [low, high] clamp.
// Requires low < high (checked).
Image renderHeatmap(const ErrorMap& map, float low, float high);

// renderHeatmap() written as PNG (atomically; an error leaves no file).
Expected<void> writeHeatmap(const std::filesystem::path& path, const ErrorMap& map, float low, float high);

}  // namespace bounce
