#pragma once
// A GI technique: one folder under techniques/, its shaders under shaders/techniques/<name>/, a doc
// page docs/techniques/<name>.md and one line in Registry.cpp.
//
// Every frame the Pipeline renders the shared passes first (scene update, light set with shadow
// maps, camera G-buffer, direct lighting), then asks the technique for the indirect radiance, and
// composes full = direct + indirect. A technique that computes its own direct light (a radiosity
// solution, say) overrides ownsDirect() and overwrites the direct target too.
#include "core/Error.h"
#include "core/Settings.h"
#include "gpu/GpuTimers.h"
#include "render/DirectLighting.h"
#include "render/GBuffer.h"
#include "render/LightSet.h"
#include "render/RenderSettings.h"
#include "render/SceneDrawer.h"

#include <map>
#include <string>
#include <string_view>

namespace bounce {

// Numbers a technique reports per frame (VPL counts, fragments per level, ...), by name.
using Counters = std::map<std::string, double>;

struct SetupContext {
    const Scene& scene;
    render::SceneGpu& sceneGpu;
    glm::ivec2 size;  // output size in pixels
    const render::RenderSettings& renderSettings;
};

struct FrameContext {
    const Scene& scene;
    render::SceneGpu& sceneGpu;  // already updated to `time`
    render::SceneDrawer& drawer;
    const render::LightSet& lights;
    const render::GBuffer& gbuffer;
    const render::View& camera;
    const gl::Texture& direct;  // direct radiance of this frame
    gl::GpuTimers& timers;
    Counters& counters;
    float time = 0.0f;   // seconds
    uint32_t frame = 0;  // frame index since the start of the run
    glm::ivec2 size{0};
};

// An intermediate result a technique exposes for inspection: the viewer lists them (registry-driven:
// the Pipeline adds the shared ones, G-buffer channels and outputs, each technique its own) and shows
// the selected one instead of the image. A view is either a texture (2D, or a layer of a 2D array)
// with a rule for turning texels into colour, or a technique setting whose value makes the technique
// draw the view into its indirect output itself (vct's voxels, photon-splat's overlap).
enum class DebugEncoding {
    Radiance,  // linear radiance, tone-mapped like the image
    Normal,    // unit vectors, shown as 0.5 + 0.5 n
    Position,  // world positions, shown as fract(p)
    Color,     // values in [0, 1] shown as they are (albedo)
    Scalar,    // the red channel / `scale`, through the heat-map colour ramp
    Points,    // a 2D array of world positions (w > 0 valid), drawn as points over the image
    ClusterPoints,  // a 2D array of sums of world positions with their count in w (a min-max pyramid
                    // level: hisr's VPL tree), drawn as points at the means over the image
    Ids,       // unsigned integers (a R32UI 2D array: radiosity's ID hemicubes), a colour per value, 0 black
};

struct DebugView {
    std::string name;                     // "gbuffer.normal", "rsm.flux"
    const gl::Texture* texture = nullptr;  // null for a setting-driven view
    DebugEncoding encoding = DebugEncoding::Radiance;
    float scale = 1.0f;                   // Scalar: the value shown at the top of the ramp; Radiance: a multiplier;
                                          // Points, ClusterPoints: the dot's diameter in pixels
    std::string setting, value;           // setting-driven: set `setting` = `value`, show the indirect output
    int level = 0;                        // the mip level shown (ClusterPoints: the pyramid level drawn)
};

class Technique : public Configurable {
public:
    ~Technique() override = default;
    virtual std::string_view name() const = 0;
    // After settings were applied and the scene uploaded: build programs and allocate targets.
    virtual Expected<void> setup(const SetupContext& ctx) = 0;
    // Writes this frame's indirect radiance, W/(m^2 sr), into `indirect` (RGBA32F, frame size).
    virtual void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) = 0;
    // True when renderIndirect also rewrites `ctx.direct` (it is then passed as writable).
    virtual bool ownsDirect() const { return false; }
    // True for techniques whose indirect light starts at the scene's lights only (VPLs, photons,
    // voxels injected from light sources): the light of emissive materials would be silently
    // missing from their indirect output, so Pipeline::create refuses scenes that have any.
    virtual bool bouncesLightsOnly() const { return false; }
    // Appends this technique's debug views (valid after setup; textures are owned by the technique).
    virtual void debugViews(std::vector<DebugView>& /*out*/) const {}
    // Reads the counters that live on the GPU (query results, atomic counts) into `out`, after the frame's
    // work is queued whole: renderIndirect runs inside a gl::FramePath and makes no read that waits for
    // the GPU (gpu/Readbacks.h; tests/gpu/ReadbackGpuTest.cpp checks every registered technique).
    virtual void collectCounters(Counters& /*out*/) {}
    // The effective value of each setting whose default the technique derives from the scene (a fraction
    // of the scene's diagonal, a grid around its bounds), in metres, under a name ending in the unit
    // ("positionThresholdMetres"); valid after setup. A setting the user set reports the value used too.
    // The run record prints them under "derived" (app/RunRecord.cpp), so a user sees what a scale-relative
    // default came to on their scene; each technique's doc page names its entries.
    virtual void derivedSettings(std::map<std::string, double>& /*out*/) const {}
    // Non-empty for a technique whose paper reads GPU results back in the middle of its frame (the
    // reason, naming the paper's step); the readback test then reports those reads instead of failing.
    virtual std::string_view frameReadbackReason() const { return {}; }
};

}  // namespace bounce
