#pragma once
// Helpers of the Nichols (2010) technique tests (rsm, isr): render a technique's indirect light with
// settings, a plane scene for closed-form RSM fluxes, and the error measures of the thesis's
// Figs. 4.9/4.13 (relative RMS error against the converged gather), and that gather, cached.
#include "GpuTestSupport.h"
#include "core/Settings.h"
#include "metrics/ErrorMetrics.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "reference/PathTracer.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace bounce::nicholstest {

inline render::RenderSettings smallRenderSettings() {
    render::RenderSettings s;
    s.shadowMapSize = 256;  // llvmpipe: small maps keep each test to seconds
    return s;
}

// Level `level` of an RGBA texture (every layer of an array texture: `layers` x size texels), as floats.
inline std::vector<glm::vec4> readLevel(const gl::Texture& texture, int level, glm::ivec2 size, int layers = 1) {
    std::vector<glm::vec4> texels(static_cast<size_t>(size.x) * size.y * layers);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // the pyramids are written as images (BOUNCE_BARRIER_CHECK)
    glGetTextureImage(texture.id(), level, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)),
                      texels.data());
    return texels;
}

inline std::unique_ptr<Pipeline> makePipeline(const Scene& scene, const std::string& technique,
                                              const std::map<std::string, std::string>& settings, int size) {
    auto t = createTechnique(technique);
    EXPECT_TRUE(t.ok());
    auto applied = applySettings(**t, settings, technique);
    EXPECT_TRUE(applied.ok()) << applied.error().message;
    auto p = Pipeline::create(scene, std::move(*t), {size, size}, smallRenderSettings());
    EXPECT_TRUE(p.ok()) << p.error().message;
    return std::move(*p);
}

// The one-line error of a pipeline the technique refuses to set up ("" when it accepts the scene).
inline std::string setupRefusal(const Scene& scene, const std::string& technique, int size = 16) {
    auto t = createTechnique(technique);
    EXPECT_TRUE(t.ok());
    auto p = Pipeline::create(scene, std::move(*t), {size, size}, smallRenderSettings());
    return p.ok() ? std::string() : p.error().message;
}

// Techniques whose indirect light starts at the scene's lights (VPLs, photons, injected voxels) refuse
// scenes with emissive materials, whose light they would silently drop (Technique::bouncesLightsOnly).
inline void expectRefusesEmissiveScene(const Scene& scene, const std::string& technique) {
    const std::string error = setupRefusal(scene, technique);
    EXPECT_NE(error.find("emissive materials"), std::string::npos) << technique << " on " << scene.name << ": '" << error << "'";
}

inline Image renderIndirect(const Scene& scene, const std::string& technique,
                            const std::map<std::string, std::string>& settings, int size) {
    auto p = makePipeline(scene, technique, settings, size);
    p->renderFrame(0);
    return p->readback(Component::Indirect);
}

// RSM resolution of the converged limit in the tests. Nichols (2010) Figs. 4.9/4.13 compare against "a
// full gather over a 1024^2 RSM" (every texel a VPL, about a million for a spot light's single map);
// `rsm` renders that limit exactly (batched gather), but it takes about 2 minutes at 64^2 on llvmpipe
// (2 shared cores; docs/techniques/rsm.md), over the GPU suite's whole budget. 256^2 (65,536 VPLs,
// about 7 s at 64^2) is the largest that fits; it is within 5.9 % relative RMS of the 1M-VPL
// gather at 64^2 (measured, rsm.md), far below the techniques' own errors that the tests bound.
constexpr int kLimitRsmSize = 256;

// The converged limit of built-in scene `sceneName` at size^2: rsm with rsmSize = vplGrid =
// kLimitRsmSize. Rendered once per scene and size per test binary (cached): it costs seconds.
inline const Image& convergedLimit(const std::string& sceneName, int size) {
    static std::map<std::pair<std::string, int>, Image> cache;
    const auto key = std::make_pair(sceneName, size);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    auto scene = loadScene(sceneName);
    EXPECT_TRUE(scene.ok()) << sceneName;
    const std::string rsm = std::to_string(kLimitRsmSize);
    return cache[key] = renderIndirect(*scene, "rsm", {{"rsmSize", rsm}, {"vplGrid", rsm}}, size);
}

// The path tracer's one-bounce indirect light (bounces 1, indirect only) of `scene` at frame
// `frame`: the scope every single-bounce technique is compared with.
inline Image oneBounceReference(const Scene& scene, int size, uint32_t frame, uint32_t spp) {
    PathTracerSettings pts;
    pts.width = pts.height = size;
    pts.samplesPerPixel = spp;
    pts.bounces = 1;
    pts.indirectOnly = true;
    pts.frame = frame;
    auto tracer = PathTracer::create(scene, pts);
    EXPECT_TRUE(tracer.ok()) << tracer.error().message;
    return tracer->render().radiance;
}

inline double totalRadiance(const Image& image) {
    double sum = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) sum += double(image.at(x, y).r) + image.at(x, y).g + image.at(x, y).b;
    return sum;
}

inline bool finiteAndNonNegative(const Image& image) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(image.at(x, y)[c]) || image.at(x, y)[c] < 0.0f) return false;
    return true;
}

using gputest::kPlaneAlbedo;
using gputest::kPlaneHalf;
using gputest::planeScene;

}  // namespace bounce::nicholstest
