// Hemicube radiosity's GL-free parts (van de Hoef 2013): the delta form factors sum to one, pixel
// projection round-trips, the disk approximation against the analytic point-to-disk and disk-to-disk
// form factors, and the patch model (charts, element areas, insets, atlas packing, refusals;
// RadiosityChartTest.cpp: charts of many small triangles and of curved surfaces).
#include "scene/MeshBuilder.h"
#include "scene/SceneLoader.h"
#include "techniques/radiosity/HemicubeMath.h"
#include "techniques/radiosity/PatchModel.h"
#include "techniques/radiosity/radiosity_shared.h"

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace bounce;
using namespace bounce::radiosity;

TEST(RadiosityMath, DeltaFormFactorsSumToOne) {
    // The pixel sums approach the exact hemisphere integral 1 as the pixels shrink (midpoint rule,
    // error O(1/R^2)): measured 1.0021 (R = 16), 1.0005 (32), 1.0001 (64).
    for (int r : {16, 32, 64, 128}) {
        const auto ff = deltaFormFactors(r);
        double sum = 0.0;
        for (float f : ff) sum += f;
        EXPECT_NEAR(sum, 1.0, 0.6 / (double(r) * r)) << r;
    }
}

TEST(RadiosityMath, PixelDirectionsProjectBackToTheirPixel) {
    const HemicubeFrame f = hemicubeFrame(glm::normalize(glm::vec3(0.3f, 0.8f, -0.2f)), 1.1f);
    constexpr int kR = 16;
    for (int face = 0; face < kHemicubeFaces; ++face)
        for (int y = 0; y < (face == 0 ? kR : kR / 2); ++y)
            for (int x = 0; x < kR; ++x) {
                const float u = -1.0f + (x + 0.5f) * 2.0f / kR;
                const float v = face == 0 ? -1.0f + (y + 0.5f) * 2.0f / kR : (y + 0.5f) * 2.0f / kR;
                const glm::vec3 d = f.axis(face) + u * f.right(face) + v * f.up(face);
                int gotFace = -1;
                glm::vec2 px;
                ASSERT_TRUE(projectToHemicube(f, d, kR, gotFace, px));
                EXPECT_EQ(gotFace, face);
                EXPECT_NEAR(px.x, x + 0.5f, 1e-3f);
                EXPECT_NEAR(px.y, y + 0.5f, 1e-3f);
            }
    glm::vec2 px;
    int face;
    EXPECT_FALSE(projectToHemicube(f, -f.normal, kR, face, px)) << "below the horizon";
}

TEST(RadiosityMath, DiskApproximationMatchesAnalyticDisks) {
    // Eq. 2.2.7 with one sample is exact for a receiver on the axis of a facing disk:
    // A / (pi h^2 + A) = r^2 / (h^2 + r^2) with A = pi r^2.
    const float r = 0.3f, h = 0.5f, area = glm::pi<float>() * r * r;
    const glm::vec3 shooterN(0, -1, 0), receiverN(0, 1, 0);
    EXPECT_NEAR(diskFormFactor({0, 0, 0}, receiverN, {{0, h, 0}}, shooterN, area), pointToDiskFormFactor(r, h), 1e-6f);
    // Disk to disk (r1 receiver, r2 shooter): the receiver-area average of the point values with the
    // shooter split into sub-disks; 1.5 % for the disk approximation off the axis.
    const float r1 = 0.2f, r2 = 0.3f;
    std::vector<glm::vec3> samples;
    constexpr int kRings = 24, kSpokes = 48;
    for (int i = 0; i < kRings; ++i)
        for (int j = 0; j < kSpokes; ++j) {
            const float rho = r2 * std::sqrt((i + 0.5f) / kRings), phi = glm::two_pi<float>() * (j + 0.5f) / kSpokes;
            samples.push_back({rho * std::cos(phi), h, rho * std::sin(phi)});
        }
    double sum = 0.0;
    constexpr int kPoints = 400;
    for (int k = 0; k < kPoints; ++k) {
        const float rho = r1 * std::sqrt((k + 0.5f) / kPoints), phi = 2.399963f * k;  // golden-angle spiral
        sum += diskFormFactor({rho * std::cos(phi), 0, rho * std::sin(phi)}, receiverN, samples, shooterN,
                              glm::pi<float>() * r2 * r2);
    }
    const double f12 = sum / kPoints, exact = diskToDiskFormFactor(r1, r2, h);
    EXPECT_NEAR(f12, exact, 0.015 * exact);
    // Reciprocity of the analytic values: A1 F12 = A2 F21.
    EXPECT_NEAR(r1 * r1 * diskToDiskFormFactor(r1, r2, h), r2 * r2 * diskToDiskFormFactor(r2, r1, h), 1e-6);
}

TEST(RadiosityMath, RotationIsDeterministicPerPosition) {
    EXPECT_EQ(rotationAngle({0.1f, 0.2f, 0.3f}), rotationAngle({0.1f, 0.2f, 0.3f}));
    EXPECT_NE(rotationAngle({0.1f, 0.2f, 0.3f}), rotationAngle({0.1f, 0.2f, 0.31f}));
    const HemicubeFrame f = hemicubeFrame({0, 0, 1}, 0.7f);
    EXPECT_NEAR(glm::dot(f.tangent, f.normal), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::cross(f.tangent, f.normal) - f.bitangent), 0.0f, 1e-6f);
}

namespace {

Scene load(const std::string& name, const SceneParams& params = {}) {
    auto s = loadScene(name, params);
    EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
    return std::move(*s);
}

double triangleArea(const Scene& s) {
    double a = 0.0;
    for (const Object& o : s.objects) {
        const Mesh& m = s.meshes[o.mesh];
        const glm::mat3 w(o.worldFromObject(0.0f));
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const glm::vec3 p0 = w * m.positions[m.indices[3 * t]], p1 = w * m.positions[m.indices[3 * t + 1]],
                            p2 = w * m.positions[m.indices[3 * t + 2]];
            a += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        }
    }
    return a;
}

}  // namespace

TEST(RadiosityPatchModel, BuiltinScenesBecomeChartsWithExactAreas) {
    for (const char* name : {"cornell-box-area", "cornell-box-rotating", "furnace", "indirect-light"}) {
        SCOPED_TRACE(name);
        const Scene s = load(name);
        auto pm = PatchModel::build(s, PatchOptions{0.1f, 0.1f});
        ASSERT_TRUE(pm.ok()) << pm.error().message;
        size_t triangles = 0;
        for (const Object& o : s.objects) triangles += s.meshes[o.mesh].triangleCount();
        // Their faces are rectangles (two triangles) or walls of several: a chart has at least two triangles.
        EXPECT_LE(pm->quads().size() - pm->lightQuadCount(), triangles / 2) << "a chart per face or fewer";
        double quadArea = 0.0, lightArea = 0.0;
        for (const Quad& q : pm->quads()) {
            double elementArea = 0.0;
            for (int k = 0; k < q.nu * q.nv; ++k) elementArea += pm->elements()[q.firstElement + k].area;
            EXPECT_NEAR(elementArea, q.area, 1e-5 * q.area);
            ((q.flags & RAD_QUAD_LIGHT) ? lightArea : quadArea) += q.area;
        }
        // Rigid transforms keep areas: the quads cover the triangles exactly.
        EXPECT_NEAR(quadArea, triangleArea(s), 1e-4 * quadArea);
        double lights = 0.0;
        for (const Light& l : s.lights) lights += l.area();
        EXPECT_NEAR(lightArea, lights, 1e-6);
        // Atlas regions do not overlap and stay inside.
        std::set<std::pair<int, int>> used;
        for (const Quad& q : pm->quads())
            for (int j = 0; j < q.nv; ++j)
                for (int i = 0; i < q.nu; ++i) {
                    EXPECT_LT(q.atlasX + i, pm->atlasSize().x);
                    EXPECT_LT(q.atlasY + j, pm->atlasSize().y);
                    EXPECT_TRUE(used.insert({q.atlasX + i, q.atlasY + j}).second);
                }
    }
}

TEST(RadiosityPatchModel, CoplanarCellsBecomeOneChartJunctionsAreInset) {
    // The furnace's walls are 4 x 4 cells (32 triangles each): each wall is one chart of 9 x 9 texels at
    // 0.25 m (2 m walls), its cells sharing the texel grid; samples on the room's edges (a junction with
    // the next wall) sit at their half cell's centroid, a quarter pitch inside.
    const Scene s = load("furnace");
    auto pm = PatchModel::build(s, PatchOptions{0.25f, 0.25f});
    ASSERT_TRUE(pm.ok());
    EXPECT_EQ(pm->quads().size() - pm->lightQuadCount(), 6u) << "one chart per wall";
    for (size_t q = 0; q < pm->quads().size() - pm->lightQuadCount(); ++q) {
        EXPECT_EQ(pm->quads()[q].nu, 9);
        EXPECT_EQ(pm->quads()[q].nv, 9);
    }
    size_t onRoomEdge = 0, inset = 0;
    for (const Element& e : pm->elements()) {
        const glm::vec3 a = glm::abs(e.position);
        const int atWall = (a.x > 0.999f) + (a.y > 0.999f) + (a.z > 0.999f);
        const int nearWall = (a.x > 0.9f) + (a.y > 0.9f) + (a.z > 0.9f);
        if (nearWall >= 2) {
            ++onRoomEdge;
            if (atWall == 1) ++inset;
        }
    }
    EXPECT_GT(onRoomEdge, 0u);
    EXPECT_EQ(inset, onRoomEdge) << "every sample next to another wall is off it";
    for (const Element& e : pm->elements()) {
        const glm::vec3 a = glm::abs(e.position);
        if ((a.x > 0.9f) + (a.y > 0.9f) + (a.z > 0.9f) >= 2) {
            const float off = 1.0f - std::max({a.x > 0.999f ? 0.0f : a.x, a.y > 0.999f ? 0.0f : a.y, a.z > 0.999f ? 0.0f : a.z});
            EXPECT_NEAR(off, 0.25f * 0.25f, 1e-4f) << "a quarter of the 0.25 m pitch";
        }
    }
}

TEST(RadiosityPatchModel, LoneTriangleIsAChartWithGhostTexels) {
    Scene s;
    s.name = "triangle";
    Material m;
    m.emission = glm::vec3(1.0f);
    s.materials = {m};
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    mesh.indices = {0, 2, 1};  // facing +y
    mesh.normals.assign(3, {0, 1, 0});
    s.meshes = {mesh};
    Object o;
    s.objects = {o};
    auto pm = PatchModel::build(s, PatchOptions{0.25f, 0.25f});
    ASSERT_TRUE(pm.ok()) << pm.error().message;
    ASSERT_EQ(pm->quads().size(), 1u);
    const Quad& q = pm->quads()[0];
    EXPECT_NEAR(q.area, 0.5f, 1e-6f);
    double area = 0.0;
    size_t ghosts = 0;
    for (const Element& e : pm->elements()) {
        area += e.area;
        ghosts += e.area == 0.0f;
        EXPECT_LE(e.position.x + e.position.z, 1.0f + 1e-5f) << "samples stay on the triangle, ghosts too";
        EXPECT_GE(std::min(e.position.x, e.position.z), -1e-6f);
    }
    EXPECT_NEAR(area, 0.5, 1e-5);
    // Its tightest rectangles (area 1 m^2) are the legs' square (5 x 5 texels at 0.25 m, 10 of them beyond
    // the hypotenuse) or the hypotenuse's 1.41 x 0.71 m (7 x 4): either way some texels are ghosts.
    EXPECT_LE(pm->elements().size(), 28u);
    EXPECT_EQ(ghosts, pm->elements().size() - pm->activeElementCount());
    EXPECT_GE(ghosts, 4u);
    EXPECT_NEAR(glm::dot(q.normal, glm::vec3(0, 1, 0)), 1.0f, 1e-6f);
}

TEST(RadiosityPatchModel, RefusesWhatItCannotShade) {
    // Point, spot and directional lights make no patches (their light is shot into the elements).
    auto spot = PatchModel::build(load("cornell-box"), {});
    ASSERT_TRUE(spot.ok()) << spot.error().message;
    EXPECT_EQ(spot->lightQuadCount(), 0u);
    auto point = PatchModel::build(load("two-rooms"), {});
    ASSERT_TRUE(point.ok()) << point.error().message;
    EXPECT_EQ(point->lightQuadCount(), 0u);
    auto textured = PatchModel::build(load("area-screen"), {});
    ASSERT_FALSE(textured.ok());
    EXPECT_NE(textured.error().message.find("area light 'screen' is textured"), std::string::npos);
    Scene twoSided = load("cornell-box-area");
    twoSided.lights.at(0).twoSided = true;
    auto both = PatchModel::build(twoSided, {});
    ASSERT_FALSE(both.ok());
    EXPECT_NE(both.error().message.find("is two-sided"), std::string::npos);
    Scene dark = load("furnace", {{"emission", "0"}});
    auto none = PatchModel::build(dark, {});
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().message.find("no light and no emissive material"), std::string::npos);
    auto tooMany = PatchModel::build(load("furnace"), PatchOptions{0.001f, 0.001f});
    ASSERT_FALSE(tooMany.ok());
    EXPECT_NE(tooMany.error().message.find("raise elementSize"), std::string::npos);
}

TEST(RadiosityPatchModel, PunctualDirectRadianceIsRhoECosOverPi) {
    // rho E cos(theta) / pi with E = I / r^2 (point), I cos^n(alpha) / r^2 inside the cone (spot),
    // E_perp (directional): hand-computed values.
    Light point;
    point.type = LightType::Point;
    point.position = {0.0f, 2.0f, 0.0f};
    point.intensity = glm::vec3(8.0f);
    const glm::vec3 up(0.0f, 1.0f, 0.0f), rho(0.5f);
    // Straight below at r = 2: 0.5 * 8 / 4 / pi.
    EXPECT_NEAR(punctualDirectRadiance(point, {0, 0, 0}, up, rho).x, 0.5f * 2.0f / glm::pi<float>(), 1e-6f);
    // At (2, 0, 0): r^2 = 8, cos = 2 / sqrt(8).
    EXPECT_NEAR(punctualDirectRadiance(point, {2, 0, 0}, up, rho).x,
                0.5f * 1.0f * (2.0f / std::sqrt(8.0f)) / glm::pi<float>(), 1e-6f);
    EXPECT_EQ(punctualDirectRadiance(point, {0, 0, 0}, -up, rho).x, 0.0f);  // facing away
    Light spot = point;
    spot.type = LightType::Spot;
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.cutoffAngle = 0.5f;  // radians
    spot.falloffExponent = 2.0f;
    EXPECT_NEAR(punctualDirectRadiance(spot, {0, 0, 0}, up, rho).x, 0.5f * 2.0f / glm::pi<float>(), 1e-6f);
    // alpha = atan(0.5 / 2) = 0.245 < 0.5: cos^2(alpha) cos(theta) I / r^2, cos(theta) = cos(alpha).
    const float r2 = 4.25f, c = 2.0f / std::sqrt(r2);
    EXPECT_NEAR(punctualDirectRadiance(spot, {0.5f, 0, 0}, up, rho).x, 0.5f * 8.0f / r2 * c * c * c / glm::pi<float>(), 1e-6f);
    EXPECT_EQ(punctualDirectRadiance(spot, {2, 0, 0}, up, rho).x, 0.0f);  // outside the cone (45 degrees)
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, -1.0f, -1.0f};
    sun.irradiance = glm::vec3(3.0f);
    EXPECT_NEAR(punctualDirectRadiance(sun, {5, 0, 7}, up, rho).x, 0.5f * 3.0f * std::sqrt(0.5f) / glm::pi<float>(), 1e-6f);
    Light area;
    area.type = LightType::Area;
    area.radiance = glm::vec3(1.0f);
    EXPECT_EQ(punctualDirectRadiance(area, {0, 0, 0}, up, rho).x, 0.0f);
}
