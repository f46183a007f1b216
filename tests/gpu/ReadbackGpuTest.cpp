// No technique waits for the GPU in the middle of its frame (issue 18): gpu/Readbacks.h wraps libepoxy's
// entry points of every blocking read (query results, buffer and texture downloads, maps, glReadPixels,
// glFinish, fence waits) and logs the calls made while Pipeline::renderFrame submits a frame. Counters
// are read in Technique::collectCounters, after the frame is queued. Every registered technique is
// rendered, so a technique added later is checked by its registry line alone; one whose paper reads
// back mid-frame says so (Technique::frameReadbackReason) and its reads are reported, not failed.
#include "GpuTestSupport.h"

#include "core/Settings.h"
#include "gpu/Objects.h"
#include "gpu/Readbacks.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <fmt/format.h>

#include <optional>

using namespace bounce;

namespace {
class ReadbackGpuTest : public gputest::GpuTest {
protected:
    void SetUp() override {
        gputest::GpuTest::SetUp();
        gl::installReadbackHooks();
        gl::resetFramePathReadbacks();
    }
};

std::string joined(const std::vector<std::string>& calls) {
    std::string out;
    for (const std::string& c : calls) out += (out.empty() ? "" : ", ") + c;
    return out;
}
}  // namespace

// The hooks see what they must and nothing else: otherwise the sweep below would pass vacuously.
TEST_F(ReadbackGpuTest, HooksLogBlockingReadsInsideAFramePathOnly) {
    gl::Buffer b = gl::Buffer::create("test.readback", 16);
    uint32_t v[4] = {};
    b.download(0, sizeof(v), v);  // outside a frame path: allowed
    EXPECT_TRUE(gl::framePathReadbacks().empty());
    gl::Query q = gl::Query::create("test.samples", GL_SAMPLES_PASSED);
    glBeginQuery(GL_SAMPLES_PASSED, q.id());
    glEndQuery(GL_SAMPLES_PASSED);
    {
        gl::FramePath path;
        GLuint available = 0;
        glGetQueryObjectuiv(q.id(), GL_QUERY_RESULT_AVAILABLE, &available);  // polls: not a wait
        EXPECT_TRUE(gl::framePathReadbacks().empty());
        b.download(0, sizeof(v), v);
        GLuint64 samples = 0;
        glGetQueryObjectui64v(q.id(), GL_QUERY_RESULT, &samples);
        glFinish();
    }
    EXPECT_EQ(joined(gl::framePathReadbacks()), "glGetNamedBufferSubData, glGetQueryObjectui64v, glFinish");
    EXPECT_FALSE(gl::inFramePath());
}

// Every registered technique, three frames of an animated scene it accepts (the light, an object or both
// move, so incremental techniques do their per-frame work), at a small size: no blocking read while
// the frame is submitted, and its counters still arrive (collected after the frame).
TEST_F(ReadbackGpuTest, NoTechniqueWaitsForTheGpuOnItsFramePath) {
    // Scenes in order of preference: the point-lit animated box, then the area-lit animated ones for
    // the techniques that shade area lights only (radiosity, area-light).
    const char* kScenes[] = {"cornell-box-dynamic", "cornell-box-rotating", "cornell-box-area"};
    int checked = 0;
    for (const TechniqueInfo& t : registeredTechniques()) {
        std::map<std::string, std::string> settings;
        if (t.name.rfind("radiosity-", 0) == 0)  // coarse elements keep llvmpipe time small
            settings = {{"elementSize", "0.3"}, {"dynamicElementSize", "0.3"}, {"hemicubeSize", "16"}};
        std::unique_ptr<Pipeline> pipeline;
        std::string sceneName;
        std::optional<Scene> scene;  // outlives the pipeline, which refers to it
        for (const char* name : kScenes) {
            pipeline.reset();
            auto loaded = loadScene(name);
            ASSERT_TRUE(loaded.ok()) << name;
            scene.emplace(std::move(*loaded));
            auto technique = createTechnique(t.name);
            ASSERT_TRUE(technique.ok());
            ASSERT_TRUE(applySettings(**technique, settings, t.name).ok());
            render::RenderSettings rs;
            rs.shadowMapSize = 256;
            auto created = Pipeline::create(*scene, std::move(*technique), {48, 48}, rs);
            if (!created.ok()) continue;  // refused (light types): the next scene
            pipeline = std::move(*created);
            sceneName = name;
            break;
        }
        ASSERT_TRUE(pipeline) << t.name << " accepts none of the test scenes";
        const std::string reason(pipeline->technique().frameReadbackReason());
        gl::resetFramePathReadbacks();
        FrameStats last;
        for (uint32_t f = 0; f < 3; ++f) last = pipeline->renderFrame(f);
        const std::vector<std::string> reads = gl::framePathReadbacks();
        if (reason.empty()) {
            EXPECT_TRUE(reads.empty()) << t.name << " on " << sceneName << " waits for the GPU mid-frame: " << joined(reads);
            ++checked;
        } else {
            RecordProperty(fmt::format("readbacks.{}", t.name), fmt::format("{} ({})", reads.size(), reason));
        }
        // Counters reach the record although they are read after the frame.
        EXPECT_FALSE(last.counters.empty()) << t.name;
    }
    // All but the techniques with a stated reason: today radiosity's three shooting methods.
    EXPECT_GE(checked, static_cast<int>(registeredTechniques().size()) - 3);
}
