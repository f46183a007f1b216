// Scale-derived defaults in the run record (issue 30): iir's filter threshold, clamp distance and
// shadow bias (fractions of the scene diagonal), vct's voxel grid (a cube around the scene's bounds),
// photon-splat's bundle width and depth tolerance (a twentieth of the diagonal, a twentieth of a
// texel), rsm's and multires-splat's r clamp and rsm-splat's fixed radius are resolved on the scene at setup; `bounce render --stats` prints the values used under
// "derived" (Technique::derivedSettings). The same scene scaled 10x about the origin must report every
// such value 10x, and a value the user set must be reported as set.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "app/RunRecord.h"
#include "core/Settings.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

using namespace bounce;

namespace {

class ScaleDerivedDefaultsGpuTest : public gputest::GpuTest {};

// The scene with every length multiplied by `factor` about the origin: objects, lights (positions and
// area edges), the camera and its clip planes.
Scene scaled(Scene s, float factor) {
    const glm::mat4 scale = glm::scale(glm::mat4(1.0f), glm::vec3(factor));
    for (Object& o : s.objects) o.transform = scale * o.transform;
    for (Light& l : s.lights) {
        l.position *= factor;
        l.edgeU *= factor;
        l.edgeV *= factor;
    }
    s.camera.position *= factor;
    s.camera.target *= factor;
    s.camera.nearPlane *= factor;
    s.camera.farPlane *= factor;
    return s;
}

double diagonal(const Scene& s) {
    glm::vec3 lo, hi;
    s.bounds(0.0f, lo, hi);
    return glm::length(glm::dvec3(hi) - glm::dvec3(lo));
}

// The run record's "derived" object for `technique` on `scene` with `settings`, after setup.
nlohmann::json derivedOf(const Scene& scene, const std::string& technique, const std::map<std::string, std::string>& settings = {}) {
    auto t = createTechnique(technique);
    EXPECT_TRUE(t.ok()) << t.error().message;
    if (!t.ok()) return {};
    auto applied = applySettings(**t, settings, "technique '" + technique + "'");
    EXPECT_TRUE(applied.ok()) << applied.error().message;
    auto pipeline = Pipeline::create(scene, std::move(*t), {32, 32}, render::RenderSettings{});
    EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
    if (!pipeline.ok()) return {};
    const nlohmann::json record = renderRunRecord(scene, **pipeline, {}, gl::Context::current()->info(), nlohmann::json::object());
    EXPECT_TRUE(record.contains("derived"));
    return record.value("derived", nlohmann::json::object());
}

}  // namespace

TEST_F(ScaleDerivedDefaultsGpuTest, RunRecordPrintsThemAndTheyScaleWithTheScene) {
    auto loaded = loadScene("cornell-box");
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const Scene small = *loaded, large = scaled(*loaded, 10.0f);
    const double d = diagonal(small);
    ASSERT_NEAR(diagonal(large), 10.0 * d, 1e-4 * d);
    // Every derived value each technique must print (its doc page lists them).
    const std::map<std::string, std::vector<std::string>> expected{
        {"iir", {"sceneDiagonalMetres", "positionThresholdMetres", "clampDistanceMetres", "shadowBiasMetres"}},
        {"vct", {"boxSideMetres", "boxCentreXMetres", "boxCentreYMetres", "boxCentreZMetres", "voxelSizeMetres",
                 "maxDistanceMetres", "aoDistanceMetres"}},
        {"photon-splat", {"sceneDiagonalMetres", "mapSizeMetres", "depthToleranceMetres"}},
        // sqrt(area / 1000): the area 100x, the size 10x.
        {"radiosity-pr", {"elementSizeMetres", "dynamicElementSizeMetres"}},
        // Eq. 3.2's r clamp (formFactor=point) and rsm-splat's fixed radius (nichols/SceneScale.h).
        {"rsm", {"minDistanceMetres"}},
        {"multires-splat", {"minDistanceMetres"}},
        {"rsm-splat", {"radiusMetres"}},
    };
    for (const auto& [technique, names] : expected) {
        const nlohmann::json a = derivedOf(small, technique), b = derivedOf(large, technique);
        for (const std::string& name : names) {
            ASSERT_TRUE(a.contains(name) && b.contains(name)) << technique << ": no derived " << name;
            const double va = a[name].get<double>(), vb = b[name].get<double>();
            std::printf("%s %s: %.6g m on cornell-box, %.6g m scaled 10x\n", technique.c_str(), name.c_str(), va, vb);
            // float arithmetic on lengths 10x apart: 1e-5 of the scaled value, or of the diagonal for a
            // centre coordinate near 0. A constant (a metric default) would report the same on both.
            EXPECT_NEAR(vb, 10.0 * va, 1e-5 * std::max(std::abs(vb), 10.0 * d)) << technique << " " << name;
        }
    }
    // The defaults as documented, against the diagonal computed here: iir's alpha 0.03, d_c 0.05 and
    // bias 0.004 of the diagonal; photon-splat's bundle width a twentieth of it; vct's cube spans the
    // bounds' largest extent with a voxel of margin on each side (64 voxels: extent x 64 / 62).
    const nlohmann::json iir = derivedOf(large, "iir"), splat = derivedOf(large, "photon-splat"), vct = derivedOf(large, "vct");
    EXPECT_NEAR(iir["positionThresholdMetres"].get<double>(), 0.03 * 10.0 * d, 1e-5 * d);
    EXPECT_NEAR(iir["clampDistanceMetres"].get<double>(), 0.05 * 10.0 * d, 1e-5 * d);
    EXPECT_NEAR(iir["shadowBiasMetres"].get<double>(), 0.004 * 10.0 * d, 1e-5 * d);
    EXPECT_NEAR(splat["mapSizeMetres"].get<double>(), 0.05 * 10.0 * d, 1e-5 * d);
    // rsm's and multires-splat's r clamp 0.05 of the diagonal, rsm-splat's fixed radius 0.3 of it.
    EXPECT_NEAR(derivedOf(large, "rsm")["minDistanceMetres"].get<double>(), 0.05 * 10.0 * d, 1e-5 * d);
    EXPECT_NEAR(derivedOf(large, "multires-splat")["minDistanceMetres"].get<double>(), 0.05 * 10.0 * d, 1e-5 * d);
    EXPECT_NEAR(derivedOf(large, "rsm-splat")["radiusMetres"].get<double>(), 0.3 * 10.0 * d, 1e-5 * d);
    glm::vec3 lo, hi;
    large.bounds(0.0f, lo, hi);
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    EXPECT_NEAR(vct["boxSideMetres"].get<double>(), extent * 64.0 / 62.0, 1e-5 * extent);
    EXPECT_NEAR(vct["boxCentreYMetres"].get<double>(), 0.5 * (lo.y + hi.y), 1e-5 * extent);
    // A value the user set is printed as used.
    EXPECT_NEAR(derivedOf(large, "iir", {{"positionThreshold", "0.06"}})["positionThresholdMetres"].get<double>(),
                0.06 * 10.0 * d, 1e-5 * d);
    EXPECT_NEAR(derivedOf(large, "vct", {{"boxSide", "30"}})["boxSideMetres"].get<double>(), 30.0, 1e-4);
    EXPECT_NEAR(derivedOf(large, "photon-splat", {{"mapSize", "2"}})["mapSizeMetres"].get<double>(), 2.0, 1e-6);
    EXPECT_NEAR(derivedOf(large, "rsm", {{"minDistance", "0.2"}})["minDistanceMetres"].get<double>(), 0.2, 1e-6);
    EXPECT_NEAR(derivedOf(large, "rsm-splat", {{"radius", "0.7"}})["radiusMetres"].get<double>(), 0.7, 1e-6);
}

// Radiosity on a scaled scene: element areas and the pitch are world metres (PatchModel's areaMap), so
// the Cornell box scaled 10x (its objects by their transforms, the light by its edges: the same
// radiance over 100x the area) gives the same image. Object-space areas and pitch (before) gave the
// scaled scene's surfaces 1/100 of their area against the light's world-space quad: 0.60 of the
// indirect light.
TEST_F(ScaleDerivedDefaultsGpuTest, RadiosityIsTheSameOnTheSceneScaled) {
    auto loaded = loadScene("cornell-box-area");
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const Scene small = *loaded, large = scaled(*loaded, 10.0f);
    double indirect[2] = {0.0, 0.0}, full[2] = {0.0, 0.0};
    int k = 0;
    for (const Scene* s : {&small, &large}) {
        auto p = nicholstest::makePipeline(*s, "radiosity-pr", {{"frameBudgetMs", "0"}}, 32);
        p->renderFrame(0);
        indirect[k] = nicholstest::totalRadiance(p->readback(Component::Indirect));
        full[k] = nicholstest::totalRadiance(p->readback(Component::Full));
        ++k;
    }
    std::printf("radiosity-pr indirect %.6g / %.6g, full %.6g / %.6g (cornell-box-area / scaled 10x)\n", indirect[0],
                indirect[1], full[0], full[1]);
    ASSERT_GT(indirect[0], 0.0);
    // Measured: indirect 508.625 / 508.579 (ratio 0.99991), full 1228.62 / 1228.58; before the fix
    // 508.6 / 303.3 (0.596). The bound 2 %: float rounding at another scale only, far inside the 40 %
    // the object-space areas lost.
    EXPECT_NEAR(indirect[1] / indirect[0], 1.0, 0.02);
    EXPECT_NEAR(full[1] / full[0], 1.0, 0.02);
}
