#pragma once
// The viewer's own settings (`bounce view --set viewer.NAME=VALUE`, the panel's "viewer settings",
// `bounce list`), declared once like a technique's.
#include "core/Settings.h"

namespace bounce {

struct ViewerSettings final : Configurable {
    // Per device profile (core/DeviceProfile.h): 250 ms (4 fps) is the viewer's llvmpipe budget (docs/
    // viewer.md); on a GPU the budget is an interactive 30 fps. Engineering choices.
    static constexpr float kFrameBudgetLlvmpipeMs = 250.0f;
    static constexpr float kFrameBudgetGpuMs = 1000.0f / 30.0f;
    float frameBudgetMs = kFrameBudgetLlvmpipeMs;
    float minScale = 0.25f;
    int graphFrames = 120;
    int metricsInterval = 10;
    int referenceSpp = 64;
    int referenceBounces = 1;
    bool referenceIndirectOnly = false;
    int referenceThreads = 1;
    float heatmapOpacity = 0.7f;

    void visitSettings(SettingsVisitor& v) override {
        v.field("frameBudgetMs", frameBudgetMs,
                "reduce the internal render size while a frame takes longer than this (ms: the longer of its CPU "
                "submission and the GPU's time for the previous frame); 0: never",
                0.0f, 10000.0f, PerProfile<float>{kFrameBudgetLlvmpipeMs, kFrameBudgetGpuMs});
        v.field("minScale", minScale, "smallest internal size, as a fraction of the view", 0.05f, 1.0f);
        v.field("graphFrames", graphFrames, "frames in the frame-time graph", 10, 1000);
        v.field("metricsInterval", metricsInterval, "frames between A/B error updates (relMSE, FLIP on the CPU)", 1, 1000);
        v.field("referenceSpp", referenceSpp, "samples per pixel of the background reference", 1, 1 << 20);
        v.field("referenceBounces", referenceBounces, "indirect bounces of the background reference (-1: unbounded)", -1, 1024);
        v.field("referenceIndirectOnly", referenceIndirectOnly, "background reference: indirect light only (compare with component indirect)");
        v.field("referenceThreads", referenceThreads, "threads of the background reference (0: all; 1 keeps the viewer responsive on 2 cores)", 0, 256);
        v.field("heatmapOpacity", heatmapOpacity, "opacity of the FLIP heat map over the image", 0.0f, 1.0f);
    }
};

}  // namespace bounce
