#pragma once
// Settings of the passes every technique shares (shadow maps, direct lighting). They appear under
// the prefix "renderer." in --set, `bounce list` and run records.
#include "core/Settings.h"

namespace bounce::render {

struct RenderSettings final : Configurable {
    int shadowMapSize = 1024;     // texels per side (2D maps and each cube face)
    int pcfRadius = 1;            // percentage-closer filter radius in texels (0 = one hard tap)
    float shadowBias = 0.002f;    // metres along the surface normal (normal-offset bias)
    float exposure = 0.0f;        // EV, for PNG output and the viewer
    std::string toneCurve = "aces";
    // Per-pass timing (gl::GpuTimers::Mode): queries (GL timestamps, the frame as it runs) or finish
    // (glFinish at every pass boundary, wall clock: each pass's own cost on a deferred renderer such
    // as llvmpipe, slower frames).
    std::string timing = "queries";

    void visitSettings(SettingsVisitor& v) override {
        static constexpr std::string_view curves[] = {"clamp", "reinhard", "aces"};
        v.field("shadowMapSize", shadowMapSize, "shadow map resolution per side (texels)", 64, 8192);
        v.field("pcfRadius", pcfRadius, "PCF kernel radius (texels); 0 gives hard shadows", 0, 4);
        v.field("shadowBias", shadowBias, "normal-offset shadow bias (metres)", 0.0f, 1.0f);
        v.field("exposure", exposure, "exposure for PNG output and the viewer (EV stops)", -20.0f, 20.0f);
        v.field("toneCurve", toneCurve, "tone curve for PNG output and the viewer", curves);
        static constexpr std::string_view timings[] = {"queries", "finish"};
        v.field("timing", timing,
                "per-pass timers: queries (GL timestamps) or finish (glFinish at each pass boundary, wall clock: "
                "truthful per-pass cost on llvmpipe, slower frames)",
                timings);
    }
};

}  // namespace bounce::render
