#pragma once
// Shared fixture of the GPU tests: one headless context per test binary. Under CI=true a missing
// context is a failure, elsewhere the GPU tests skip. Every test fails if KHR_debug reported a GL
// error while it ran, and, with BOUNCE_BARRIER_CHECK=1 (gpu/BarrierTracker.h), if a shader-written
// buffer or texture was read without the matching glMemoryBarrier bit.
#include "gpu/BarrierTracker.h"
#include "gpu/Context.h"
#include "scene/SceneLoader.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace bounce::gputest {

inline gl::Context* sharedContext(std::string* error = nullptr) {
    static std::unique_ptr<gl::Context> context;
    static std::string failure;
    static bool tried = false;
    if (!tried) {
        tried = true;
        auto c = gl::Context::createHeadless();
        if (c.ok()) context = std::move(*c);
        else failure = c.error().message;
    }
    if (error) *error = failure;
    return context.get();
}

inline bool inCi() {
    const char* ci = std::getenv("CI");
    return ci && std::string(ci) == "true";
}

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string error;
        if (!sharedContext(&error)) {
            if (inCi()) FAIL() << "CI=true and no GL context: " << error;
            GTEST_SKIP() << "no GL context: " << error;
        }
        sharedContext()->makeCurrent();
        gl::Context::resetDebugErrorCount();
        if (gl::barrierCheckRequested()) {
            gl::installBarrierTracker();
            gl::setBarrierTracking(true);
            gl::resetBarrierState();
            gl::resetBarrierViolations();
        }
    }
    void TearDown() override {
        if (sharedContext()) {
            EXPECT_EQ(gl::Context::debugErrorCount(), 0) << "GL errors were reported (see log)";
            if (gl::barrierTracking()) {
                for (const auto& v : gl::barrierViolations()) ADD_FAILURE() << "missing memory barrier: " << v;
                gl::resetBarrierViolations();
            }
        }
    }
};

constexpr float kPlaneAlbedo = 0.5f;
constexpr float kPlaneHalf = 2.0f;  // metres

// A horizontal grey Lambertian plane (y = 0, half-size kPlaneHalf, albedo kPlaneAlbedo) under
// `light`, seen from 5 m straight above: orthographically (pixel (x, y) maps linearly to the plane,
// row 0 at -z) or in perspective.
inline Scene planeScene(const Light& light, Projection projection = Projection::Perspective) {
    Scene s;
    s.name = "plane";
    Mesh m;
    m.name = "plane";
    m.positions = {{-kPlaneHalf, 0, -kPlaneHalf}, {kPlaneHalf, 0, -kPlaneHalf}, {kPlaneHalf, 0, kPlaneHalf}, {-kPlaneHalf, 0, kPlaneHalf}};
    m.normals.assign(4, glm::vec3(0, 1, 0));
    m.indices = {0, 2, 1, 0, 3, 2};
    s.meshes.push_back(m);
    Material mat;
    mat.name = "grey";
    mat.baseColor = glm::vec3(kPlaneAlbedo);
    s.materials.push_back(mat);
    Object o;
    o.name = "plane";
    s.objects.push_back(o);
    s.lights.push_back(light);
    s.camera.projection = projection;
    s.camera.orthoHeight = 2.0f * kPlaneHalf;
    // Perspective views are offset by 1 cm so the view direction is not parallel to `up`.
    s.camera.position = projection == Projection::Orthographic ? glm::vec3(0, 5, 0) : glm::vec3(0, 5, 0.01f);
    s.camera.target = {0, 0, 0};
    s.camera.up = {0, 0, -1};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

}  // namespace bounce::gputest
