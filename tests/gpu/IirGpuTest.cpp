// Incremental instant radiosity (Laine et al. 2007) on the GPU: the VPL budget under light motion,
// flux conservation, comparison mode, the indirect image against the one-bounce path-traced
// reference, temporal flicker, the geometry-aware filter at a crease, and every built-in scene.
#include "GpuTestSupport.h"
#include "core/Image.h"
#include "reference/RayCaster.h"
#include "techniques/iir/LightBasis.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/FlickerMeter.h"
#include "reference/PathTracer.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/iir/IirTechnique.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace bounce;

namespace {

class IirGpuTest : public gputest::GpuTest {};

struct IirRun {
    std::unique_ptr<Pipeline> pipeline;
    IirTechnique* iir = nullptr;
};

// Tiny images and maps keep each test at a few seconds on llvmpipe.
IirRun makeRun(const Scene& scene, int size, std::map<std::string, std::string> settings) {
    auto technique = std::make_unique<IirTechnique>();
    settings.emplace("shadowMapSize", "64");
    auto applied = applySettings(*technique, settings, "technique 'iir'");
    EXPECT_TRUE(applied.ok()) << applied.error().message;
    IirTechnique* raw = technique.get();
    render::RenderSettings rs;
    rs.shadowMapSize = 256;
    auto pipeline = Pipeline::create(scene, std::move(technique), {size, size}, rs);
    EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
    return {pipeline.ok() ? std::move(*pipeline) : nullptr, raw};
}

Scene load(const std::string& name) {
    auto scene = loadScene(name);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : Scene{};
}

glm::dvec3 totalFlux(const IirTechnique& iir) {
    glm::dvec3 sum(0.0);
    for (const glm::vec3& f : iir.sampleFlux()) sum += glm::dvec3(f);
    return sum;
}

// The flux of a scene light from its own parameters, in double, written out here rather than taken
// from IirTechnique::primaryLight or Light::flux (the code under test):
//   spot:        2 pi I0 (1 - cos^(n+1) c) / (n + 1)   (I = I0 cos^n alpha inside the cutoff c <= 90 deg)
//   point:       4 pi I
//   area:        pi L A                                  (one-sided Lambertian rectangle)
//   directional: E pi R^2, R = half the scene diagonal: the flux through the cross-section of the
//                scene's bounding sphere, which iir's far spot lights (docs: "Primary lights"). Its
//                cone of half-angle c = asin(R / D) at D = 100 diagonals carries 4 pi sin^2(c/2) E D^2
//                = E pi R^2 (1 + c^2/4 + ...), i.e. 6e-6 more.
glm::dvec3 analyticFlux(const Scene& scene, const Light& light) {
    const double pi = glm::pi<double>();
    switch (light.type) {
        case LightType::Spot: {
            const double n = light.falloffExponent;
            const double c = std::min(static_cast<double>(light.cutoffAngle), pi / 2.0);
            return glm::dvec3(light.intensity) * (2.0 * pi * (1.0 - std::pow(std::cos(c), n + 1.0)) / (n + 1.0));
        }
        case LightType::Point:
            return glm::dvec3(light.intensity) * (4.0 * pi);
        case LightType::Area:
            return glm::dvec3(light.radiance) * (pi * glm::length(glm::cross(glm::dvec3(light.edgeU), glm::dvec3(light.edgeV))));
        case LightType::Directional: {
            glm::vec3 lo, hi;
            scene.bounds(0.0f, lo, hi);
            const double radius = 0.5 * glm::length(glm::dvec3(hi) - glm::dvec3(lo));
            return glm::dvec3(light.irradiance) * (pi * radius * radius);
        }
    }
    return glm::dvec3(0.0);
}

double luminanceMean(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
    return sum / static_cast<double>(image.pixelCount());
}

}  // namespace

TEST_F(IirGpuTest, BudgetIsKeptAndFluxConservedWhileTheLightMoves) {
    const Scene scene = load("cornell-box-dynamic");
    constexpr uint32_t kMaxLights = 48;
    IirRun run = makeRun(scene, 32, {{"maxLights", std::to_string(kMaxLights)}});
    ASSERT_TRUE(run.pipeline);
    // Frames 3 apart: the spot moves by a few centimetres per step, enough to invalidate VPLs.
    for (uint32_t frame = 0; frame < 30; frame += 3) {
        const FrameStats stats = run.pipeline->renderFrame(frame);
        const VplDistribution* dist = run.iir->distribution();
        ASSERT_NE(dist, nullptr);
        const uint32_t invalid = static_cast<uint32_t>(stats.counters.at("vplsInvalidated"));
        // §4.2: every frame frees recalcMin slots and refills up to recalcMax, so the budget stays
        // full unless more than recalcMax - recalcMin = 4 samples went invalid at once.
        if (frame == 0 || invalid <= 4) {
            EXPECT_EQ(dist->sampleCount(), kMaxLights) << "frame " << frame;
        } else {
            EXPECT_GE(dist->sampleCount() + invalid, kMaxLights) << "frame " << frame;
        }
        if (frame > 0) {
            EXPECT_LE(stats.counters.at("vplShadowMaps"), 8.0) << "only new VPLs get maps";
        }
        // Cell areas sum to pi within 1e-9 (core tests); the float fluxes add ~1e-7 each.
        const glm::dvec3 flux = totalFlux(*run.iir);
        const glm::dvec3 expected = analyticFlux(scene, scene.lights[0].at(scene.timeOfFrame(frame)));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c], expected[c], 1e-5 * expected[c]) << "frame " << frame;
    }
}

TEST_F(IirGpuTest, FluxIsConservedForPointAreaAndDirectionalLights) {
    for (const std::string name : {"two-rooms", "cornell-box-area", "atrium"}) {
        const Scene scene = load(name);
        IirRun run = makeRun(scene, 16, {{"maxLights", "32"}});
        ASSERT_TRUE(run.pipeline);
        run.pipeline->renderFrame(0);
        // The light's analytic flux (not primaryLight(), which is what the technique itself uses).
        const glm::dvec3 expected = analyticFlux(scene, scene.lights[0].at(0.0f));
        const glm::dvec3 flux = totalFlux(*run.iir);
        ASSERT_GT(expected.r + expected.g + expected.b, 0.0) << name;
        // As above: float fluxes summed over 32 samples (1e-5), plus the directional light's 6e-6.
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c], expected[c], 2e-5 * expected[c]) << name;
    }
}

TEST_F(IirGpuTest, ComparisonModeRegeneratesEveryVplAndMapEachFrame) {
    const Scene scene = load("cornell-box-dynamic");
    IirRun run = makeRun(scene, 16, {{"maxLights", "32"}, {"incremental", "false"}});
    ASSERT_TRUE(run.pipeline);
    for (uint32_t frame = 0; frame < 4; ++frame) {
        const FrameStats stats = run.pipeline->renderFrame(frame);
        EXPECT_EQ(stats.counters.at("vplSamplesCreated"), 32.0);
        EXPECT_EQ(stats.counters.at("vplShadowMaps"), stats.counters.at("vpls"));
    }
}

// vplMapSamples (GL_SAMPLES_PASSED over the frame's paraboloid maps, read after the frame): a paraboloid
// projects the hemisphere onto the map's inscribed disc, so a map passes at most pi/4 of its 64^2 texels
// (+2 % for the disc's edge texels); in the Cornell box every VPL's hemisphere sees the walls except
// through the open front, so each map passes a good share of them. No maps (incremental, nothing new):
// no counter.
TEST_F(IirGpuTest, MapSamplesCountTheMapsCoveredTexels) {
    const Scene scene = load("cornell-box");
    IirRun run = makeRun(scene, 16, {{"maxLights", "32"}, {"incremental", "false"}});
    ASSERT_TRUE(run.pipeline);
    const FrameStats stats = run.pipeline->renderFrame(0);
    const double maps = stats.counters.at("vplShadowMaps");
    ASSERT_GT(maps, 0.0);
    const double perMap = stats.counters.at("vplMapSamples") / maps;
    RecordProperty("samplesPerMap", std::to_string(perMap));
    const double disc = 3.14159265358979 / 4.0 * 64.0 * 64.0;
    EXPECT_LE(perMap, 1.02 * disc);
    EXPECT_GT(perMap, 0.5 * disc);
}

TEST_F(IirGpuTest, IndirectImageIsCloseToTheOneBounceReference) {
    const Scene scene = load("cornell-box");
    constexpr int kSize = 48;
    IirRun run = makeRun(scene, kSize, {{"maxLights", "64"}});
    ASSERT_TRUE(run.pipeline);
    run.pipeline->renderFrame(0);
    const Image iir = run.pipeline->readback(Component::Indirect);

    PathTracerSettings pts;
    pts.width = pts.height = kSize;
    pts.samplesPerPixel = 256;
    pts.bounces = 1;
    pts.indirectOnly = true;
    pts.diffuseOnly = true;
    auto tracer = PathTracer::create(scene, pts);
    ASSERT_TRUE(tracer.ok()) << tracer.error().message;
    const Image reference = tracer->render().radiance;

    auto metrics = compareImages(iir, reference);
    ASSERT_TRUE(metrics.ok()) << metrics.error().message;
    const double meanRatio = luminanceMean(iir) / luminanceMean(reference);
    std::printf("iir vs reference (cornell-box, 48^2, 64 VPLs): relMSE %.4f, FLIP %.4f, mean ratio %.4f\n",
                metrics->relMse, metrics->flipLdr, meanRatio);
    // The mean indirect radiance: 64 VPLs estimate the one-bounce integral without bias except for the
    // irradiance clamp (removes energy near VPLs) and the 256-spp reference's noise: 15 %.
    EXPECT_NEAR(meanRatio, 1.0, 0.15);
    // Per pixel: VPL noise at 64 VPLs, the clamp in the corners and blocky paraboloid edges: 0.1.
    EXPECT_LT(metrics->relMse, 0.1);
}

TEST_F(IirGpuTest, FlickerOfIncrementalAndComparisonModes) {
    const Scene scene = load("cornell-box-dynamic");
    double flicker[2] = {0.0, 0.0};
    for (int mode = 0; mode < 2; ++mode) {
        IirRun run = makeRun(scene, 32, {{"maxLights", "48"}, {"incremental", mode == 0 ? "true" : "false"}});
        ASSERT_TRUE(run.pipeline);
        FlickerMeter meter;
        for (uint32_t frame = 0; frame < 12; ++frame) {
            run.pipeline->renderFrame(frame);
            ASSERT_TRUE(meter.addFrame(run.pipeline->readback(Component::Indirect)).ok());
        }
        auto f = meter.flicker();
        ASSERT_TRUE(f.ok()) << f.error().message;
        flicker[mode] = *f;
    }
    std::printf("flicker (cornell-box-dynamic, 32^2, 48 VPLs, 12 frames): incremental %.5f, comparison %.5f\n",
                flicker[0], flicker[1]);
    ASSERT_TRUE(std::isfinite(flicker[0]) && std::isfinite(flicker[1]));
    // The paper's claim (§6: "less flickering artifacts than the comparison method using the same
    // number of VPLs"). Both runs are deterministic; measured 0.057 against 0.41 since VPLs keep their
    // interleaving tile (0.23 against 0.41 when tiles were re-dealt every frame), so the margin is wide.
    EXPECT_LT(flicker[0], flicker[1]);
}

TEST_F(IirGpuTest, RendersEveryBuiltinScene) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const std::string& name = info.name;
        const Scene scene = load(name);
        if (scene.hasEmissiveMaterials()) {
            // furnace, lit by emission only: iir's VPLs come from the scene's lights, so it refuses
            // the scene instead of silently dropping the emitted light (Technique::bouncesLightsOnly).
            auto refused = Pipeline::create(scene, std::make_unique<IirTechnique>(), {16, 16}, render::RenderSettings{});
            ASSERT_FALSE(refused.ok()) << name;
            EXPECT_NE(refused.error().message.find("emissive materials"), std::string::npos) << refused.error().message;
            continue;
        }
        // 18 is not a multiple of the 4x4 tiling: the atlas has empty pixels at the tile ends.
        IirRun run = makeRun(scene, 18, {{"maxLights", "16"}});
        ASSERT_TRUE(run.pipeline) << name;
        run.pipeline->renderFrame(0);
        const FrameStats stats = run.pipeline->renderFrame(1);
        const Image indirect = run.pipeline->readback(Component::Indirect);
        const Image direct = run.pipeline->readback(Component::Direct);
        for (const glm::vec3& p : indirect.pixels()) {
            ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b)) << name;
            ASSERT_GE(std::min({p.r, p.g, p.b}), 0.0f) << name;
        }
        if (!scene.lights.empty() && luminanceMean(direct) == 0.0) {
            // furnished-room: its uplight lights only a disc of the ceiling that the camera does not see,
            // so the view holds no direct light to compare with; the indirect light must be there.
            EXPECT_GT(luminanceMean(indirect), 0.0) << name;
            continue;
        }
        const double ratio = luminanceMean(indirect) / std::max(luminanceMean(direct), 1e-30);
        std::printf("iir %s: mean indirect / mean direct %.4f\n", name.c_str(), ratio);
        // A positive, bounded level, not just a finite image: one diffuse bounce off surfaces of
        // albedo <= 0.9 in a closed or half-open scene returns a fraction of the direct light, more
        // in scenes whose visible surfaces are mostly lit indirectly (the spot-lit Cornell boxes, whose
        // pool covers little of the view; two-rooms' dark room; indirect-light, whose window is out of
        // view). Measured at 18^2 with 16 VPLs: cornell-box 0.79, cornell-box-area 0.060,
        // cornell-box-dynamic 0.99, cornell-box-rotating 0.091, two-rooms 0.37, atrium 0.10,
        // indirect-light 0.85; the bounds are 3x outside that range.
        EXPECT_GT(ratio, 0.02) << name;
        EXPECT_LT(ratio, 3.0) << name;
    }
}

namespace {

// Directions drawn from a spot's intensity, I0 cos^n(alpha) for alpha <= c, by rejection (uniform in
// solid angle inside the cone, accepted with probability cos^n): independent of SpotDiscMap.
glm::dvec3 drawSpotDirection(const Light& spot, const LightBasis& basis, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double cosCutoff = std::cos(std::min(static_cast<double>(spot.cutoffAngle), glm::half_pi<double>()));
    for (;;) {
        const double cosAlpha = cosCutoff + (1.0 - cosCutoff) * u(rng);
        if (u(rng) >= std::pow(cosAlpha, static_cast<double>(spot.falloffExponent))) continue;
        const double sinAlpha = std::sqrt(std::max(0.0, 1.0 - cosAlpha * cosAlpha));
        const double phi = glm::two_pi<double>() * u(rng);
        return basis.toWorld(glm::dvec3(sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha));
    }
}

}  // namespace

TEST_F(IirGpuTest, VplFluxMatchesTheMonteCarloShareOfItsVoronoiCell) {
    // §4.7: each VPL carries the flux of the light's directions in its Voronoi cell. After frames of
    // light motion on cornell-box-dynamic (48 VPLs), every sample's flux in the technique (what the
    // accumulation is given) over the spot's analytic flux must equal the share of directions drawn
    // from the spot's intensity that land in its cell (mapped with the distribution's disc map).
    const Scene scene = load("cornell-box-dynamic");
    constexpr uint32_t kMaxLights = 48;
    IirRun run = makeRun(scene, 16, {{"maxLights", std::to_string(kMaxLights)}});
    ASSERT_TRUE(run.pipeline);
    uint32_t frame = 0;
    for (; frame <= 18; frame += 3) run.pipeline->renderFrame(frame);
    frame -= 3;
    const VplDistribution& dist = *run.iir->distribution();
    const Light spot = scene.lights[0].at(scene.timeOfFrame(frame));
    ASSERT_EQ(spot.type, LightType::Spot);
    const LightBasis basis = LightBasis::fromAxis(glm::normalize(glm::dvec3(spot.direction)));
    const glm::dvec3 flux = analyticFlux(scene, spot);
    constexpr int kDraws = 100000;
    std::vector<int> hits(kMaxLights, 0);
    std::mt19937_64 rng(5);
    for (int i = 0; i < kDraws; ++i) {
        const std::optional<glm::dvec3> point = dist.toDomain(drawSpotDirection(spot, basis, rng));
        ASSERT_TRUE(point.has_value());
        SlotId best = 0;
        double bestDistance = std::numeric_limits<double>::infinity();
        for (SlotId slot = 0; slot < kMaxLights; ++slot) {
            if (dist.sample(slot).kind == SampleKind::Empty) continue;
            const double d = glm::distance(*point, dist.sample(slot).domainPoint);
            if (d < bestDistance) bestDistance = d, best = slot;
        }
        ++hits[best];
    }
    double worst = 0.0, lo = 1.0, hi = 0.0;
    for (SlotId slot = 0; slot < kMaxLights; ++slot) {
        if (dist.sample(slot).kind == SampleKind::Empty) continue;
        const double expected = hits[slot] / static_cast<double>(kDraws);
        const double share = run.iir->sampleFlux()[slot].g / flux.g;
        // 5 binomial sigma (48 cells, fixed seed) plus float rounding of the flux.
        const double sigma = std::sqrt(expected * (1.0 - expected) / kDraws);
        EXPECT_NEAR(share, expected, 5.0 * sigma + 1e-6) << "slot " << slot;
        worst = std::max(worst, std::abs(share - expected) / sigma);
        lo = std::min(lo, share);
        hi = std::max(hi, share);
    }
    std::printf("iir VPL flux vs Monte Carlo cell share (frame %u): worst %.2f sigma, shares %.4f..%.4f\n", frame, worst, lo, hi);
}

TEST_F(IirGpuTest, SurvivingVplsKeepTheirInterleavingTile) {
    // Laine §5.1/§7: VPLs are dealt to the 4x4 tiles in generation order. A VPL that survives into the
    // next frame must stay in its tile, or the interleaving pattern shifts under a still image. Read
    // back from the buffers the accumulation uses: per tile, the VPLs' slots (iir.vpls position.w).
    const Scene scene = load("cornell-box-dynamic");
    constexpr uint32_t kMaxLights = 64, kTiles = 16;
    IirRun run = makeRun(scene, 16, {{"maxLights", std::to_string(kMaxLights)}});
    ASSERT_TRUE(run.pipeline);
    std::vector<int> previousTile(kMaxLights, -1);
    std::vector<uint64_t> previousSerial(kMaxLights, 0);
    int survivors = 0, replaced = 0;
    for (uint32_t frame = 0; frame < 30; frame += 2) {
        run.pipeline->renderFrame(frame);
        const VplDistribution& dist = *run.iir->distribution();
        const uint32_t vplCount = dist.vplCount();
        std::vector<uint32_t> tileData(kTiles + 1 + vplCount);
        run.iir->tileBuffer().download(0, tileData.size() * sizeof(uint32_t), tileData.data());
        std::vector<glm::vec4> vpls(4 * vplCount);
        run.iir->vplBuffer().download(0, vpls.size() * sizeof(glm::vec4), vpls.data());
        std::vector<int> tileOf(kMaxLights, -1);
        for (uint32_t t = 0; t < kTiles; ++t) {
            for (uint32_t k = tileData[t]; k < tileData[t + 1]; ++k) {
                const auto slot = static_cast<SlotId>(vpls[4 * tileData[k]].w);
                ASSERT_LT(slot, kMaxLights);
                EXPECT_EQ(tileOf[slot], -1) << "slot " << slot << " in two tiles";
                tileOf[slot] = static_cast<int>(t);
            }
        }
        for (SlotId slot = 0; slot < kMaxLights; ++slot) {
            const VplSample& s = dist.sample(slot);
            EXPECT_EQ(tileOf[slot] >= 0, s.kind == SampleKind::Vpl) << "frame " << frame << " slot " << slot;
            if (s.kind != SampleKind::Vpl) continue;
            EXPECT_EQ(tileOf[slot], run.iir->tiles().tileOf(slot));
            if (previousTile[slot] >= 0 && previousSerial[slot] == s.serial) {
                ++survivors;
                EXPECT_EQ(tileOf[slot], previousTile[slot]) << "frame " << frame << " slot " << slot;
            } else if (frame > 0) {
                ++replaced;
            }
        }
        for (SlotId slot = 0; slot < kMaxLights; ++slot) {
            previousTile[slot] = tileOf[slot];
            previousSerial[slot] = dist.sample(slot).serial;
        }
    }
    std::printf("iir tiles: %d survivor-frames kept their tile, %d VPLs replaced\n", survivors, replaced);
    EXPECT_GT(survivors, 500);
    EXPECT_GT(replaced, 30);  // the sequence does replace VPLs (each could shift the old dealing)
}

TEST_F(IirGpuTest, NewVplsGetTheirOwnParaboloidMap) {
    // §4.6/§6: a shadow map is rendered for every new VPL. After frame 0 new VPLs reuse the slots (and
    // so the map layers) of deleted ones; a layer left unrendered still holds the old VPL's map. Each
    // map of a VPL created this frame is checked against ray casts from the VPL through its texel
    // centres (static geometry, the map's own frame: x = paraboloidTangent, z = the VPL's normal).
    const Scene scene = load("cornell-box-dynamic");
    constexpr int kMapSize = 64;
    IirRun run = makeRun(scene, 16, {{"maxLights", "32"}});
    ASSERT_TRUE(run.pipeline);
    auto rays = RayCaster::create(scene, 0.0f, GeometryFilter::StaticOnly);
    ASSERT_TRUE(rays.ok()) << rays.error().message;
    int checkedMaps = 0;
    double worstAgreement = 1.0;
    for (uint32_t frame = 0; frame < 24; frame += 3) {
        run.pipeline->renderFrame(frame);
        if (frame == 0) continue;
        const VplDistribution& dist = *run.iir->distribution();
        const float far = run.iir->paraboloidFar();
        for (SlotId slot = 0; slot < 32; ++slot) {
            const VplSample& s = dist.sample(slot);
            if (s.kind != SampleKind::Vpl || s.createdFrame != dist.frameStats().frame) continue;
            std::vector<float> depth(kMapSize * kMapSize);
            glGetTextureSubImage(run.iir->shadowMaps().id(), 0, 0, 0, static_cast<int>(slot), kMapSize, kMapSize, 1,
                                 GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(depth.size() * sizeof(float)), depth.data());
            const glm::vec3 n = run.iir->slotNormal(slot);
            const glm::vec3 t = IirTechnique::paraboloidTangent(n);
            const glm::vec3 b = glm::cross(n, t);
            const glm::vec3 origin = run.iir->paraboloidOrigin(s.positionWorld, n);
            int inside = 0, agree = 0;
            for (int y = 1; y < kMapSize; y += 2) {
                for (int x = 1; x < kMapSize; x += 2) {
                    const glm::vec2 uv = (glm::vec2(x, y) + 0.5f) / float(kMapSize) * 2.0f - 1.0f;
                    const float r2 = glm::dot(uv, uv);
                    if (r2 > 0.9f) continue;  // the rim's grazing directions
                    const float stored = depth[static_cast<size_t>(y * kMapSize + x)];
                    // Only covered texels: without the paper's tessellation, triangles that cross the
                    // hemisphere's horizon are clipped with straight edges in paraboloid space and
                    // leave parts of the map at the clear depth 1 (a known coverage gap, iir.md).
                    if (stored >= 1.0f) continue;
                    ++inside;
                    const glm::vec3 local = glm::vec3(2.0f * uv.x, 2.0f * uv.y, 1.0f - r2) / (1.0f + r2);
                    const glm::vec3 dir = glm::normalize(local.x * t + local.y * b + local.z * n);
                    const std::optional<RayHit> hit = rays->closestHit(origin, dir);
                    const float expected = hit ? std::min(hit->t / far, 1.0f) : 1.0f;
                    // 1 % of the depth range (1 cm): 16-bit depth and the texel's footprint away
                    // from silhouettes; silhouette texels are what the 90 % below leaves out.
                    if (std::abs(stored - expected) < 0.01f) ++agree;
                }
            }
            const double agreement = agree / static_cast<double>(inside);
            worstAgreement = std::min(worstAgreement, agreement);
            EXPECT_GT(agreement, 0.9) << "frame " << frame << " slot " << slot;
            ++checkedMaps;
        }
    }
    std::printf("iir new-VPL maps: %d checked, worst texel agreement with ray casts %.3f\n", checkedMaps, worstAgreement);
    EXPECT_GT(checkedMaps, 10);
}

namespace {

// A floor (y = 0) and a wall (z = -1) meeting in a crease along x, grey Lambertian, lit by a 30-degree
// spot pointing straight down whose cone stops 2 cm short of the wall: every VPL lies on the floor, so
// the floor receives no indirect light at all (both cosines of a coplanar VPL are 0) and the wall all of
// it. Seen orthographically at 45 degrees with the crease across the image's middle: image rows
// 0..size/2-1 (the top half, Image row 0 is the top) are wall, the rest floor.
Scene creaseScene() {
    Scene s;
    s.name = "crease";
    auto quad = [&](const std::string& name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n) {
        Mesh m;
        m.name = name;
        m.positions = {a, b, c, d};
        m.normals.assign(4, n);
        m.indices = {0, 1, 2, 0, 2, 3};
        s.meshes.push_back(m);
        Object o;
        o.name = name;
        o.mesh = static_cast<uint32_t>(s.meshes.size() - 1);
        s.objects.push_back(o);
    };
    quad("floor", {-2, 0, -1}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -1}, {0, 1, 0});
    quad("wall", {-2, 0, -1}, {2, 0, -1}, {2, 2.5f, -1}, {-2, 2.5f, -1}, {0, 0, 1});
    Material grey;
    grey.name = "grey";
    grey.baseColor = glm::vec3(0.5f);
    s.materials.push_back(grey);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 1.0f, -0.4f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.intensity = glm::vec3(20.0f);
    spot.cutoffAngle = glm::radians(30.0f);
    s.lights.push_back(spot);
    s.camera.projection = Projection::Orthographic;
    s.camera.orthoHeight = 1.2f;
    s.camera.target = {0.0f, 0.0f, -1.0f};
    s.camera.position = glm::vec3(0.0f, 0.0f, -1.0f) + 3.0f * glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

double rowMean(const Image& image, int y) {
    double sum = 0.0;
    for (int x = 0; x < image.width(); ++x) sum += double(image.at(x, y).r) + image.at(x, y).g + image.at(x, y).b;
    return sum / (3.0 * image.width());
}

}  // namespace

TEST_F(IirGpuTest, GeometryAwareFilterKeepsFloorAndWallApartAtACrease) {
    const Scene scene = creaseScene();
    constexpr int kSize = 48;
    // 1x1 tiles: every pixel sums all 256 VPLs and the filter has one tap; the filter-free image.
    IirRun unfiltered = makeRun(scene, kSize, {{"maxLights", "256"}, {"shadowMapSize", "128"}, {"tilesX", "1"}, {"tilesY", "1"}});
    ASSERT_TRUE(unfiltered.pipeline);
    unfiltered.pipeline->renderFrame(0);
    const Image u = unfiltered.pipeline->readback(Component::Indirect);
    const int crease = kSize / 2;  // first floor row
    double wallMean = 0.0;
    for (int y = 0; y < crease; ++y) wallMean += rowMean(u, y) / crease;
    ASSERT_GT(wallMean, 0.0);
    for (const std::string kernel : {"box", "tent"}) {
        // 256 VPLs: a wall pixel next to the crease keeps only the wall taps of its window (box: 8 of the
        // 16 interleaved VPL subsets, the same 8 along the whole row; tent: the wall rows of its 7x7).
        IirRun filtered = makeRun(scene, kSize, {{"maxLights", "256"}, {"shadowMapSize", "128"}, {"filter", kernel}});
        ASSERT_TRUE(filtered.pipeline);
        filtered.pipeline->renderFrame(0);
        const Image f = filtered.pipeline->readback(Component::Indirect);
        // The filter's model on the filter-free image: each pixel's weighted mean over the in-image taps
        // of its window that pass the geometry test (wall pixels: rows above the crease), and the same
        // with every tap. Box: 4x4, columns x-2..x+1, rows y-1..y+2 of the top-down Image (gl_FragCoord's
        // y-2..y+1), weight 1. Tent: 7x7 centred, weight (4-|dx|)(4-|dy|).
        const bool tent = kernel == "tent";
        auto model = [&](int y, bool geometryAware) {
            double sum = 0.0;
            for (int x = 0; x < kSize; ++x) {
                double tapSum = 0.0, weights = 0.0;
                for (int dy = tent ? -3 : -1; dy <= (tent ? 3 : 2); ++dy)
                    for (int dx = tent ? -3 : -2; dx <= (tent ? 3 : 1); ++dx) {
                        const int qx = x + dx, qy = y + dy;
                        if (qx < 0 || qy < 0 || qx >= kSize || qy >= kSize) continue;
                        if (geometryAware && qy >= crease) continue;
                        const double w = tent ? double((4 - std::abs(dx)) * (4 - std::abs(dy))) : 1.0;
                        const glm::vec3 p = u.at(qx, qy);
                        tapSum += w * (double(p.r) + p.g + p.b);
                        weights += w;
                    }
                sum += tapSum / (3.0 * weights);
            }
            return sum / kSize;
        };
        for (int y = crease - 2; y < crease; ++y) {
            const double ratio = rowMean(f, y) / model(y, true), boxRatio = model(y, false) / model(y, true);
            std::printf("%s: wall row %d (crease at %d): unfiltered %.4f, filtered %.4f, filtered / model %.4f (geometry-blind model %.4f)\n",
                        kernel.c_str(), y, crease, rowMean(u, y), rowMean(f, y), ratio, boxRatio);
            RecordProperty(kernel + "WallRow" + std::to_string(crease - y) + "Ratio", std::to_string(ratio));
            // A geometry-blind filter would average in the floor taps of zero irradiance: box 2 of 4 rows on
            // the first wall row, 1 on the second (model 0.5, 0.75 of the geometry-aware one); tent 0.43 and
            // 0.64 (the floor rows' weights). What is left is the VPL subsets' noise (the first row keeps
            // part of the 16 subsets, the same along the row): 12 %. Measured on llvmpipe: box 0.961 (second
            // wall row from the crease), 1.072 (first); tent 0.995, 1.006; the unfiltered wall light drops to a quarter of
            // its level 3 rows above in the first row (floor VPLs seen at grazing angles).
            EXPECT_NEAR(ratio, 1.0, 0.12) << kernel << " wall row " << y;
        }
        for (int y = crease; y < crease + 2; ++y) {
            const double floorRow = rowMean(f, y);
            std::printf("%s: floor row %d: filtered %.3g, wall mean %.3g\n", kernel.c_str(), y, floorRow, wallMean);
            // The floor receives nothing; a geometry-blind filter would bring a quarter of the wall's
            // irradiance into the first floor row. 1e-4 of the wall's mean: float rounding of coplanar cosines.
            EXPECT_LT(floorRow, 1e-4 * wallMean) << kernel << " floor row " << y;
            EXPECT_LT(rowMean(u, y), 1e-4 * wallMean) << "floor row " << y << ", unfiltered";
        }
    }
}

namespace {

// Local period-n structure of an image: its luminance differences (horizontal ones along rows, vertical
// ones along columns) cut into segments of kSegment pixels, and the share of their power (Parseval:
// kSegment x the sum of squares) at the segment DFT's frequencies k/n cycles per pixel, k = 1..n-1.
// Segments, because where the steps fall (which interleave residue carries the gradient) changes across
// the image. A smooth image has its differences at frequency 0 (share near 0); a staircase of period n,
// one jump every n pixels, has them spread evenly over the n harmonics (share (n-1)/n); white noise gives
// (n-1)/n too.
double interleaveStepShare(const Image& image, int n) {
    constexpr int kSegment = 16;
    auto lum = [&](int x, int y) {
        const glm::vec3 p = image.at(x, y);
        return 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
    };
    double atPeriod = 0.0, total = 0.0;
    const double twoPi = 2.0 * glm::pi<double>();
    for (int axis = 0; axis < 2; ++axis) {
        const int lines = axis == 0 ? image.height() : image.width();
        const int length = (axis == 0 ? image.width() : image.height()) - 1;
        for (int line = 0; line < lines; ++line) {
            for (int start = 0; start + kSegment <= length; start += kSegment) {
                double d[kSegment];
                for (int i = 0; i < kSegment; ++i) {
                    const int j = start + i;
                    d[i] = axis == 0 ? lum(j + 1, line) - lum(j, line) : lum(line, j + 1) - lum(line, j);
                    total += kSegment * d[i] * d[i];
                }
                for (int k = 1; k < n; ++k) {
                    double re = 0.0, im = 0.0;
                    for (int i = 0; i < kSegment; ++i) {
                        re += d[i] * std::cos(twoPi * k * i / n);
                        im += d[i] * std::sin(twoPi * k * i / n);
                    }
                    atPeriod += re * re + im * im;
                }
            }
        }
    }
    return total > 0.0 ? atPeriod / total : 0.0;
}

}  // namespace

// Issue 30: on the Sponza-class courtyard under the sun, iir's indirect light showed blocky 4x4
// stair-steps on the flat walls that never went away (a static sun keeps the same VPLs). The paper's
// n x m box filter holds each interleaved VPL subset's irradiance over n pixels, so where a few VPLs near
// the receiver (in a few subsets) carry the light's gradient, the output only changes when their
// residue's tap jumps: steps of period n. The tent filter interpolates each subset instead. Seen here on
// the courtyard's sunlit north wall filling the view (every tap of every window on the same plane).
TEST_F(IirGpuTest, NoInterleavingStairStepsOnTheCourtyardsSunlitWall) {
    auto scene = loadScene("courtyard", {{"triangles", "4000"}});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.front().type, LightType::Directional);
    Camera wall = scene->camera;
    wall.position = {0.0f, 3.0f, -4.0f};  // 6 m in front of the north wall (z = -10), the view 4.4 m high
    wall.target = {0.0f, 3.0f, -10.0f};
    wall.verticalFov = glm::radians(40.0f);
    constexpr int kSize = 128;
    std::map<std::string, double> share;
    for (const std::string kernel : {"box", "tent", "1x1"}) {
        std::map<std::string, std::string> settings{{"shadowMapSize", "128"}};
        if (kernel == "1x1") settings.insert({{"tilesX", "1"}, {"tilesY", "1"}});
        else settings.insert({"filter", kernel});
        IirRun run = makeRun(*scene, kSize, settings);
        ASSERT_TRUE(run.pipeline);
        for (uint32_t frame = 0; frame < 3; ++frame) run.pipeline->renderFrame(frame, &wall);
        const Image image = run.pipeline->readback(Component::Indirect);
        ASSERT_GT(luminanceMean(image), 0.0);
        share[kernel] = interleaveStepShare(image, 4);
        std::printf("iir courtyard north wall, %s: share of the differences at period 4 %.4f, mean %.4g\n",
                    kernel.c_str(), share[kernel], luminanceMean(image));
        RecordProperty("stepShare_" + kernel, std::to_string(share[kernel]));
    }
    // Measured on llvmpipe: box (the paper's filter, the code before the fix) 0.547, tent 0.022, and the
    // filter-free 1x1-tiled image of the same VPLs 0.0066 (white noise would give 0.75). Mutations of the
    // tent: equal weights over its 7x7 window 0.988. The bound, 0.1, is 4.5x the tent's share and 5.5x
    // under the box's.
    EXPECT_LT(share["tent"], 0.1);
    EXPECT_GT(share["box"], 0.1);  // the measure sees the steps the paper's box leaves
}
