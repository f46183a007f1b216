// Running right on real GPUs (issue 29; docs/gpu.md): the context's state and device profile, the
// portable-limits audit of linked programs (GL's program interface queries, the one-line refusal of
// BOUNCE_PORTABLE_LIMITS=1), per-profile defaults, and GPU timers read one frame late.
#include "GpuTestSupport.h"
#include "app/Options.h"
#include "app/viewer/ViewerSettings.h"
#include "gpu/Bindings.h"
#include "gpu/GpuTimers.h"
#include "gpu/Program.h"
#include "gpu/ProgramChecks.h"
#include "gpu/ShaderLimits.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"
#include "techniques/nichols/MinMaxPyramid.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

using namespace bounce;
namespace fs = std::filesystem;

namespace {

class PortabilityGpuTest : public gputest::GpuTest {};

// Sets an environment variable for the lifetime of the object and restores it after.
struct EnvOverride {
    std::string name;
    std::optional<std::string> old;
    EnvOverride(std::string n, const char* value) : name(std::move(n)) {
        if (const char* v = std::getenv(name.c_str())) old = v;
        if (value) ::setenv(name.c_str(), value, 1);
        else ::unsetenv(name.c_str());
    }
    ~EnvOverride() {
        if (old) ::setenv(name.c_str(), old->c_str(), 1);
        else ::unsetenv(name.c_str());
    }
};

// A temporary shader tree (BOUNCE_SHADER_DIR) holding one compute shader with `images` image uniforms
// bound to units 0..images-1: the shape of finding #1's pyramid_reduce.comp.
struct ImageProbeShaders {
    fs::path root;
    std::optional<EnvOverride> dir;
    explicit ImageProbeShaders(int images) {
        root = fs::temp_directory_path() / ("bounce-portability-" + std::to_string(::getpid()));
        fs::create_directories(root / "shaders");
        fs::create_directories(root / "src" / "gpu");
        fs::copy_file(fs::path(BOUNCE_SOURCE_DIR) / "src/gpu/Bindings.h", root / "src/gpu/Bindings.h",
                      fs::copy_options::overwrite_existing);
        std::ofstream out(root / "shaders" / "probe.comp");
        out << "layout(local_size_x = 8, local_size_y = 8) in;\n";
        for (int i = 0; i < images; ++i)
            out << "layout(rgba32f, binding = " << i << ") uniform image2D i_" << i << ";\n";
        out << "void main() {\n  vec4 s = vec4(0.0);\n";
        for (int i = 0; i < images; ++i) out << "  s += imageLoad(i_" << i << ", ivec2(gl_GlobalInvocationID.xy));\n";
        out << "  imageStore(i_0, ivec2(gl_GlobalInvocationID.xy), s);\n}\n";
        out.close();
        dir.emplace("BOUNCE_SHADER_DIR", (root / "shaders").c_str());
    }
    ~ImageProbeShaders() {
        dir.reset();
        std::error_code ec;
        fs::remove_all(root, ec);
    }
};

gl::ProgramUse useOf(const gl::Program& p, const std::vector<std::pair<GLenum, std::string>>& stages,
                     const std::vector<std::pair<std::string, std::string>>& defines = {}) {
    std::vector<gl::StageSource> sources;
    for (const auto& [stage, file] : stages) {
        auto text = gl::preprocessShader(file, defines);
        EXPECT_TRUE(text.ok()) << file;
        sources.push_back({stage, file, text.ok() ? *text : std::string()});
    }
    return gl::queryProgramUse(p.id(), sources);
}

}  // namespace

TEST_F(PortabilityGpuTest, ContextEnablesSeamlessCubeMapFilteringAndNamesItsProfile) {
    // Issue 29 #14: point-light distance maps are LINEAR-filtered cube maps.
    EXPECT_TRUE(glIsEnabled(GL_TEXTURE_CUBE_MAP_SEAMLESS));
    const gl::GpuInfo& info = gputest::sharedContext()->info();
    // The tests run with KHR_debug (GpuTest fails on any GL error); measured runs do not.
    EXPECT_TRUE(info.debugContext);
    if (!std::getenv("BOUNCE_PROFILE")) {
        EXPECT_EQ(info.profile, profileOfRenderer(info.renderer));
        if (info.renderer.find("llvmpipe") != std::string::npos) {
            EXPECT_EQ(info.profile, DeviceProfile::Llvmpipe);
            EXPECT_EQ(gl::shaderLoopIterationBudget(), 65535);
        }
    }
    EXPECT_EQ(gl::shaderLoopIterationBudget(), gl::shaderLoopIterationBudget(info.profile));
    EXPECT_EQ(gl::shaderLoopIterationBudget(DeviceProfile::Gpu), 1 << 24);
}

TEST_F(PortabilityGpuTest, InterfaceQueriesCountThePyramidPassesWithinEightImageUnits) {
    // Finding #1, fixed: pyramid_reduce.comp bound image units 0..9 (five inputs, five outputs); it now
    // reads level k-1 through five samplers (units BINDING_TEX_PYRAMID0..4) and writes five images.
    // On the old shader this test saw 10 image uniforms and a finding past the portable limit.
    const std::vector<std::pair<GLenum, std::string>> stages = {{GL_COMPUTE_SHADER, "techniques/nichols/pyramid_reduce.comp"}};
    auto p = gl::Program::build({"test.pyramidReduce", stages});
    ASSERT_TRUE(p.ok()) << p.error().message;
    const gl::ProgramUse use = useOf(*p, stages);
    const auto& compute = use.stages[static_cast<size_t>(gl::ShaderStage::Compute)];
    EXPECT_TRUE(compute.present);
    EXPECT_EQ(compute.imageUniforms, 5);
    EXPECT_EQ(use.imageUnits, 5);
    EXPECT_EQ(compute.samplers, 5);
    EXPECT_EQ(use.textureUnits, BINDING_TEX_PYRAMID4 + 1);
    EXPECT_EQ(use.computeLocalSize[0], 8);
    EXPECT_EQ(use.computeLocalSize[1], 8);
    EXPECT_EQ(use.computeInvocations, 64);
    for (const auto& f : gl::auditProgram("test.pyramidReduce", use)) EXPECT_FALSE(f.pastPortable) << f.key;
    // pyramid_flag.comp: units 0..6, MinMaxPyramid::kImageUniforms.
    const std::vector<std::pair<GLenum, std::string>> flagStages = {{GL_COMPUTE_SHADER, "techniques/nichols/pyramid_flag.comp"}};
    auto flag = gl::Program::build({"test.pyramidFlag", flagStages});
    ASSERT_TRUE(flag.ok()) << flag.error().message;
    EXPECT_EQ(useOf(*flag, flagStages).imageUnits, nichols::MinMaxPyramid::kImageUniforms);

    // The pyramid's setup check answers as a driver with fewer units would (one line, naming the limits).
    gl::GpuInfo info = gputest::sharedContext()->info();
    EXPECT_TRUE(nichols::MinMaxPyramid::checkLimits(info).ok());
    info.maxImageUniforms[static_cast<size_t>(gl::ShaderStage::Compute)] = nichols::MinMaxPyramid::kImageUniforms - 1;
    auto refused = nichols::MinMaxPyramid::checkLimits(info);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("GL_MAX_COMPUTE_IMAGE_UNIFORMS"), std::string::npos) << refused.error().message;
    EXPECT_EQ(refused.error().message.find('\n'), std::string::npos);

    // A graphics program: compose reads two textures in its fragment stage and nothing else.
    const std::vector<std::pair<GLenum, std::string>> compose = {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                                 {GL_FRAGMENT_SHADER, "render/compose.frag"}};
    auto c = gl::Program::build({"test.compose", compose});
    ASSERT_TRUE(c.ok()) << c.error().message;
    const gl::ProgramUse cu = useOf(*c, compose);
    EXPECT_EQ(cu.stages[static_cast<size_t>(gl::ShaderStage::Fragment)].samplers, 2);
    EXPECT_EQ(cu.stages[static_cast<size_t>(gl::ShaderStage::Vertex)].samplers, 0);
    EXPECT_EQ(cu.stages[static_cast<size_t>(gl::ShaderStage::Fragment)].imageUniforms, 0);
    EXPECT_FALSE(cu.stages[static_cast<size_t>(gl::ShaderStage::Compute)].present);
    EXPECT_GE(cu.textureUnits, 2);
}

TEST_F(PortabilityGpuTest, PortableModeRefusesNineImageUnitsInOneLineAndAcceptsEight) {
    if (std::getenv("BOUNCE_PORTABLE_ALLOW")) GTEST_SKIP() << "an allow-list is active";
    EnvOverride portable("BOUNCE_PORTABLE_LIMITS", "1");
    {
        ImageProbeShaders shaders(9);
        auto p = gl::Program::build({"test.nineImages", {{GL_COMPUTE_SHADER, "probe.comp"}}});
        ASSERT_FALSE(p.ok()) << "9 image units linked under BOUNCE_PORTABLE_LIMITS=1";
        const std::string& m = p.error().message;
        EXPECT_NE(m.find("test.nineImages"), std::string::npos) << m;
        EXPECT_NE(m.find("(units 0..8)"), std::string::npos) << m;
        EXPECT_NE(m.find("portable limit 8"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    {
        ImageProbeShaders shaders(8);  // at the GL minimum: links, no finding
        auto p = gl::Program::build({"test.eightImages", {{GL_COMPUTE_SHADER, "probe.comp"}}});
        EXPECT_TRUE(p.ok()) << p.error().message;
    }
    EnvOverride normal("BOUNCE_PORTABLE_LIMITS", nullptr);
    ImageProbeShaders shaders(9);  // outside the mode a finding is logged, the program links (llvmpipe has 192)
    auto p = gl::Program::build({"test.nineImagesNormal", {{GL_COMPUTE_SHADER, "probe.comp"}}});
    EXPECT_TRUE(p.ok()) << p.error().message;
}

TEST_F(PortabilityGpuTest, EverySettingStartsAtItsLlvmpipeDefault) {
    // Per-profile defaults (core/Settings.h) need the member's initial value to be the llvmpipe one:
    // code that never applies a profile (tests, benchmarks) then runs llvmpipe's values everywhere.
    auto check = [](Configurable& fresh, Configurable& applied, const std::string& what) {
        const nlohmann::json before = settingsToJson(fresh);
        applyProfileDefaults(applied, DeviceProfile::Llvmpipe);
        EXPECT_EQ(settingsToJson(applied), before) << what;
    };
    for (const TechniqueInfo& t : registeredTechniques()) {
        auto a = t.create(), b = t.create();
        check(*a, *b, t.name);
    }
    render::RenderSettings r1, r2;
    check(r1, r2, "renderer");
    ViewerSettings v1, v2;
    check(v1, v2, "viewer");
}

TEST_F(PortabilityGpuTest, RsmBatchAndViewerBudgetFollowTheProfile) {
    auto rsm = createTechnique("rsm");
    ASSERT_TRUE(rsm.ok());
    EXPECT_EQ(settingsToJson(**rsm)["vplBatch"], 32768);
    applyProfileDefaults(**rsm, DeviceProfile::Gpu);
    EXPECT_EQ(settingsToJson(**rsm)["vplBatch"], 1024);
    ViewerSettings v;
    applyProfileDefaults(v, DeviceProfile::Gpu);
    EXPECT_NEAR(v.frameBudgetMs, 1000.0f / 30.0f, 1e-3f);
    // applyAllSettings: the profile's defaults first, the command line's values over them.
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    render::RenderSettings rs;
    ASSERT_TRUE(applyAllSettings(*scene, **rsm, rs, {"vplBatch=64"}, DeviceProfile::Gpu).ok());
    EXPECT_EQ(settingsToJson(**rsm)["vplBatch"], 64);
    ASSERT_TRUE(applyAllSettings(*scene, **rsm, rs, {}, DeviceProfile::Llvmpipe).ok());
    EXPECT_EQ(settingsToJson(**rsm)["vplBatch"], 32768);
}

TEST_F(PortabilityGpuTest, LateTimersReturnThePreviousFramesScopes) {
    gl::GpuTimers t;
    t.setLatency(gl::GpuTimers::Latency::OneFrame);
    t.beginFrame();
    { auto s = t.scope("first"); }
    const auto none = t.endFrame();
    EXPECT_TRUE(none.empty());  // nothing was pending
    EXPECT_EQ(t.resultsFrame(), -1);
    t.beginFrame();
    { auto s = t.scope("second"); }
    const auto late = t.endFrame();
    ASSERT_EQ(late.size(), 2u);
    EXPECT_EQ(late[0].name, "frame");
    EXPECT_EQ(late[1].name, "first");  // frame 0's scope, read while frame 1 was queued
    EXPECT_EQ(t.resultsFrame(), 0);
    EXPECT_GE(late[1].milliseconds, 0.0);
    t.setLatency(gl::GpuTimers::Latency::Immediate);
    t.beginFrame();
    { auto s = t.scope("third"); }
    const auto now = t.endFrame();
    ASSERT_EQ(now.size(), 2u);
    EXPECT_EQ(now[1].name, "third");
    EXPECT_EQ(t.resultsFrame(), 2);
}

TEST_F(PortabilityGpuTest, PipelineWithLateTimingsRendersTheSameImage) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    render::RenderSettings rs;
    rs.shadowMapSize = 256;
    auto make = [&] {
        auto t = createTechnique("ambient");
        EXPECT_TRUE(t.ok());
        return Pipeline::create(*scene, std::move(*t), {32, 32}, rs);
    };
    auto now = make(), late = make();
    ASSERT_TRUE(now.ok() && late.ok());
    (*late)->setLateTimings(true);
    const FrameStats n0 = (*now)->renderFrame(0), l0 = (*late)->renderFrame(0);
    EXPECT_FALSE(n0.passes.empty());
    EXPECT_FALSE(n0.passesLate);
    EXPECT_TRUE(l0.passes.empty());
    EXPECT_TRUE(l0.passesLate);
    const FrameStats l1 = (*late)->renderFrame(1);
    ASSERT_FALSE(l1.passes.empty());
    EXPECT_EQ(l1.passes.front().name, "frame");
    (*now)->renderFrame(1);
    const Image a = (*now)->readback(Component::Full), b = (*late)->readback(Component::Full);
    ASSERT_EQ(a.pixelCount(), b.pixelCount());
    for (size_t i = 0; i < a.pixelCount(); ++i) ASSERT_EQ(a.data()[i], b.data()[i]) << i;
}
