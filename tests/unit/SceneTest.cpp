// Built-in scenes, scene validation (finalizeScene) and the scene loaders.
#include "scene/Scene.h"
#include "scene/SceneLoader.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

using namespace bounce;

namespace {

const Object* findObject(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return &o;
    return nullptr;
}

const Material* findMaterial(const Scene& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

// World-space bounds of one object at time t.
void objectBounds(const Scene& s, const Object& o, float t, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(1e30f);
    hi = glm::vec3(-1e30f);
    const glm::mat4 m = o.worldFromObject(t);
    for (const glm::vec3& p : s.meshes[o.mesh].positions) {
        const glm::vec3 w(m * glm::vec4(p, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
}

}  // namespace

TEST(BuiltinScenes, AllLoadAndPassFinalize) {
    ASSERT_FALSE(builtinScenes().empty());
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        SCOPED_TRACE(info.name);
        EXPECT_FALSE(info.description.empty());
        Expected<Scene> scene = loadScene(info.name);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        EXPECT_FALSE(scene->objects.empty());
        EXPECT_EQ(scene->source, "builtin:" + info.name);
        // finalizeScene is idempotent on an already finalized scene.
        Scene copy = *scene;
        ASSERT_TRUE(finalizeScene(copy).ok());
        EXPECT_EQ(copy.triangleCount(), scene->triangleCount());
        // Every vertex has a unit normal after finalizing.
        for (const Mesh& m : scene->meshes) {
            ASSERT_EQ(m.normals.size(), m.positions.size());
            for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);  // float normalize
        }
    }
}

TEST(CornellBox, PublishedDimensionsAndNames) {
    Expected<Scene> scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (const char* name : {"floor", "ceiling", "back", "left", "right", "short-block", "tall-block"})
        EXPECT_NE(findObject(*scene, name), nullptr) << name;
    for (const char* name : {"white", "red", "green"}) {
        const Material* m = findMaterial(*scene, name);
        ASSERT_NE(m, nullptr) << name;
        EXPECT_EQ(m->specularF0, 0.0f);  // pure Lambert
        EXPECT_EQ(m->metallic, 0.0f);
        EXPECT_EQ(m->roughness, 1.0f);
    }
    EXPECT_EQ(scene->materials[scene->objects[0].material].name, "white");
    EXPECT_EQ(scene->materials[findObject(*scene, "left")->material].name, "red");
    EXPECT_EQ(scene->materials[findObject(*scene, "right")->material].name, "green");

    // Published data (mm): floor x 0..552.8 (549.6 at the back), z 0..559.2; ceiling at 548.8.
    glm::vec3 lo, hi;
    objectBounds(*scene, *findObject(*scene, "floor"), 0.0f, lo, hi);
    constexpr float kTol = 1e-5f;  // float rounding of mm -> m
    EXPECT_NEAR(lo.x, 0.0f, kTol);
    EXPECT_NEAR(hi.x, 0.5528f, kTol);
    EXPECT_NEAR(hi.z, 0.5592f, kTol);
    EXPECT_NEAR(hi.y, 0.0f, kTol);
    objectBounds(*scene, *findObject(*scene, "ceiling"), 0.0f, lo, hi);
    EXPECT_NEAR(lo.y, 0.5488f, kTol);
    objectBounds(*scene, *findObject(*scene, "tall-block"), 0.0f, lo, hi);
    EXPECT_NEAR(hi.y, 0.330f, kTol);
    EXPECT_NEAR(lo.x, 0.265f, kTol);
    EXPECT_NEAR(hi.x, 0.472f, kTol);
    objectBounds(*scene, *findObject(*scene, "short-block"), 0.0f, lo, hi);
    EXPECT_NEAR(hi.y, 0.165f, kTol);
    EXPECT_NEAR(lo.z, 0.065f, kTol);

    // Walls face into the room: the floor's normal is +y, the ceiling's -y.
    const Mesh& floor = scene->meshes[findObject(*scene, "floor")->mesh];
    EXPECT_GT(floor.normals[0].y, 0.99f);
    const Mesh& ceiling = scene->meshes[findObject(*scene, "ceiling")->mesh];
    EXPECT_LT(ceiling.normals[0].y, -0.99f);

    // Classic camera: (278, 273, -800) mm looking along +z, vertical fov 2 atan(12.5/35) = 39.31 deg.
    EXPECT_NEAR(scene->camera.position.x, 0.278f, kTol);
    EXPECT_NEAR(scene->camera.position.z, -0.800f, kTol);
    EXPECT_NEAR(glm::degrees(scene->camera.verticalFov), 39.31f, 0.01f);  // rounding of the quoted value
    const glm::vec3 view = glm::normalize(scene->camera.target - scene->camera.position);
    EXPECT_NEAR(view.z, 1.0f, 1e-6f);

    ASSERT_EQ(scene->lights.size(), 1u);
    const Light& spot = scene->lights[0];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_NEAR(spot.direction.y, -1.0f, 1e-6f);
    EXPECT_LT(spot.position.y, 0.5488f);
    EXPECT_GT(spot.position.y, 0.5f);
    EXPECT_FALSE(scene->hasEmissiveMaterials());
    for (const Object& o : scene->objects) EXPECT_FALSE(o.isDynamic()) << o.name;
}

TEST(CornellBox, AreaVariantUsesTheMeasuredLightRectangle) {
    Expected<Scene> scene = loadScene("cornell-box-area");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.size(), 1u);
    const Light& light = scene->lights[0];
    EXPECT_EQ(light.type, LightType::Area);
    // 130 mm x 105 mm, emitting downward from the ceiling plane.
    EXPECT_NEAR(light.area(), 0.130f * 0.105f, 1e-7f);  // float rounding
    EXPECT_NEAR(light.areaNormal().y, -1.0f, 1e-6f);
    EXPECT_NEAR(light.position.y, 0.5488f, 1e-6f);
    EXPECT_FALSE(scene->hasEmissiveMaterials());  // the light is not also an emissive mesh
    // The ceiling has an opening where the light is: no ceiling triangle covers the light's centre.
    const Object* ceiling = findObject(*scene, "ceiling");
    ASSERT_NE(ceiling, nullptr);
    const Mesh& m = scene->meshes[ceiling->mesh];
    const glm::vec2 c(light.position.x, light.position.z);
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        glm::vec2 v[3];
        for (int k = 0; k < 3; ++k) v[k] = {m.positions[m.indices[t + k]].x, m.positions[m.indices[t + k]].z};
        // Same-sign edge functions mean the point is inside the triangle (in the xz plane).
        const auto edge = [&](glm::vec2 a, glm::vec2 b) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); };
        const float e0 = edge(v[0], v[1]), e1 = edge(v[1], v[2]), e2 = edge(v[2], v[0]);
        const bool inside = (e0 > 0 && e1 > 0 && e2 > 0) || (e0 < 0 && e1 < 0 && e2 < 0);
        EXPECT_FALSE(inside) << "ceiling triangle " << t / 3 << " covers the light";
    }
}

TEST(CornellBox, DynamicVariantAnimates) {
    Expected<Scene> scene = loadScene("cornell-box-dynamic");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Light& spot = scene->lights[0];
    ASSERT_TRUE(spot.isDynamic());
    EXPECT_EQ(spot.animation.interpolation, Interpolation::CatmullRom);
    const float period = spot.animation.duration();
    EXPECT_GT(period, 1.0f);
    const glm::vec3 p0 = spot.at(0.0f).position, p1 = spot.at(0.25f * period).position;
    EXPECT_GT(glm::length(p1 - p0), 0.05f);  // moved by a good fraction of its 0.12 m orbit radius
    EXPECT_NEAR(glm::length(spot.at(period).position - p0), 0.0f, 1e-5f);  // closed loop
    // Stays under the ceiling, inside the box, pointing down.
    for (float t = 0.0f; t < period; t += 0.1f) {
        const Light l = spot.at(t);
        EXPECT_LT(l.position.y, 0.5488f);
        EXPECT_GT(l.position.x, 0.1f);
        EXPECT_LT(l.position.x, 0.45f);
        EXPECT_NEAR(l.direction.y, -1.0f, 1e-5f);
    }

    for (const Object& o : scene->objects) EXPECT_EQ(o.isDynamic(), o.name == "tall-block") << o.name;
    const Object& tall = *findObject(*scene, "tall-block");
    // A quarter period turns the block by 90 degrees about its vertical axis through its centre.
    const glm::mat4 m0 = tall.worldFromObject(0.0f);
    const glm::mat4 mq = tall.worldFromObject(0.25f * tall.animation.duration());
    const glm::vec3 x0 = glm::normalize(glm::vec3(m0[0])), xq = glm::normalize(glm::vec3(mq[0]));
    EXPECT_NEAR(glm::dot(x0, xq), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::vec3(m0[3]) - glm::vec3(mq[3])), 0.0f, 1e-6f);  // axis stays put
    // At t = 0 it matches the static box.
    Expected<Scene> still = loadScene("cornell-box");
    ASSERT_TRUE(still.ok());
    glm::vec3 lo0, hi0, lo1, hi1;
    objectBounds(*scene, tall, 0.0f, lo0, hi0);
    objectBounds(*still, *findObject(*still, "tall-block"), 0.0f, lo1, hi1);
    EXPECT_NEAR(glm::length(lo0 - lo1) + glm::length(hi0 - hi1), 0.0f, 1e-5f);
}

TEST(SceneLoader, UnknownNameListsBuiltins) {
    Expected<Scene> scene = loadScene("cornel-box");
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("cornell-box"), std::string::npos) << scene.error().message;
}

TEST(SceneLoader, UnknownParameterListsKnownOnes) {
    Expected<Scene> scene = loadScene("cornell-box", {{"bogus", "1"}});
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("bogus"), std::string::npos) << scene.error().message;
}
