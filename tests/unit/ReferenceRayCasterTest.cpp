// The ray-casting service against analytic planes and boxes.
#include "ReferenceTestScenes.h"
#include "reference/RayCaster.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <vector>

using namespace bounce;

namespace {

// Hit distances are computed in float by Embree from float vertices: 1e-5 m covers the rounding of
// metre-scale coordinates (a few ulps of 1.0, which is 1.2e-7).
constexpr float kDistanceTolerance = 1e-5f;

RayCaster makeCaster(const Scene& scene, float time = 0.0f, GeometryFilter filter = GeometryFilter::All) {
    auto caster = RayCaster::create(scene, time, filter);
    EXPECT_TRUE(caster.ok()) << (caster.ok() ? "" : caster.error().message);
    return std::move(caster).value();
}

TEST(ReferenceRayCaster, HitsPlaneAtAnalyticDistance) {
    const Scene scene = testscenes::planeUnderOrthoCamera(0.5f, 1.0f);
    const RayCaster caster = makeCaster(scene);
    EXPECT_EQ(caster.triangleCount(), 2u);
    const glm::vec3 origin(0.3f, 2.0f, -0.1f);
    const glm::vec3 direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.25f));
    const auto hit = caster.closestHit(origin, direction);
    ASSERT_TRUE(hit.has_value());
    const float expectedT = 2.0f / -direction.y;  // plane y = 0
    EXPECT_NEAR(hit->t, expectedT, kDistanceTolerance);
    EXPECT_NEAR(hit->position.y, 0.0f, kDistanceTolerance);
    EXPECT_NEAR(hit->position.x, origin.x + expectedT * direction.x, kDistanceTolerance);
    EXPECT_NEAR(hit->geometricNormal.y, 1.0f, 1e-6f);
    EXPECT_NEAR(hit->shadingNormal.y, 1.0f, 1e-6f);
    EXPECT_TRUE(hit->frontFacing);
    EXPECT_EQ(hit->objectIndex, 0u);
    EXPECT_EQ(hit->materialIndex, 0u);
    EXPECT_LT(hit->triangleIndex, 2u);

    // From below the plane is hit on its back; upwards from above, nothing.
    const auto below = caster.closestHit({0.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
    ASSERT_TRUE(below.has_value());
    EXPECT_FALSE(below->frontFacing);
    EXPECT_NEAR(below->t, 1.0f, kDistanceTolerance);
    EXPECT_FALSE(caster.closestHit(origin, {0.0f, 1.0f, 0.0f}).has_value());
    // tMin and tMax bound the search.
    EXPECT_FALSE(caster.closestHit(origin, direction, 0.0f, 0.9f * expectedT).has_value());
    EXPECT_FALSE(caster.closestHit(origin, direction, 1.1f * expectedT).has_value());
}

TEST(ReferenceRayCaster, HitsInsideOfBoxAtAnalyticDistances) {
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);  // cube [-1, 1]^3 facing inwards
    const RayCaster caster = makeCaster(scene);
    const glm::vec3 origin(0.2f, -0.3f, 0.1f);
    const glm::vec3 directions[] = {{1, 0, 0}, {0, -1, 0}, {0.3f, 0.5f, -0.8f}, {-1, -1, 1}, {0.01f, 0.02f, 1.0f}};
    for (glm::vec3 d : directions) {
        d = glm::normalize(d);
        // Distance to the first face: the smallest positive (+-1 - o_i) / d_i.
        float expected = std::numeric_limits<float>::infinity();
        for (int i = 0; i < 3; ++i)
            if (d[i] != 0.0f) expected = std::min(expected, ((d[i] > 0.0f ? 1.0f : -1.0f) - origin[i]) / d[i]);
        const auto hit = caster.closestHit(origin, d);
        ASSERT_TRUE(hit.has_value());
        EXPECT_NEAR(hit->t, expected, kDistanceTolerance);
        EXPECT_TRUE(hit->frontFacing) << "walls face inwards";
        EXPECT_LT(glm::dot(hit->geometricNormal, d), 0.0f);
    }
    EXPECT_FALSE(caster.occluded(origin, {-0.5f, 0.7f, 0.9f}));
    EXPECT_TRUE(caster.occluded(origin, {3.0f, 0.0f, 0.0f}));
    // Endpoints on the walls do not occlude themselves.
    EXPECT_FALSE(caster.occluded({-1.0f, 0.2f, 0.3f}, {1.0f, -0.4f, 0.5f}));
}

TEST(ReferenceRayCaster, BatchesMatchSingleRays) {
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    const RayCaster caster = makeCaster(scene);
    // 5000 rays: above the threshold where batches are split across threads.
    std::vector<CastRay> rays;
    std::vector<Segment> segments;
    for (int i = 0; i < 5000; ++i) {
        const float a = 0.001f * static_cast<float>(i);
        CastRay r;
        r.origin = {0.5f * std::sin(a * 3.0f), 0.5f * std::cos(a * 5.0f), 0.3f * std::sin(a * 7.0f)};
        r.direction = {std::cos(a * 11.0f), std::sin(a * 13.0f), std::cos(a * 17.0f) - 0.2f};
        r.tMax = (i % 3 == 0) ? 0.5f : std::numeric_limits<float>::infinity();
        rays.push_back(r);
        segments.push_back({r.origin, r.origin + 3.0f * r.direction * static_cast<float>(i % 2)});
    }
    std::vector<std::optional<RayHit>> hits(rays.size());
    std::vector<uint8_t> blocked(segments.size());
    caster.closestHits(rays, hits);
    caster.occluded(segments, blocked);
    int hitCount = 0, blockedCount = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const auto single = caster.closestHit(rays[i].origin, rays[i].direction, rays[i].tMin, rays[i].tMax);
        ASSERT_EQ(single.has_value(), hits[i].has_value()) << i;
        if (single) {
            EXPECT_EQ(single->t, hits[i]->t);
            EXPECT_EQ(single->triangleIndex, hits[i]->triangleIndex);
            ++hitCount;
        }
        EXPECT_EQ(caster.occluded(segments[i].from, segments[i].to), blocked[i] != 0) << i;
        blockedCount += blocked[i];
    }
    // Both outcomes occur, so the comparison means something.
    EXPECT_GT(hitCount, 1000);
    EXPECT_LT(hitCount, 5000);
    EXPECT_GT(blockedCount, 1000);
    EXPECT_LT(blockedCount, 5000);
}

// A dynamic box (it has an animation track) sitting over a static plane: the static-only caster
// sees through it; the full caster finds it where the animation puts it at the requested time.
TEST(ReferenceRayCaster, StaticOnlyIgnoresDynamicObjects) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.5f, 1.0f);
    Mesh box = testscenes::roomMesh(0.25f);
    // Flip the room inside out (swap two indices per triangle) so that its faces point outwards.
    for (size_t t = 0; t + 2 < box.indices.size(); t += 3) std::swap(box.indices[t + 1], box.indices[t + 2]);
    box.name = "box";
    scene.meshes.push_back(box);
    Object mover;
    mover.name = "mover";
    mover.mesh = 1;
    TransformKey k0, k1;
    k0.time = 0.0f;
    k0.translation = {0.0f, 1.0f, 0.0f};
    k1.time = 2.0f;
    k1.translation = {2.0f, 1.0f, 0.0f};
    mover.animation.keys = {k0, k1};
    mover.animation.loop = false;
    scene.objects.push_back(mover);

    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    const RayCaster all = makeCaster(scene, 1.0f, GeometryFilter::All);          // box centred at x = 1
    const RayCaster staticOnly = makeCaster(scene, 1.0f, GeometryFilter::StaticOnly);
    EXPECT_EQ(staticOnly.triangleCount(), 2u);
    const auto onBox = all.closestHit({1.0f, 3.0f, 0.0f}, down);
    ASSERT_TRUE(onBox.has_value());
    EXPECT_EQ(onBox->objectIndex, 1u);
    EXPECT_NEAR(onBox->t, 3.0f - 1.25f, kDistanceTolerance);
    EXPECT_TRUE(onBox->frontFacing);
    const auto throughBox = staticOnly.closestHit({1.0f, 3.0f, 0.0f}, down);
    ASSERT_TRUE(throughBox.has_value());
    EXPECT_EQ(throughBox->objectIndex, 0u);
    EXPECT_NEAR(throughBox->t, 3.0f, kDistanceTolerance);
    // At time 1 s the box has left x = 0.
    const auto atOrigin = all.closestHit({0.0f, 3.0f, 0.0f}, down);
    ASSERT_TRUE(atOrigin.has_value());
    EXPECT_EQ(atOrigin->objectIndex, 0u);
    EXPECT_TRUE(all.occluded({1.0f, 3.0f, 0.0f}, {1.0f, 0.0f, 0.0f}));
    EXPECT_FALSE(staticOnly.occluded({1.0f, 3.0f, 0.0f}, {1.0f, 0.0f, 0.0f}));
}

TEST(ReferenceRayCaster, BadSceneIsAnError) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.5f, 1.0f);
    scene.objects[0].mesh = 7;
    auto caster = RayCaster::create(scene, 0.0f, GeometryFilter::All);
    ASSERT_FALSE(caster.ok());
    EXPECT_NE(caster.error().message.find("plane"), std::string::npos) << caster.error().message;
}

}  // namespace
