// `area-light` (Nichols 2010 ch. 5) on the GPU: the like-for-like comparison with the path tracer's
// direct light (`--bounces 0`), the VPL sum against the exact polygon irradiance, soft shadows that a
// hard centre-shadowed direct pass cannot produce, incremental visibility reusing rays and agreeing
// with brute force, textured and animated lights, culling, and refusals.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "scene/AreaTexture.h"
#include "scene/MeshBuilder.h"
#include "scene/SceneLoader.h"
#include "techniques/Registry.h"
#include "techniques/area_light/AreaLightTechnique.h"

#include <bit>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class AreaLightGpuTest : public gputest::GpuTest {};

using Settings = std::map<std::string, std::string>;

struct AreaRun {
    Image direct;
    Counters counters;
};

AreaRun renderAreaLight(const Scene& scene, const Settings& settings, int size, uint32_t frame = 0) {
    auto p = makePipeline(scene, "area-light", settings, size);
    AreaRun r;
    r.counters = p->renderFrame(frame).counters;
    r.direct = p->readback(Component::Direct);
    return r;
}

Image directReference(const Scene& scene, int size, uint32_t spp, uint32_t frame = 0, bool diffuseOnly = true) {
    PathTracerSettings pts;
    pts.width = pts.height = size;
    pts.samplesPerPixel = spp;
    pts.bounces = 0;
    pts.diffuseOnly = diffuseOnly;
    pts.frame = frame;
    auto tracer = PathTracer::create(scene, pts);
    EXPECT_TRUE(tracer.ok()) << tracer.error().message;
    return tracer->render().radiance;
}

// Zeroes, in both images, the pixels of emitters and their neighbours (the reference filters the
// light's edge over its pixel footprint, the rasterizer samples pixel centres: the light's radiance
// there would swamp every measure of the receivers).
std::pair<Image, Image> receiversOnly(const Image& test, const Image& ref, float emitterRadiance) {
    Image a = test, b = ref;
    const float cut = 0.5f * emitterRadiance;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            bool near = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int u = std::clamp(x + dx, 0, a.width() - 1), v = std::clamp(y + dy, 0, a.height() - 1);
                    near = near || luminance(test.at(u, v)) > cut || luminance(ref.at(u, v)) > cut;
                }
            if (near) a.at(x, y) = b.at(x, y) = glm::vec3(0.0f);
        }
    return {a, b};
}

// Zeroes, in both images, the pixels whose G-buffer surface (from `p`, rendered at the images' size)
// lies on one of the scene's area lights, and their neighbours: for a textured light whose dark texels
// the luminance cut of receiversOnly would keep.
std::pair<Image, Image> withoutEmitters(const Image& test, const Image& ref, Pipeline& p, const Scene& scene) {
    const Image positions = readTexture(p.gbuffer().position());
    const auto onLight = [&](int x, int y) {
        const glm::vec3 q = positions.at(x, y);
        for (const Light& l : scene.lights) {
            if (l.type != LightType::Area) continue;
            const glm::vec3 d = q - l.position;
            const float size = std::max(glm::length(l.edgeU), glm::length(l.edgeV));
            const float u = glm::dot(d, l.edgeU) / glm::dot(l.edgeU, l.edgeU), v = glm::dot(d, l.edgeV) / glm::dot(l.edgeV, l.edgeV);
            if (std::abs(glm::dot(d, l.areaNormal())) < 1e-3f * size && std::abs(u) <= 0.51f && std::abs(v) <= 0.51f) return true;
        }
        return false;
    };
    Image a = test, b = ref;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            bool near = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    near = near || onLight(std::clamp(x + dx, 0, a.width() - 1), std::clamp(y + dy, 0, a.height() - 1));
            if (near) a.at(x, y) = b.at(x, y) = glm::vec3(0.0f);
        }
    return {a, b};
}

double relMse(const Image& a, const Image& b) {
    auto m = compareImages(a, b);
    EXPECT_TRUE(m.ok());
    return m->relMse;
}

Light ceilingLight(float height, float side, glm::vec3 radiance) {
    Light l;
    l.name = "panel";
    l.type = LightType::Area;
    l.position = {0.0f, height, 0.0f};
    l.edgeU = {side, 0.0f, 0.0f};
    l.edgeV = {0.0f, 0.0f, side};  // cross(edgeU, edgeV) = -y: emits downwards
    l.radiance = radiance;
    return l;
}

// planeScene plus a thin closed slab (a box) floating between the plane and the light.
Scene planeWithOccluder(const Light& light, float occluderHeight, float occluderHalf, float occluderZ = 0.0f) {
    Scene s = gputest::planeScene(light, Projection::Orthographic);
    MeshBuilder b("occluder");
    b.axisBox({-occluderHalf, occluderHeight, occluderZ - occluderHalf},
              {occluderHalf, occluderHeight + 0.02f, occluderZ + occluderHalf});
    s.meshes.push_back(b.take());
    Object o;
    o.name = "occluder";
    o.mesh = static_cast<uint32_t>(s.meshes.size() - 1);
    s.objects.push_back(o);
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

}  // namespace

TEST_F(AreaLightGpuTest, MatchesThePathTracersDirectLightOnCornellBoxArea) {
    // Like for like: area-light computes direct light only, which is `bounce reference --bounces 0`;
    // beside it the shared `direct` pass, whose area light is shadowed from its centre (hard shadows).
    auto scene = loadScene("cornell-box-area");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 128;
    const Image ref = directReference(*scene, kSize, 512);
    const float emitted = luminance(scene->lights[0].radiance);
    const AreaRun run = renderAreaLight(*scene, {}, kSize);
    const AreaRun unshadowed = renderAreaLight(*scene, {{"visibility", "none"}}, kSize);
    auto hard = makePipeline(*scene, "direct", {}, kSize);
    hard->renderFrame(0);
    const Image hardImage = hard->readback(Component::Direct);
    auto [test, reference] = receiversOnly(run.direct, ref, emitted);
    auto [open, reference2] = receiversOnly(unshadowed.direct, ref, emitted);
    auto [hardTest, reference3] = receiversOnly(hardImage, ref, emitted);
    const double error = relMse(test, reference), errorUnshadowed = relMse(open, reference2);
    const double errorHard = relMse(hardTest, reference3);
    const double wholeError = relMse(run.direct, ref), wholeErrorHard = relMse(hardImage, ref);
    RecordProperty("relMse", std::to_string(error));
    RecordProperty("relMseWithoutVisibility", std::to_string(errorUnshadowed));
    RecordProperty("relMseHardShadows", std::to_string(errorHard));
    RecordProperty("relMseWholeImage", std::to_string(wholeError));
    RecordProperty("relMseWholeImageHardShadows", std::to_string(wholeErrorHard));
    // Over the receivers: measured 0.0057 (0.0119 before the voxelization set each triangle's exact
    // depth span per pixel, the march took 64 steps and the colour threshold compared display colours),
    // against 0.0121 for the hard shadows and 0.23 without visibility. What is left is mostly the
    // pixels' edges (the reference filters them over the pixel, the G-buffer samples their centres: a
    // perfect point-sampled image scores about 0.003 on the receivers here) and the tall block's
    // penumbra on the red wall, over-occluded by the depth span of its grazing side face in a voxel
    // column. 0.01 leaves room for the path tracer's noise at 512 spp.
    EXPECT_LT(error, 0.01);
    EXPECT_LT(error, errorUnshadowed / 10.0);
    // The whole image, the light included (the bound: at most half the hard-shadow pass's
    // relMSE): measured 0.0060 against 0.0153 (the light box-filtered over its pixels as the reference
    // does; the G-buffer's point-sampled light costs `direct` about 0.003).
    EXPECT_LT(wholeError, 0.5 * wholeErrorHard);
    // Energy over the receivers: measured 0.990 (the penumbra above); 0.04 fails if visibility or a
    // VPL's radiance is lost wholesale (halving the VPLs gives 0.5, no visibility 1.08).
    const double ratio = totalRadiance(test) / totalRadiance(reference);
    RecordProperty("energyRatio", std::to_string(ratio));
    EXPECT_NEAR(ratio, 0.99, 0.04);
    // The whole image's energy, 70 % of which is the light's own pixels: measured 0.99 (0.92 for the
    // point-sampled light, 4 of its 4.5 pixel rows at 128^2).
    const double wholeRatio = totalRadiance(run.direct) / totalRadiance(ref);
    RecordProperty("energyRatioWholeImage", std::to_string(wholeRatio));
    EXPECT_NEAR(wholeRatio, 1.0, 0.03);
    EXPECT_DOUBLE_EQ(run.counters.at("vpls"), 256.0);
}

TEST_F(AreaLightGpuTest, VplSumWithoutVisibilityMatchesTheExactPolygonIrradiance) {
    // A 1 m panel 1.5 m above the plane, no occluders: the 16 x 16 VPL sum of Eq. 5.2 against the
    // `direct` technique's exact irradiance of a uniform Lambertian rectangle (common/lighting.glsl).
    // The midpoint rule over 6 cm cells at 1.5 m is exact to a few 1e-4 (the integrand's second
    // derivative over a cell); the multiresolution interpolation adds the rest.
    const Scene scene = gputest::planeScene(ceilingLight(1.5f, 1.0f, glm::vec3(4.0f)), Projection::Orthographic);
    constexpr int kSize = 64;
    auto p = makePipeline(scene, "direct", {}, kSize);
    p->renderFrame(0);
    const Image direct = p->readback(Component::Direct);
    const AreaRun run = renderAreaLight(scene, {{"visibility", "none"}}, kSize);
    EXPECT_LT(relMse(run.direct, direct), 1e-3);
    EXPECT_NEAR(totalRadiance(run.direct) / totalRadiance(direct), 1.0, 0.01);
}

TEST_F(AreaLightGpuTest, NearFieldStaysBelowAFullHemisphereOfTheLight) {
    // The plane 5 mm under the 1 m panel (0.08 of a VPL cell's side): no receiver can get more than
    // pi L, its whole hemisphere filled with the light, and under the panel the path tracer gives pi L
    // to 1 %. At 64^2 over the 4 m view the pixel centres under the panel lie exactly under VPLs,
    // where Eq. 5.2's point form A cos cos / r^2 gives 156 L for that VPL alone; the bound
    // (r^2 >= A / pi, area_common.glsl) gives pi L cos cos. Interleaving is off: within a VPL spacing
    // of the light each VPL lights only the cells right under it, so the 2x2 subsets of neighbouring
    // cells are not interchangeable and the reconstruction reads twice the light (recorded below;
    // docs/techniques/area-light.md: no built-in scene has a receiver that close).
    constexpr float kRadiance = 4.0f, kHeight = 0.005f;
    const Scene scene = gputest::planeScene(ceilingLight(kHeight, 1.0f, glm::vec3(kRadiance)), Projection::Orthographic);
    constexpr int kSize = 64;
    const AreaRun run = renderAreaLight(scene, {{"visibility", "none"}, {"interleave", "false"}}, kSize);
    const AreaRun interleaved = renderAreaLight(scene, {{"visibility", "none"}}, kSize);
    const Image ref = directReference(scene, kSize, 256);
    // Radiance = albedo / pi E on the grey plane: E / (pi L) = radiance / (albedo L).
    const auto peakOf = [&](const Image& img) {
        float peak = 0.0f;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) peak = std::max(peak, luminance(img.at(x, y)) / (gputest::kPlaneAlbedo * kRadiance));
        return peak;
    };
    const float peak = peakOf(run.direct);
    const double error = relMse(run.direct, ref);
    RecordProperty("peakOverPiL", std::to_string(peak));
    RecordProperty("peakOverPiLInterleaved", std::to_string(peakOf(interleaved.direct)));
    RecordProperty("relMse", std::to_string(error));
    // Measured 1.012 with the bound (the VPL above plus its neighbours' grazing light); the point form
    // gave 50 (99 interleaved). 1.1 allows the neighbours' light at this height, not a second VPL's worth.
    EXPECT_LT(peak, 1.1f);
    EXPECT_GT(peak, 0.9f);
    // Measured 0.0047 against the path tracer (the panel's edge: its light falls from pi L to 0 within
    // a pixel); 151 with the point form. 0.02 leaves room for the path tracer's noise at 256 spp.
    EXPECT_LT(error, 0.02);
}

TEST_F(AreaLightGpuTest, SoftShadowPenumbraMatchesTheReferenceWhereTheHardShadowCannot) {
    // A 0.8 m slab half-way under a 1 m panel at 1.5 m: its shadow on the plane has a 1.2 m umbra and
    // a 0.5 m penumbra. The `direct` technique shadows area lights from their centre (a hard shadow),
    // so its penumbra pixels are either lit or dark; area-light's voxel visibility grades them.
    const Light light = ceilingLight(1.5f, 1.0f, glm::vec3(4.0f));
    const Scene scene = planeWithOccluder(light, 0.75f, 0.4f);
    const Scene open = gputest::planeScene(light, Projection::Orthographic);
    constexpr int kSize = 64;
    const Image ref = directReference(scene, kSize, 1024);
    const Image refOpen = directReference(open, kSize, 256);
    auto p = makePipeline(scene, "direct", {}, kSize);
    p->renderFrame(0);
    const Image hard = p->readback(Component::Direct);
    const AreaRun soft = renderAreaLight(scene, {}, kSize);
    double errorSoft = 0.0, errorHard = 0.0;
    int penumbra = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const float lit = luminance(refOpen.at(x, y)), r = luminance(ref.at(x, y));
            if (!(lit > 0.0f) || r < 0.2f * lit || r > 0.8f * lit) continue;  // penumbra: partly visible light
            ++penumbra;
            errorSoft += std::abs(luminance(soft.direct.at(x, y)) - r) / lit;
            errorHard += std::abs(luminance(hard.at(x, y)) - r) / lit;
        }
    ASSERT_GT(penumbra, 100);
    errorSoft /= penumbra;
    errorHard /= penumbra;
    RecordProperty("penumbraPixels", std::to_string(penumbra));
    RecordProperty("penumbraErrorAreaLight", std::to_string(errorSoft));
    RecordProperty("penumbraErrorHardShadow", std::to_string(errorHard));
    // Mean error over the penumbra as a fraction of the unoccluded level: a hard shadow is off by
    // about a quarter of it on average (inside its edge too dark, outside too bright); 0.08 for
    // area-light allows the 256-VPL banding and the voxel grid's one-voxel blur of the slab's edge.
    EXPECT_LT(errorSoft, 0.08);
    EXPECT_GT(errorHard, 2.0 * errorSoft);
}

TEST_F(AreaLightGpuTest, PartlyHiddenLightGivesThePartItSees) {
    // A 2 m panel 1 m above the plane, over x in [0, 2]; the orthographic camera sees x, z in [-1, 1]
    // only. A slab 0.5 m up over x in [1.1, 2.5], beside the view, hides the panel's far part from the
    // plane's visible right half: a receiver at x = 0.8 sees about half of the panel. Each VPL has its
    // own visibility (§5.3.3), so such a receiver must get the light of the part it sees. The slab is
    // outside the camera's frustum and so outside the screen-space voxels (the thesis's grid holds what
    // the camera sees); area-light's second grid along the light (voxelOutside) holds it.
    Light light = ceilingLight(1.0f, 2.0f, glm::vec3(2.0f));
    light.position.x = 1.0f;
    Scene scene = gputest::planeScene(light, Projection::Orthographic);
    scene.camera.orthoHeight = 2.0f;
    MeshBuilder b("slab");
    b.axisBox({1.1f, 0.5f, -1.5f}, {2.5f, 0.52f, 1.5f});
    scene.meshes.push_back(b.take());
    Object o;
    o.name = "slab";
    o.mesh = static_cast<uint32_t>(scene.meshes.size() - 1);
    scene.objects.push_back(o);
    ASSERT_TRUE(finalizeScene(scene).ok());
    constexpr int kSize = 64;
    const Image ref = directReference(scene, kSize, 512);
    const AreaRun run = renderAreaLight(scene, {}, kSize);
    const AreaRun open = renderAreaLight(scene, {{"visibility", "none"}}, kSize);
    const AreaRun screenOnly = renderAreaLight(scene, {{"voxelOutside", "false"}}, kSize);
    double error = 0.0, errorScreenOnly = 0.0, seen = 0.0;
    int partial = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const float lit = luminance(open.direct.at(x, y)), r = luminance(ref.at(x, y));
            if (!(lit > 0.0f) || r > 0.8f * lit || r < 0.2f * lit) continue;  // the partly hidden receivers
            ++partial;
            seen += r / lit;
            error += std::abs(luminance(run.direct.at(x, y)) - r) / r;
            errorScreenOnly += std::abs(luminance(screenOnly.direct.at(x, y)) - r) / r;
        }
    ASSERT_GT(partial, 200);
    error /= partial;
    errorScreenOnly /= partial;
    RecordProperty("partlyHiddenPixels", std::to_string(partial));
    RecordProperty("meanFractionSeen", std::to_string(seen / partial));
    RecordProperty("meanRelativeError", std::to_string(error));
    RecordProperty("meanRelativeErrorScreenGridOnly", std::to_string(errorScreenOnly));
    EXPECT_LT(error, 0.1);
}

TEST_F(AreaLightGpuTest, IncrementalVisibilityCastsFewerRaysAndAgreesWithBruteForce) {
    auto scene = loadScene("cornell-box-area");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 128;
    const AreaRun incremental = renderAreaLight(*scene, {}, kSize);
    const AreaRun brute = renderAreaLight(*scene, {{"visibility", "brute"}}, kSize);
    const double cast = incremental.counters.at("raysCast"), reused = incremental.counters.at("raysReused");
    const double bruteCast = brute.counters.at("raysCast");
    RecordProperty("raysCastIncremental", std::to_string(cast));
    RecordProperty("raysReusedIncremental", std::to_string(reused));
    RecordProperty("raysCastBrute", std::to_string(bruteCast));
    RecordProperty("partiallyVisibleFraction", std::to_string(incremental.counters.at("partiallyVisibleFraction")));
    EXPECT_EQ(brute.counters.at("raysReused"), 0.0);
    EXPECT_GT(reused, 0.0);
    // Reuse must pay: at 128^2 only two levels exist (64^2 and 128^2), so at most the finer level's
    // rays are saved; measured 0.36; 0.6 fails if reuse stops working.
    EXPECT_LT(cast, 0.6 * bruteCast);
    // The reused bits are the ones the coarse level agreed on: the images agree closely (relMse of
    // the incremental image against brute force: measured 3.5e-4; reusing a bit also where the coarse
    // cells disagree gives 0.052).
    const float emitted = luminance(scene->lights[0].radiance);
    auto [a, b] = receiversOnly(incremental.direct, brute.direct, emitted);
    const double error = relMse(a, b);
    RecordProperty("relMseAgainstBrute", std::to_string(error));
    EXPECT_LT(error, 0.004);
}

TEST_F(AreaLightGpuTest, TexturedLightColoursTheReceiverUnderEachHalf) {
    // A two-colour panel (left half red, right half green, seen from below) over the plane: the plane
    // under the red half is red, under the green half green, and the total equals the untextured
    // panel's times the texture mean (the VPLs carry the block averages).
    Light light = ceilingLight(0.6f, 2.0f, glm::vec3(4.0f));
    Scene scene = gputest::planeScene(light, Projection::Orthographic);
    TextureImage tex;
    tex.name = "halves";
    tex.image = Image(16, 16);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) tex.image.at(x, y) = x < 8 ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    scene.textures.push_back(tex);
    scene.lights[0].texture.kind = AreaTexture::Kind::Images;
    scene.lights[0].texture.frames = {static_cast<uint32_t>(scene.textures.size() - 1)};
    const Scene untextured = gputest::planeScene(light, Projection::Orthographic);
    constexpr int kSize = 64;
    const AreaRun run = renderAreaLight(scene, {{"visibility", "none"}}, kSize);
    const AreaRun plain = renderAreaLight(untextured, {{"visibility", "none"}}, kSize);
    // The light's u axis is world +x; the orthographic camera looks down with up = -z, so image x is
    // world x: the left image half lies under the texture's u < 1/2 (red) half.
    const glm::vec3 left = run.direct.at(kSize / 4, kSize / 2), right = run.direct.at(3 * kSize / 4, kSize / 2);
    EXPECT_GT(left.r, 3.0f * left.g);
    EXPECT_GT(right.g, 3.0f * right.r);
    double sumRG = 0.0, sumPlain = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            sumRG += double(run.direct.at(x, y).r) + run.direct.at(x, y).g;
            sumPlain += plain.direct.at(x, y).r;
        }
    // Red + green of the textured light = one channel of the untextured one (each texel is 1 in
    // exactly one of the two channels).
    EXPECT_NEAR(sumRG / sumPlain, 1.0, 0.01);
    // Like for like with the path tracer, which samples the texture exactly (importance by texel
    // luminance): the 256 VPLs' block averages and the plane's sharp colour edge under the panel's
    // seam are within relMSE 0.01 (the VPL sum alone is exact to 1e-3, see above).
    // (The full-BRDF path: the reference's vectorised diffuse-only kernel does not read emission
    // textures; see docs/techniques/area-light.md.)
    const Image ref = directReference(scene, kSize, 512, 0, false);
    const double error = relMse(run.direct, ref);
    RecordProperty("relMseTextured", std::to_string(error));
    EXPECT_LT(error, 0.01);
}

TEST_F(AreaLightGpuTest, AreaScreenAgainstThePathTracer) {
    // The thesis's set-up (built-in area-screen: a textured, animated 1.6 m x 0.9 m screen over
    // diffuse and glossy objects), frame 2, against `bounce reference --bounces 0`.
    auto scene = loadScene("area-screen");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    constexpr int kSize = 96;
    PathTracerSettings pts;
    pts.width = pts.height = kSize;
    pts.samplesPerPixel = 256;
    pts.bounces = 0;
    pts.frame = 2;
    auto tracer = PathTracer::create(*scene, pts);
    ASSERT_TRUE(tracer.ok());
    const Image ref = tracer->render().radiance;
    auto p = makePipeline(*scene, "area-light", {}, kSize);
    p->renderFrame(2);
    const Image test = p->readback(Component::Direct);
    auto m = compareImages(test, ref);
    ASSERT_TRUE(m.ok());
    const double energy = totalRadiance(test) / totalRadiance(ref);
    RecordProperty("flipHdr", std::to_string(m->flipHdr));
    RecordProperty("energyRatio", std::to_string(energy));
    // The hard-shadow `direct` pass beside it, over the whole image and over the receivers (the screen's
    // pixels and their neighbours zeroed in both).
    auto hard = makePipeline(*scene, "direct", {}, kSize);
    hard->renderFrame(2);
    const Image hardImage = hard->readback(Component::Direct);
    auto [test2, ref2] = withoutEmitters(test, ref, *p, *scene);
    auto [hard2, ref3] = withoutEmitters(hardImage, ref, *p, *scene);
    const double whole = relMse(test, ref), wholeHard = relMse(hardImage, ref);
    const double receivers = relMse(test2, ref2), receiversHard = relMse(hard2, ref3);
    RecordProperty("relMseWholeImage", std::to_string(whole));
    RecordProperty("relMseWholeImageHardShadows", std::to_string(wholeHard));
    RecordProperty("relMseReceivers", std::to_string(receivers));
    RecordProperty("relMseReceiversHardShadows", std::to_string(receiversHard));
    // Measured energy 0.998, HDR-FLIP 0.17 (the glossy objects' terminators over-occluded by the
    // voxels, the lobe quadrature); bounds with room for the path tracer's noise at 256 spp.
    EXPECT_NEAR(energy, 1.0, 0.05);
    EXPECT_LT(m->flipHdr, 0.25);
    // The bound, at most half the hard-shadow pass's relMSE: whole image measured 0.024 against
    // 10.8 (the G-buffer's screen, point-sampled through a trilinear filter, blends the colour bars'
    // primaries into pixels the reference shows pure: the relMSE's 0.01 epsilon makes each such channel
    // cost thousands); over the receivers 0.021 against 0.80 (the soft shadows, and the bars' colours,
    // which `direct` replaces by the screen's mean).
    EXPECT_LT(whole, 0.5 * wholeHard);
    EXPECT_LT(receivers, 0.5 * receiversHard);
}

TEST_F(AreaLightGpuTest, AnimatedTextureMovesTheLightOnTheReceiver) {
    // The bouncing square (thesis Fig. 5.15): the floor's brightest region follows the square; a
    // technique that froze its VPLs after frame 0 would show the same image at frame 40.
    Light light = ceilingLight(0.4f, 2.0f, glm::vec3(20.0f));
    light.texture.kind = AreaTexture::Kind::BouncingSquare;
    light.texture.squareSize = 0.25f;
    Scene scene = gputest::planeScene(light, Projection::Orthographic);
    constexpr int kSize = 64;
    auto p = makePipeline(scene, "area-light", {{"visibility", "none"}}, kSize);
    auto centroid = [&](uint32_t frame) {
        p->renderFrame(frame);
        const Image img = p->readback(Component::Direct);
        glm::dvec2 c(0.0);
        double w = 0.0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const double l = luminance(img.at(x, y));
                c += l * glm::dvec2(x + 0.5, y + 0.5);
                w += l;
            }
        return glm::vec2(c / w / double(kSize));  // image fraction
    };
    for (uint32_t frame : {0u, 40u}) {
        const glm::vec2 got = centroid(frame);
        const glm::vec2 uv = bouncingSquareCentre(scene.lights[0].texture, scene.timeOfFrame(frame));
        // The square's centre on the plane: world x = (u - 1/2) |edgeU|, z = (v - 1/2) |edgeV| (edgeU
        // is +x, edgeV +z); the orthographic view spans [-kPlaneHalf, kPlaneHalf] with image x = world
        // x and image row 0 at -z.
        const glm::vec2 square = 0.5f + (uv - 0.5f) * (2.0f / (2.0f * kPlaneHalf));
        SCOPED_TRACE(frame);
        // The light's glow spreads beyond the square and the plane clips it: the centroid sits within
        // 0.08 (of the image) of the square's centre, far closer than the 0.2 the square moves.
        EXPECT_NEAR(got.x, square.x, 0.08f);
        EXPECT_NEAR(got.y, square.y, 0.08f);
    }
    const glm::vec2 a = bouncingSquareCentre(scene.lights[0].texture, scene.timeOfFrame(0));
    const glm::vec2 b = bouncingSquareCentre(scene.lights[0].texture, scene.timeOfFrame(40));
    ASSERT_GT(glm::length(a - b), 0.2f) << "the test needs the square to move";
}

TEST_F(AreaLightGpuTest, ReceiversBehindAOneSidedLightAreCulled) {
    // The panel faces away from the plane (emits upwards): every plane cell is behind the one-sided
    // light and is culled by the stencil (§5.3.2); nothing is gathered and the plane stays black.
    Light light = ceilingLight(1.0f, 1.0f, glm::vec3(4.0f));
    std::swap(light.edgeU, light.edgeV);  // cross(edgeU, edgeV) = +y
    const Scene scene = gputest::planeScene(light, Projection::Orthographic);
    const AreaRun run = renderAreaLight(scene, {}, 64);
    EXPECT_EQ(run.counters.at("gatherFragments"), 0.0);
    EXPECT_EQ(run.counters.at("raysCast"), 0.0);
    // The plane outside the emitter's footprint (the camera sees the panel's lit face from above).
    EXPECT_EQ(run.direct.at(4, 4), glm::vec3(0.0f));
    EXPECT_EQ(run.direct.at(32, 4), glm::vec3(0.0f));
    // Two-sided, the same panel lights the plane.
    Scene twoSided = scene;
    twoSided.lights[0].twoSided = true;
    const AreaRun lit = renderAreaLight(twoSided, {}, 64);
    EXPECT_GT(lit.counters.at("gatherFragments"), 0.0);
    EXPECT_GT(luminance(lit.direct.at(32, 4)), 0.0f);
}

TEST_F(AreaLightGpuTest, RefusesScenesWithOtherLights) {
    Light point;
    point.name = "bulb";
    point.type = LightType::Point;
    point.position = {0, 1, 0};
    point.intensity = glm::vec3(1.0f);
    const Scene scene = gputest::planeScene(point);
    auto t = createTechnique("area-light");
    ASSERT_TRUE(t.ok());
    auto p = Pipeline::create(scene, std::move(*t), {32, 32}, smallRenderSettings());
    ASSERT_FALSE(p.ok());
    EXPECT_NE(p.error().message.find("'bulb' is not an area light"), std::string::npos) << p.error().message;
}

TEST_F(AreaLightGpuTest, SpecularPassMatchesTheReferenceOnAGlossyPlane) {
    // A glossy metal plane (GGX roughness 0.4, metallic) seen at an angle reflects the panel: the
    // separate specular pass (§5.3.2.1) against the path tracer's direct light with the full BRDF.
    Scene scene = gputest::planeScene(ceilingLight(1.0f, 1.0f, glm::vec3(4.0f)));
    scene.materials[0].metallic = 1.0f;
    scene.materials[0].roughness = 0.4f;
    scene.materials[0].baseColor = glm::vec3(0.9f);
    scene.camera.position = {0.0f, 1.2f, 3.2f};
    scene.camera.target = {0.0f, 0.0f, -0.5f};
    scene.camera.up = {0.0f, 1.0f, 0.0f};
    ASSERT_TRUE(finalizeScene(scene).ok());
    constexpr int kSize = 64;
    const Image ref = directReference(scene, kSize, 1024, 0, false);
    const AreaRun withSpecular = renderAreaLight(scene, {}, kSize);
    const AreaRun diffuseOnly = renderAreaLight(scene, {{"specular", "false"}}, kSize);
    const float emitted = luminance(scene.lights[0].radiance);
    auto [a, r1] = receiversOnly(withSpecular.direct, ref, emitted);
    auto [b, r2] = receiversOnly(diffuseOnly.direct, ref, emitted);
    const double error = relMse(a, r1), errorWithout = relMse(b, r2);
    RecordProperty("relMseSpecular", std::to_string(error));
    RecordProperty("relMseWithoutSpecularPass", std::to_string(errorWithout));
    RecordProperty("energyRatioSpecular", std::to_string(totalRadiance(a) / totalRadiance(r1)));
    EXPECT_GT(withSpecular.counters.at("specularFragments"), 0.0);
    // Without the pass a metal shows nothing at all (its diffuse lobe is zero).
    EXPECT_GT(errorWithout, 3.0 * error);
    EXPECT_EQ(totalRadiance(b), 0.0);
    // The per-pixel Schlick factor at N.V instead of per VPL direction, the cell-mean normals and
    // the lobe's VPL or 5x5 quadrature leave about 5 % (measured, docs); 0.1 bounds it.
    EXPECT_LT(error, 0.1);
    EXPECT_NEAR(totalRadiance(a) / totalRadiance(r1), 1.0, 0.1);
    // Nothing occludes the plane's view of the panel, and most rays leave the camera's view (the
    // panel is above it), where the second voxel grid tests them: with visibility the image must
    // equal the one without. A draw of more VPLs than the shader loop budget allows (llvmpipe ends
    // the loops silently) lost VPLs: 0.978 of the light (measured 1.000).
    const AreaRun open = renderAreaLight(scene, {{"visibility", "none"}}, kSize);
    const double visibleShare = totalRadiance(withSpecular.direct) / totalRadiance(open.direct);
    RecordProperty("energyWithVisibilityOverWithout", std::to_string(visibleShare));
    EXPECT_GT(visibleShare, 0.995);
}

TEST_F(AreaLightGpuTest, ShadowMapBaselineShadowsLikeTheVoxels) {
    // The §5.4.6 baseline (one rasterized 64^2 paraboloid map per VPL, 1024 VPLs): its penumbra and
    // umbra under the slab agree with the voxel visibility's, and it refuses more than 1024 maps.
    const Light light = ceilingLight(1.5f, 1.0f, glm::vec3(4.0f));
    const Scene scene = planeWithOccluder(light, 0.75f, 0.4f);
    constexpr int kSize = 64;
    const AreaRun maps = renderAreaLight(scene, {{"visibility", "shadow-maps"}, {"vplsPerSide", "32"}}, kSize);
    const AreaRun voxels = renderAreaLight(scene, {{"vplsPerSide", "32"}}, kSize);
    const AreaRun open = renderAreaLight(scene, {{"visibility", "none"}, {"vplsPerSide", "32"}}, kSize);
    EXPECT_EQ(maps.counters.at("raysReused"), 0.0);
    // 0.45 m from the centre, just outside the slab's outline (0.4 m), the plane lies deep in the
    // shadow (umbra to 0.35 m, penumbra to 0.85 m): most of the light is blocked in both.
    const int x = kSize / 2 + static_cast<int>(0.45f * kSize / (2.0f * kPlaneHalf)) + 1;
    const float lit = luminance(open.direct.at(x, kSize / 2));
    EXPECT_LT(luminance(maps.direct.at(x, kSize / 2)), 0.6f * lit);
    EXPECT_LT(luminance(voxels.direct.at(x, kSize / 2)), 0.6f * lit);
    // Whole images within relMSE 0.02: both resolve the same penumbra; the maps' depth bias and the
    // voxels' one-voxel blur move its edge by about a pixel (measured 4e-3).
    EXPECT_LT(relMse(maps.direct, voxels.direct), 0.02);
    auto t = createTechnique("area-light");
    ASSERT_TRUE(t.ok());
    ASSERT_TRUE(applySettings(**t, {{"visibility", "shadow-maps"}, {"vplsPerSide", "64"}}, "area-light").ok());
    auto p = Pipeline::create(scene, std::move(*t), {32, 32}, smallRenderSettings());
    ASSERT_FALSE(p.ok());
    EXPECT_NE(p.error().message.find("at most 1024"), std::string::npos) << p.error().message;
}

TEST_F(AreaLightGpuTest, SharpLobesUseLobeSamplesAndVarianceVisibility) {
    // A near-mirror metal plane (GGX roughness 0.08) reflecting the panel past a slab: lobes too
    // sharp for 256 VPLs switch to the 5x5 lobe-centred texture samples (§5.3.2.1), whose visibility
    // comes from the variance queries (§5.3.3.3). Against the path tracer with the full BRDF.
    // The camera sees the panel's mirror image around z = 1.3 on the plane; the slab hangs half-way
    // between there and the panel, so that it shadows part of the reflection.
    Scene scene = planeWithOccluder(ceilingLight(1.0f, 1.0f, glm::vec3(4.0f)), 0.5f, 0.15f, 0.65f);
    scene.materials[0].metallic = 1.0f;
    scene.materials[0].roughness = 0.08f;
    scene.materials[0].baseColor = glm::vec3(0.9f);
    scene.camera.projection = Projection::Perspective;
    scene.camera.position = {0.0f, 1.0f, 2.6f};
    scene.camera.target = {0.0f, 0.0f, -0.6f};
    scene.camera.up = {0.0f, 1.0f, 0.0f};
    ASSERT_TRUE(finalizeScene(scene).ok());
    constexpr int kSize = 64;
    const Image ref = directReference(scene, kSize, 2048, 0, false);
    const AreaRun variance = renderAreaLight(scene, {}, kSize);
    const AreaRun binary = renderAreaLight(scene, {{"varianceVisibility", "false"}}, kSize);
    const AreaRun vpls = renderAreaLight(scene, {{"lobeVpls", "0"}}, kSize);  // never the 5x5 samples
    const AreaRun open = renderAreaLight(scene, {{"visibility", "none"}}, kSize);
    // The camera sits level with the downward-facing panel, so no emitter pixel is in view: every
    // pixel is a receiver, the light's sharp reflection included.
    auto err = [&](const Image& img) { return relMse(img, ref); };
    const double eVariance = err(variance.direct), eBinary = err(binary.direct), eVpls = err(vpls.direct);
    const double eOpen = err(open.direct);
    RecordProperty("relMseNoVisibility", std::to_string(eOpen));
    RecordProperty("relMseVariance", std::to_string(eVariance));
    RecordProperty("relMseBinary", std::to_string(eBinary));
    RecordProperty("relMseVplsOnly", std::to_string(eVpls));
    RecordProperty("lobeSampledCells", std::to_string(variance.counters.at("lobeSampledCells")));
    EXPECT_GT(variance.counters.at("lobeSampledCells"), 100.0);
    EXPECT_EQ(vpls.counters.at("lobeSampledCells"), 0.0);
    // 256 VPLs alone show the single VPLs' reflections in a sharp lobe (the thesis's reason for the
    // 5x5 samples): the lobe samples must do better.
    EXPECT_LT(eVariance, eVpls);
    EXPECT_LT(eBinary, eVpls);
    EXPECT_LT(eVariance, 0.15);
    // The slab's shadow in the reflection: without visibility the error is several times larger.
    EXPECT_LT(eVariance, eOpen / 2.0);
}

namespace {

// The diffuse pass's cell flags and layer-0 bitstreams of every level, downloaded after a frame.
struct CellRecords {
    std::vector<uint32_t> flags;     // atlas texels
    std::vector<glm::uvec4> bits;    // atlas texels of bitstream layer 0
    glm::ivec2 atlas{0};
    std::vector<glm::ivec2> origins, sizes;

    explicit CellRecords(const AreaLightTechnique& t) {
        const nichols::MultiresBuffer& b = t.diffuseBuffer();
        atlas = b.atlasSize();
        for (int k = 0; k < b.levels(); ++k) {
            origins.push_back(b.levelOrigin(k));
            sizes.push_back(b.levelSize(k));
        }
        const size_t texels = static_cast<size_t>(atlas.x) * atlas.y;
        flags.resize(texels);
        glGetTextureImage(t.cellFlags().id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                          static_cast<GLsizei>(texels * sizeof(uint32_t)), flags.data());
        const int layers = t.bitstreams().desc().depth;
        std::vector<glm::uvec4> all(texels * static_cast<size_t>(layers));
        glGetTextureImage(t.bitstreams().id(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                          static_cast<GLsizei>(all.size() * sizeof(glm::uvec4)), all.data());
        bits.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(texels));
    }
    bool inside(int k, glm::ivec2 c) const { return c.x >= 0 && c.y >= 0 && c.x < sizes[k].x && c.y < sizes[k].y; }
    size_t at(int k, glm::ivec2 c) const { return static_cast<size_t>(origins[k].y + c.y) * atlas.x + origins[k].x + c.x; }
    uint32_t flag(int k, glm::ivec2 c) const { return flags[at(k, c)]; }
    bool tree(int k, glm::ivec2 c) const { return (flag(k, c) & AL_CELL_TREE) != 0u; }
    glm::uvec4 bitsAt(int k, glm::ivec2 c) const { return bits[at(k, c)]; }
};

int parity(glm::ivec2 c) { return (c.x & 1) + 2 * (c.y & 1); }
int popcount(glm::uvec4 v) { return std::popcount(v.x) + std::popcount(v.y) + std::popcount(v.z) + std::popcount(v.w); }

// The thesis's region (§5.3.3.2) of subset s around cell c at level k, by the rule area_common.glsl
// states: the subset's tree cells within two cells of c (2x2 interleaving: a lattice of spacing 2).
// AND and OR of their bits; returns how many there are.
int regionBits(const CellRecords& r, int k, glm::ivec2 c, int s, glm::uvec4& anyBits, glm::uvec4& allBits) {
    anyBits = glm::uvec4(0u);
    allBits = glm::uvec4(0xFFFFFFFFu);
    int n = 0;
    for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
            const glm::ivec2 q = c + glm::ivec2(dx, dy);
            if (!r.inside(k, q) || parity(q) != s || !r.tree(k, q)) continue;
            anyBits |= r.bitsAt(k, q);
            allBits &= r.bitsAt(k, q);
            ++n;
        }
    return n;
}

// The thesis's reuse over every finer level's tree cells: the bits their subset's region around the
// parent agrees on (two or more tree cells), counted; `wrongBits` counts cells whose bits differ from
// the agreed value there.
uint64_t expectedReuse(const CellRecords& r, int& wrongBits) {
    uint64_t reused = 0;
    wrongBits = 0;
    for (int k = 0; k + 1 < static_cast<int>(r.sizes.size()); ++k)
        for (int y = 0; y < r.sizes[k].y; ++y)
            for (int x = 0; x < r.sizes[k].x; ++x) {
                const glm::ivec2 c(x, y);
                if (!r.tree(k, c)) continue;
                glm::uvec4 a, b;
                const glm::ivec2 parent = glm::min(c / 2, r.sizes[k + 1] - 1);
                if (regionBits(r, k + 1, parent, parity(c), a, b) < 2) continue;
                const glm::uvec4 agree = ~(a ^ b);  // 64 VPLs: words 0 and 1
                reused += std::popcount(agree.x) + std::popcount(agree.y);
                const glm::uvec4 own = r.bitsAt(k, c);
                wrongBits += ((own.x ^ a.x) & agree.x) != 0u || ((own.y ^ a.y) & agree.y) != 0u;
            }
    return reused;
}

}  // namespace

TEST_F(AreaLightGpuTest, IncrementalVisibilityFollowsTheThesissRules) {
    // The slab under the panel at 64^2 with levels 16^2, 32^2, 64^2 (coarsest=16), every receiver facing
    // the light (no VPL is culled), the colour threshold out of reach so that only the bit count flags
    // cells for refinement. The cells' flags and bitstreams are downloaded and the rules of §5.3.3.2 are
    // recomputed on the CPU (2x2 interleaving: 64 VPLs of a cell's subset, one bit each):
    //  - reuse: a child's VPL bit comes from the parent level when its subset's tree cells in the 3x3
    //    region around the parent (2 to 9 of them) agree on it; the old 3x3 block of cells held one
    //    same-parity parent for a quarter of the children, whose "agreement" was vacuous;
    //  - bit count: the VPLs whose bits differ in their subset's region, over all four subsets (the old
    //    3x3 block of cells never saw the cell's own subset: at most 192 of 256); at least
    //    bitCountFraction (thesis: half) of all VPLs flags the cell;
    //  - partiallyVisibleFraction = partially visible / examined VPLs (not / every VPL of every cell).
    // All integer logic: the GPU must match exactly.
    const Light light = ceilingLight(1.5f, 1.0f, glm::vec3(4.0f));
    const Scene scene = planeWithOccluder(light, 0.75f, 0.4f);
    constexpr int kSize = 64, kLevels = 3, kVpls = 256, kPerCell = 64;
    auto p = makePipeline(scene, "area-light", {{"coarsest", "16"}, {"colourThreshold", "1e9"}}, kSize);
    const Counters counters = p->renderFrame(0).counters;
    const auto& technique = dynamic_cast<const AreaLightTechnique&>(p->technique());
    const CellRecords r(technique);
    ASSERT_EQ(r.sizes.size(), static_cast<size_t>(kLevels));
    const int threshold = kVpls / 2;  // bitCountFraction's default, 0.5: 128 of 256
    uint64_t partialSum = 0, examinedSum = 0, treeCells = 0, flagged = 0;
    int wrongFlags = 0, wrongBits = 0;
    for (int k = 0; k < kLevels; ++k)
        for (int y = 0; y < r.sizes[k].y; ++y)
            for (int x = 0; x < r.sizes[k].x; ++x) {
                const glm::ivec2 c(x, y);
                if (!r.tree(k, c)) continue;
                ++treeCells;
                int partial = 0;
                for (int s = 0; s < 4; ++s) {
                    glm::uvec4 a, b;
                    if (regionBits(r, k, c, s, a, b) < 2) continue;
                    partial += popcount(a & ~b);
                    examinedSum += kPerCell;
                }
                partialSum += partial;
                const bool refine = partial >= threshold;
                flagged += refine;
                wrongFlags += refine != ((r.flag(k, c) & AL_CELL_REFINE) != 0u);
            }
    const uint64_t expectedReused = expectedReuse(r, wrongBits);
    RecordProperty("treeCells", std::to_string(treeCells));
    RecordProperty("flaggedByBitCount", std::to_string(flagged));
    RecordProperty("partiallyVisibleFraction", std::to_string(counters.at("partiallyVisibleFraction")));
    RecordProperty("raysReused", std::to_string(counters.at("raysReused")));
    // The scene exercises both sides of the threshold (measured 1008 tree cells, 311 flagged).
    ASSERT_GT(flagged, treeCells / 10);
    ASSERT_LT(flagged, treeCells - treeCells / 10);
    EXPECT_EQ(wrongFlags, 0) << "cells whose bit-count flag differs from the thesis's rule";
    // Every VPL of an interior cell is examined (measured 254 per cell on average; the border's cells
    // lose a subset or two); the old count saw at most 192 of the 256.
    EXPECT_GT(double(examinedSum) / double(treeCells), 0.95 * kVpls);
    EXPECT_EQ(counters.at("partiallyVisibleVpls"), double(partialSum));
    EXPECT_EQ(counters.at("examinedVpls"), double(examinedSum));
    EXPECT_DOUBLE_EQ(counters.at("partiallyVisibleFraction"), double(partialSum) / double(examinedSum));
    // Reuse: exactly the agreed bits are reused (test record), and they carry the agreed value.
    EXPECT_EQ(counters.at("raysCulled"), 0.0);
    EXPECT_EQ(counters.at("raysReused"), double(expectedReused));
    EXPECT_EQ(counters.at("raysCast") + counters.at("raysReused"), double(treeCells * kPerCell));
    EXPECT_EQ(wrongBits, 0);
    // Every cell refined (bitCountFraction 0: all levels' cells in the tree): at the image's corners a
    // child's subset has one tree cell in its region around the parent, which agrees with nothing
    // and must not be reused (the ray is re-cast).
    auto all = makePipeline(scene, "area-light", {{"coarsest", "16"}, {"colourThreshold", "1e9"}, {"bitCountFraction", "0"}}, kSize);
    const Counters allCounters = all->renderFrame(0).counters;
    const CellRecords allCells(dynamic_cast<const AreaLightTechnique&>(all->technique()));
    int wrongAll = 0;
    const uint64_t reusedAll = expectedReuse(allCells, wrongAll);
    EXPECT_EQ(allCounters.at("raysReused"), double(reusedAll));
    EXPECT_EQ(wrongAll, 0);
}
