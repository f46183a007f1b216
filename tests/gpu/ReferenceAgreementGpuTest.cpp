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
    constexpr int kSize = 64;

    auto technique = createTechnique("direct");
    ASSERT_TRUE(technique.ok());
    render::RenderSettings rs;
    rs.shadowMapSize = 2048;  // shadow edges within a fraction of a 64x64 pixel
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

    // 1. Image means agree within three standard errors of the reference's mean, plus 1 % for what
    //    the two sample differently: the GPU shades pixel centres, the reference integrates each
    //    pixel's footprint (geometric and shadow edges).
    const double gpuMean = meanLuminance(gpu), refMean = meanLuminance(ref.radiance);
    ASSERT_GT(refMean, 0.0);
    const double tolerance = 3.0 * ref.noise.imageRelativeError + 0.01;
    EXPECT_NEAR(gpuMean / refMean, 1.0, tolerance) << "gpu " << gpuMean << " reference " << refMean;

    // 2. Pixel by pixel: away from edges both are exact, so 90 % of the lit pixels must agree within
    //    5 % (the other 10 % allows for pixels straddling an edge, about 4 per row at 64x64).
    int lit = 0, close = 0;
    for (size_t i = 0; i < gpu.pixelCount(); ++i) {
        const float r = luminance(ref.radiance.data()[i]);
        if (r < 0.02f * static_cast<float>(refMean)) continue;
        ++lit;
        if (std::abs(luminance(gpu.data()[i]) - r) <= 0.05f * r) ++close;
    }
    ASSERT_GT(lit, kSize * kSize / 4);
    EXPECT_GE(static_cast<double>(close) / lit, 0.90) << close << " of " << lit << " lit pixels within 5 %";
}
}  // namespace

TEST_F(ReferenceAgreementGpuTest, DirectMatchesReferenceBouncesZeroOnCornellBox) { expectAgreement("cornell-box"); }
