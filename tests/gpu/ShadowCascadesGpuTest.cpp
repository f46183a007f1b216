// Directional-light shadows on a scene large against the view (issue 30, docs/rendering.md "Shadows"):
// `direct` on the Sponza-class `courtyard` under the sun against the reference's direct light
// (--bounces 0). The GPU image is rendered at 4x4 samples per pixel and box-filtered, as the reference
// integrates each pixel's footprint, so what is left of the error is the shadows' (aliasing at
// geometric edges would otherwise dominate: docs/rendering.md). Before the view-fitted cascades and the
// receiver-plane bias, the whole-scene 1024^2 map (2.4 cm texels on the 25 m scene) and its PCF kernel
// on sloped receivers left acne over grazing-lit walls and coarse shadow edges.
#include "GpuTestSupport.h"
#include "core/Check.h"
#include "core/DeviceProfile.h"
#include "core/Settings.h"
#include "gpu/Objects.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/NoiseFloor.h"
#include "reference/PathTracer.h"
#include "render/RenderSettings.h"
#include "render/ShadowCascades.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <cmath>
#include <cstdio>

using namespace bounce;

namespace {

class ShadowCascadesGpuTest : public gputest::GpuTest {};

constexpr int kSize = 128;         // compared image, pixels per side
constexpr int kSupersample = 4;    // GPU samples per pixel per axis (box filter)
constexpr const char* kTriangles = "4000";  // CourtyardGpuTest's CI budget: the same layout, coarser meshes

Image boxDown(const Image& in, int factor) {
    Image out(in.width() / factor, in.height() / factor);
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x) {
            glm::vec3 sum(0.0f);
            for (int j = 0; j < factor; ++j)
                for (int i = 0; i < factor; ++i) sum += in.at(x * factor + i, y * factor + j);
            out.at(x, y) = sum / static_cast<float>(factor * factor);
        }
    return out;
}

double relMse(const Image& test, const Image& ref) {
    double sum = 0.0;
    for (int y = 0; y < ref.height(); ++y)
        for (int x = 0; x < ref.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                const double r = ref.at(x, y)[c], d = test.at(x, y)[c] - r;
                sum += d * d / (r * r + kRelMseEpsilon);
            }
    return sum / (3.0 * ref.pixelCount());
}

struct Reference {
    Image radiance;
    double floor = 0.0;  // relMSE of an exact image against this reference (docs/metrics.md)
};

const Reference& courtyardReference() {
    static const Reference ref = [] {
        auto scene = loadScene("courtyard", {{"triangles", kTriangles}});
        BOUNCE_CHECK(scene.ok(), "courtyard loads");
        PathTracerSettings pts;
        pts.width = pts.height = kSize;
        pts.samplesPerPixel = 64;
        pts.bounces = 0;
        auto tracer = PathTracer::create(*scene, pts);
        BOUNCE_CHECK(tracer.ok(), "courtyard traces");
        const PathTracerResult r = tracer->render();
        auto floor = linearNoiseFloor(r.radiance, r.variance);
        BOUNCE_CHECK(floor.ok(), "noise floor");
        return Reference{r.radiance, floor->relMse};
    }();
    return ref;
}

// relMSE of `direct` (4x4 supersampled) against the reference, with the renderer's settings `rs`;
// `textureBytes`: the texture storage live after the frame (gl::liveResources), the pipeline's included.
double directRelMse(const render::RenderSettings& rs, uint64_t* textureBytes = nullptr) {
    auto scene = loadScene("courtyard", {{"triangles", kTriangles}});
    EXPECT_TRUE(scene.ok());
    auto technique = createTechnique("direct");
    EXPECT_TRUE(technique.ok());
    auto pipeline = Pipeline::create(*scene, std::move(*technique), {kSize * kSupersample, kSize * kSupersample}, rs);
    if (!pipeline.ok()) { ADD_FAILURE() << pipeline.error().message; return 1.0; }
    (*pipeline)->renderFrame(0);
    if (textureBytes) *textureBytes = gl::liveResources().textureBytes;
    const Image gpu = boxDown((*pipeline)->readback(Component::Direct), kSupersample);
    return relMse(gpu, courtyardReference().radiance);
}

}  // namespace

TEST_F(ShadowCascadesGpuTest, CourtyardSunMatchesTheReferencesDirectLight) {
    const double floor = courtyardReference().floor;
    const double fitted = directRelMse(render::RenderSettings{});
    std::printf("courtyard sun: relMSE %.5f (reference floor %.5f)\n", fitted, floor);
    // Measured (llvmpipe, 128^2 from 512^2, reference 64 spp, floor 0.00086): 0.0023 at the defaults
    // (0.0025 before the tent-weighted taps and the bilinear compare's exact slack); the mutations of
    // docs/techniques/direct.md's table: 0.0050 with the whole-scene map alone (no fit), 0.056 without
    // the bilinear slack, 0.066 without the receiver-plane bias. 0.0035 is 1.5x the measurement (room
    // for another GL's rasterization of texel edges) and below each mutation.
    EXPECT_LT(fitted, 0.0035);
    EXPECT_GT(fitted, floor);  // a fitted map is not the path tracer: the metric is not saturated
}

TEST_F(ShadowCascadesGpuTest, CascadesAreFinerThanTheWholeSceneMap) {
    render::RenderSettings whole;
    whole.shadowCascades = 0;  // the whole-scene map alone (the receiver-plane bias stays)
    const double fitted = directRelMse(render::RenderSettings{});
    const double single = directRelMse(whole);
    std::printf("courtyard sun: relMSE %.5f with cascades, %.5f with the whole-scene map only\n", fitted, single);
    // Measured 0.0023 against 0.0050 (0.46 of it): at most 0.6 of it leaves room for the reference's
    // noise (floor 0.00086 on both) and fails a fit that gains less than 40 %.
    EXPECT_LT(fitted, 0.6 * single);
}

// The gpu profile's cascade tiles (renderer.cascadeMapSize 4096, docs/techniques/direct.md): finer
// than the llvmpipe profile's 1024 (= shadowMapSize), and the atlas is sized by them.
TEST_F(ShadowCascadesGpuTest, TheGpuProfilesCascadeTilesAreCloserToTheReference) {
    render::RenderSettings gpu;
    applyProfileDefaults(gpu, DeviceProfile::Gpu);
    ASSERT_EQ(gpu.cascadeMapSize, 4096);
    ASSERT_EQ(gpu.shadowMapSize, 1024);  // point and spot maps keep theirs
    uint64_t llvmpipeBytes = 0, gpuBytes = 0;
    const double llvmpipe = directRelMse(render::RenderSettings{}, &llvmpipeBytes);
    const double fine = directRelMse(gpu, &gpuBytes);
    std::printf("courtyard sun: relMSE %.5f with 1024^2 cascade tiles, %.5f with 4096^2 (floor %.5f)\n", llvmpipe, fine,
                courtyardReference().floor);
    // The sun's 2 x 2 atlas (three cascades and the whole-scene map) of DEPTH32F tiles is all that differs.
    EXPECT_EQ(gpuBytes - llvmpipeBytes, 4ull * (4096ull * 4096ull - 1024ull * 1024ull) * 4ull);
    // Measured 0.00215 against 0.00231 here: at 4x4 samples and a 64-spp reference (floor 0.00086) the
    // edges' aliasing and the reference's noise are most of both, so only the order is held (the same
    // reference both times, and llvmpipe renders deterministically); bench/shadows/run.py at 16x16
    // samples and 256 spp measures the tiles themselves (docs/techniques/direct.md).
    EXPECT_LT(fine, llvmpipe);
}

// The directional maps' constant normal offset (renderer.sunShadowBias, 0.5 mm) against the 2 mm that
// point and spot maps keep: the larger offset moves the sun's shadow edges off their occluders and
// leaks light where an occluder meets its receiver (bench/shadows/run.py at 16x16 samples and 4096^2
// tiles: 2.6x against 1.8x the reference's noise on courtyard; docs/techniques/direct.md).
TEST_F(ShadowCascadesGpuTest, TheSunsSmallerNormalOffsetIsCloserToTheReference) {
    render::RenderSettings quarter;
    applyProfileDefaults(quarter, DeviceProfile::Gpu);  // fine tiles: the offset, not the texels, decides
    ASSERT_FLOAT_EQ(quarter.sunShadowBias, 0.0005f);
    render::RenderSettings full = quarter;
    full.sunShadowBias = full.shadowBias;
    const double small = directRelMse(quarter), large = directRelMse(full);
    std::printf("courtyard sun, 4096^2 tiles: relMSE %.6f with a 0.5 mm normal offset, %.6f with 2 mm\n", small, large);
    // Measured 0.002147 against 0.002170 here (the same reference both times, and llvmpipe renders
    // deterministically): at 4x4 samples the edges' aliasing is most of both, so only the order is held,
    // with half the measured difference as margin. Directional lights given shadowBias again (the
    // mutation in direct.md) make the two equal; the taps' box weights (for the tent) or the bilinear
    // slack without its margin reverse them (direct.md's mutations).
    constexpr double kMinGain = 1.1e-5;
    EXPECT_LT(small, large - kMinGain);
}

// The bilinear compare's slack at an inside corner (docs/techniques/direct.md, atrium's north-west
// corner): a north wall (z = 0, facing +z) lit by the sun at 78 degrees incidence and a west wall
// (x = 0, z in [0, kWestDepth]) the sun sees from behind. Every point of the north wall with
// x < kWestDepth |l.x| / l.z lies in the west wall's shadow; near the corner the occluder's depth is
// within the receiver plane's slack of the wall's own, the taps pass and light leaks into the strip.
// The whole-scene map alone at 256^2 (1.8 cm texels over the 4.6 m scene) makes the slack wide.
constexpr float kWestDepth = 0.3f;                     // metres: the shadow reaches x = 3 kWestDepth
constexpr float kCornerView = 4.2f;                    // metres: the orthographic view's height and width
constexpr int kCornerSize = 256;                       // pixels per side
const glm::vec3 kToSun = glm::normalize(glm::vec3(-0.6f, 0.75f, 0.2f));  // l.z = 0.20: 78 degrees

Scene cornerScene() {
    Scene s;
    s.name = "corner";
    Mesh north, west;
    north.name = "north";
    north.positions = {{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {0, 2, 0}};  // counter-clockwise seen from +z
    north.normals.assign(4, glm::vec3(0, 0, 1));
    north.indices = {0, 1, 2, 0, 2, 3};
    west.name = "west";
    west.positions = {{0, 0, 0}, {0, 0, kWestDepth}, {0, 2, kWestDepth}, {0, 2, 0}};  // seen from -x
    west.normals.assign(4, glm::vec3(-1, 0, 0));
    west.indices = {0, 1, 2, 0, 2, 3};
    Material grey;
    grey.name = "grey";
    grey.baseColor = glm::vec3(0.5f);
    s.materials.push_back(grey);
    for (Mesh* m : {&north, &west}) {
        Object o;
        o.name = m->name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        s.meshes.push_back(*m);
        s.objects.push_back(o);
    }
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = -kToSun;
    sun.irradiance = glm::vec3(1.0f);
    s.lights.push_back(sun);
    s.camera.projection = Projection::Orthographic;
    s.camera.orthoHeight = kCornerView;
    s.camera.position = {2.0f, 1.0f, 5.0f};
    s.camera.target = {2.0f, 1.0f, 0.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

TEST_F(ShadowCascadesGpuTest, TheBilinearSlackLeaksLittleLightAtAnInsideCorner) {
    const Scene scene = cornerScene();
    auto technique = createTechnique("direct");
    ASSERT_TRUE(technique.ok());
    render::RenderSettings rs;
    rs.shadowCascades = 0;
    rs.shadowMapSize = 256;
    auto pipeline = Pipeline::create(scene, std::move(*technique), {kCornerSize, kCornerSize}, rs);
    ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
    (*pipeline)->renderFrame(0);
    const Image image = (*pipeline)->readback(Component::Direct);
    double shadowed = 0.0, lit = 0.0, litLeast = 1e30;
    int shadowedPixels = 0, litPixels = 0;
    for (int py = 0; py < kCornerSize; ++py)
        for (int px = 0; px < kCornerSize; ++px) {
            const float x = 2.0f + ((px + 0.5f) / kCornerSize - 0.5f) * kCornerView;
            const float y = 1.0f + (0.5f - (py + 0.5f) / kCornerSize) * kCornerView;
            const double r = image.at(px, py).r;
            if (x > 0.0f && x < 0.8f && y > 0.2f && y < 0.6f) {  // in the west wall's shadow (to x = 0.9)
                shadowed += r;
                ++shadowedPixels;
            } else if (x > 1.2f && x < 3.8f && y > 0.2f && y < 1.8f) {  // in the sun
                lit += r;
                litLeast = std::min(litLeast, r);
                ++litPixels;
            }
        }
    ASSERT_GT(shadowedPixels, 0);
    ASSERT_GT(litPixels, 0);
    lit /= litPixels;
    const double expected = 0.5 / glm::pi<double>() * kToSun.z;  // rho / pi E cos(theta), E = 1
    const double leak = shadowed / shadowedPixels / lit;
    std::printf("inside corner: lit %.6f (expected %.6f, least %.6f), shadowed strip %.4f of it\n", lit, expected, litLeast, leak);
    // The lit wall: exact but for float rounding (no acne at 78 degrees; the slack off gives 0.53 of it).
    EXPECT_NEAR(lit, expected, 1e-3 * expected);
    EXPECT_GT(litLeast, 0.999 * expected);
    // The strip should be dark. Measured 0.0612 with the slack the compare needs at the lookup's position;
    // the whole texel's slope as slack (the code before) 0.0796, a half-texel margin 0.0741. 0.070 is 14 %
    // above the measurement (another GL's rasterisation of the map) and below both.
    EXPECT_LT(leak, 0.070);
}

// The fit itself (no GL): finer cascades first, whole texels, and the texel size of the sphere-fitted
// cascades unchanged when the camera turns (what keeps shadow edges from shimmering).
TEST(ShadowCascadesFit, FinerFirstSnappedAndStableUnderRotation) {
    auto scene = loadScene("courtyard", {{"triangles", kTriangles}});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    glm::vec3 lo, hi;
    scene->bounds(0.0f, lo, hi);
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(hi - lo);
    const glm::vec3 d = glm::normalize(scene->lights[0].direction);
    const glm::mat4 base = glm::ortho(-radius, radius, -radius, radius, radius, 3.0f * radius) *
                           glm::lookAt(centre - 2.0f * radius * d, centre, glm::vec3(0.0f, 1.0f, 0.0f));
    constexpr int kTile = 1024;
    const render::View view = render::cameraView(scene->camera, {kSize, kSize});
    const render::ShadowCascades fit = render::fitShadowCascades(base, radius, view, lo, hi, 3, kTile);
    ASSERT_GE(fit.count, 3);  // at least two view cascades before the whole-scene map on courtyard
    EXPECT_EQ(fit.cascades[fit.count - 1], glm::vec4(0.0f, 0.0f, 1.0f, 2.0f * radius / kTile));
    for (int c = 0; c + 1 < fit.count; ++c) {
        EXPECT_LT(fit.cascades[c].w, fit.cascades[c + 1].w) << c;  // texel sizes grow with distance
        const double texelUv = 1.0 / (fit.cascades[c].z * kTile);
        for (int axis = 0; axis < 2; ++axis) {  // origins on whole texels of the cascade
            const double t = fit.cascades[c][axis] / texelUv;
            EXPECT_NEAR(t, std::round(t), 1e-2) << c;
        }
    }
    // Turn the camera by 2 degrees about the vertical: the first (sphere-fitted) cascade keeps its texel.
    Camera turned = scene->camera;
    const glm::vec3 forward = turned.target - turned.position;
    turned.target = turned.position + glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(2.0f), glm::vec3(0, 1, 0)) *
                                                glm::vec4(forward, 0.0f));
    const render::ShadowCascades again =
        render::fitShadowCascades(base, radius, render::cameraView(turned, {kSize, kSize}), lo, hi, 3, kTile);
    EXPECT_EQ(again.cascades[0].w, fit.cascades[0].w);
}
