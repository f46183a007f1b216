// GPU `direct` against the reference path tracer's direct light (--bounces 0) on cornell-box: the
// two renderers must share units, the spot's falloff and cutoff, the BRDF and shadowing.
#include "GpuTestSupport.h"
#include "reference/PathTracer.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <algorithm>
#include <cmath>

using namespace bounce;

namespace {
class ReferenceAgreementGpuTest : public gputest::GpuTest {};

double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& v : image.pixels()) sum += luminance(v);
    return sum / static_cast<double>(image.pixelCount());
}

void expectAgreement(const std::string& sceneName) {
    auto scene = loadScene(sceneName);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    constexpr int kSize = 96;

    auto technique = createTechnique("direct");
    ASSERT_TRUE(technique.ok());
    render::RenderSettings rs;
    rs.shadowMapSize = 2048;  // shadow edges within a fraction of a 96x96 pixel
    rs.pcfRadius = 0;         // hard shadows, as the reference's point-light shadows
    auto pipeline = Pipeline::create(*scene, std::move(*technique), {kSize, kSize}, rs);
    ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
    (*pipeline)->renderFrame(0);
    const Image gpu = (*pipeline)->readback(Component::Direct);

    PathTracerSettings pts;
    pts.width = pts.height = kSize;
    pts.samplesPerPixel = 256;
    pts.bounces = 0;
    auto tracer = PathTracer::create(*scene, pts);
    ASSERT_TRUE(tracer.ok()) << tracer.error().message;
    const PathTracerResult ref = tracer->render();

    // The GPU shades pixel centres while the reference integrates each pixel's footprint, so pixels
    // on a geometric or shadow edge legitimately differ (at 64x64 they are ~10 % of the lit area and
    // bias the image mean by ~5 %). Compare away from edges: a pixel is interior when the reference
    // is locally linear in x and y (second differences under 5 % of its value): the spot's smooth
    // falloff passes, edges and shadow boundaries do not.
    auto interior = [&](int x, int y) {
        auto L = [&](int px, int py) { return luminance(ref.radiance.at(px, py)); };
        const float c = L(x, y);
        const float dxx = L(x - 1, y) + L(x + 1, y) - 2.0f * c;
        const float dyy = L(x, y - 1) + L(x, y + 1) - 2.0f * c;
        return std::abs(dxx) < 0.05f * c && std::abs(dyy) < 0.05f * c;
    };
    const double refMean = meanLuminance(ref.radiance);
    double gpuSum = 0.0, refSum = 0.0;
    int lit = 0, close = 0;
    for (int y = 1; y < kSize - 1; ++y)
        for (int x = 1; x < kSize - 1; ++x) {
            const float r = luminance(ref.radiance.at(x, y));
            if (r < 0.02f * static_cast<float>(refMean) || !interior(x, y)) continue;
            const float g = luminance(gpu.at(x, y));
            gpuSum += g;
            refSum += r;
            ++lit;
            if (std::abs(g - r) <= 0.03f * r) ++close;
        }
    ASSERT_GT(lit, kSize * kSize / 8);
    // 1. Interior means agree within three reference standard errors (the reference's only noise
    //    here is pixel-footprint jitter) plus 0.5 % for shadow-map resolution at penumbra-free edges.
    const double tolerance = 3.0 * ref.noise.imageRelativeError + 0.005;
    EXPECT_NEAR(gpuSum / refSum, 1.0, tolerance) << "gpu " << gpuSum / lit << " reference " << refSum / lit;
    // 2. 95 % of interior lit pixels agree within 3 % (the rest: shadow-map texels vs exact rays).
    EXPECT_GE(static_cast<double>(close) / lit, 0.95) << close << " of " << lit << " interior pixels within 3 %";
}
}  // namespace

TEST_F(ReferenceAgreementGpuTest, DirectMatchesReferenceBouncesZeroOnCornellBox) { expectAgreement("cornell-box"); }
