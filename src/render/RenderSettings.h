#pragma once
// Settings of the passes every technique shares (shadow maps, direct lighting). They appear under
// the prefix "renderer." in --set, `bounce list` and run records.
#include "common/shared.h"
#include "core/Settings.h"

namespace bounce::render {

struct RenderSettings final : Configurable {
    static constexpr int kCascadeMapSizeLlvmpipe = 0;     // texels; 0 = shadowMapSize
    static constexpr int kCascadeMapSizeGpu = 4096;       // texels (4 tiles x 4096^2 x 4 B = 268 MB a directional light)
    int shadowMapSize = 1024;     // texels per side (2D maps and each cube face)
    int pcfRadius = 1;            // percentage-closer filter radius in texels (0 = one hard tap)
    float shadowBias = 0.002f;    // metres along the surface normal (the normal offset's constant part)
    // The same for directional lights' maps, whose receiver-plane depth bias already keeps planar
    // receivers off their own depth: a quarter of it, because the constant offset moves their shadow
    // edges and leaks light at contacts (courtyard / atrium at 4096^2 tiles: 2.6x / 3.2x the reference's
    // noise with 2 mm, 1.8x / 2.3x with 0.5 mm or none), while a normal-mapped receiver's plane, tilted
    // by its shading normal, still needs some (MaskedNormalMappedGpuTest: acne at 0.25 mm, clean at
    // 0.5 mm; docs/techniques/direct.md).
    float sunShadowBias = 0.0005f;
    // Normal offset per texel of a 2D map, in units of the PCF kernel's reach (pcfRadius + 1) * sqrt(2)
    // texels, times sin(theta) of the light's incidence (1 alone would lift every tap of a planar
    // receiver above its own stored depth). Off by default: the receiver-plane depth bias already does
    // that, and on courtyard any offset leaked light at concave junctions (0.2: relMSE 0.0060 against
    // 0.0037; docs/rendering.md "Shadows").
    float shadowNormalOffset = 0.0f;
    // View-fitted cascades of directional lights' maps in front of the whole-scene map (0: the
    // whole-scene map alone, as before issue 30). Each cascade has cascadeMapSize^2 texels.
    int shadowCascades = 3;
    // Texels per side of each tile of a directional light's map (its view-fitted cascades and its
    // whole-scene map), per device profile: 0 (= shadowMapSize) on llvmpipe, which re-renders the atlas on
    // the CPU at every camera move; 4096 on a GPU, where the finer tiles bring the shared direct pass on a
    // large scene several times closer to the reference (measured: docs/techniques/direct.md).
    int cascadeMapSize = 0;
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
        v.field("shadowBias", shadowBias, "constant normal-offset shadow bias of point, spot and area lights' maps (metres)",
                0.0f, 1.0f);
        v.field("sunShadowBias", sunShadowBias, "constant normal-offset shadow bias of directional lights' maps (metres)",
                0.0f, 1.0f);
        v.field("shadowNormalOffset", shadowNormalOffset,
                "texel-scaled normal offset of 2D shadow maps, in PCF-kernel reaches x sin(incidence); 0 = off", 0.0f,
                8.0f);
        v.field("shadowCascades", shadowCascades,
                "view-fitted cascades of a directional light's shadow map before its whole-scene map (0 = none)", 0,
                SHADOW_MAX_CASCADES - 1);
        v.field("cascadeMapSize", cascadeMapSize,
                "texels per side of each tile of a directional light's map (its cascades and whole-scene map); 0 = shadowMapSize",
                0, 8192, PerProfile<int>{kCascadeMapSizeLlvmpipe, kCascadeMapSizeGpu});
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
