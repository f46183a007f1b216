// The GPU layer: RAII objects, shader building with includes and error locations, timers, and the
// G-buffer of a known box.
#include "GpuTestSupport.h"
#include "gpu/Bindings.h"
#include "gpu/GpuTimers.h"
#include "gpu/Objects.h"
#include "gpu/Program.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <glm/gtc/constants.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <type_traits>

using namespace bounce;
namespace fs = std::filesystem;

namespace {
class GpuFoundationGpuTest : public gputest::GpuTest {};

// Makes BOUNCE_SHADER_DIR point at a temporary shader tree for the lifetime of the object.
struct ShaderDirOverride {
    fs::path root;
    explicit ShaderDirOverride(const std::string& name) {
        root = fs::temp_directory_path() / ("bounce-shaders-" + name + "-" + std::to_string(::getpid()));
        fs::create_directories(root / "shaders" / "inc");
        fs::create_directories(root / "src" / "gpu");
        fs::copy_file(fs::path(BOUNCE_SOURCE_DIR) / "src/gpu/Bindings.h", root / "src/gpu/Bindings.h",
                      fs::copy_options::overwrite_existing);
        ::setenv("BOUNCE_SHADER_DIR", (root / "shaders").c_str(), 1);
    }
    void write(const std::string& file, const std::string& text) const { std::ofstream(root / "shaders" / file) << text; }
    ~ShaderDirOverride() {
        ::unsetenv("BOUNCE_SHADER_DIR");
        std::error_code ec;
        fs::remove_all(root, ec);
    }
};
}  // namespace

TEST_F(GpuFoundationGpuTest, ObjectsAreMoveOnlyAndMovesTransferOwnership) {
    static_assert(!std::is_copy_constructible_v<gl::Buffer>);
    static_assert(std::is_nothrow_move_constructible_v<gl::Buffer>);
    static_assert(std::is_nothrow_move_assignable_v<gl::Handle<gl::BufferTraits>>);
    static_assert(!std::is_copy_constructible_v<gl::Texture>);
    gl::Buffer a = gl::Buffer::create("test.a", 64);
    const GLuint id = a.id();
    ASSERT_NE(id, 0u);
    gl::Buffer b = std::move(a);
    EXPECT_EQ(b.id(), id);
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is the point
    {
        gl::Buffer c = gl::Buffer::create("test.c", 16);
        const GLuint cid = c.id();
        c = std::move(b);  // c's old buffer now belongs to b and dies with it
        EXPECT_EQ(c.id(), id);
        EXPECT_EQ(b.id(), cid);
    }
    EXPECT_TRUE(glIsBuffer(id) == GL_FALSE);  // c (holding id) went out of scope
}

TEST_F(GpuFoundationGpuTest, BufferRoundTrip) {
    const std::vector<float> data = {1.0f, 2.0f, 3.0f, 4.0f};
    gl::Buffer b = gl::Buffer::create("test.roundtrip", data.size() * sizeof(float), data.data());
    std::vector<float> back(4);
    b.download(0, back.size() * sizeof(float), back.data());
    EXPECT_EQ(back, data);
}

TEST_F(GpuFoundationGpuTest, ShaderErrorsNameFileAndLine) {
    ShaderDirOverride dir("errors");
    dir.write("inc/helper.glsl", "float helper() { return 1.0; }\n");
    dir.write("broken.comp",
              "layout(local_size_x = 1) in;\n#include \"inc/helper.glsl\"\nvoid main() {\n  float x = helper();\n"
              "  undefined_function(x);\n}\n");
    auto p = gl::Program::build({"broken", {{GL_COMPUTE_SHADER, "broken.comp"}}});
    ASSERT_FALSE(p.ok());
    // Line 5 of broken.comp, counted in the file (the include and the prepended header must not shift it).
    EXPECT_NE(p.error().message.find("broken.comp:5:"), std::string::npos) << p.error().message;
    dir.write("missing.comp", "#include \"inc/nope.glsl\"\nvoid main() {}\n");
    auto q = gl::Program::build({"missing", {{GL_COMPUTE_SHADER, "missing.comp"}}});
    ASSERT_FALSE(q.ok());
    EXPECT_NE(q.error().message.find("missing.comp:1"), std::string::npos) << q.error().message;
    EXPECT_NE(q.error().message.find("nope.glsl"), std::string::npos) << q.error().message;
}

TEST_F(GpuFoundationGpuTest, ComputeShaderWithIncludesRuns) {
    ShaderDirOverride dir("compute");
    dir.write("inc/value.glsl", "uint value(uint i) { return i * i + 1u; }\n");
    dir.write("fill.comp",
              "layout(local_size_x = 8) in;\n#include \"inc/value.glsl\"\n"
              "layout(std430, binding = BINDING_SSBO_TECH0) buffer Out { uint u_out[]; };\n"
              "void main() { u_out[gl_GlobalInvocationID.x] = value(gl_GlobalInvocationID.x); }\n");
    auto p = gl::Program::build({"fill", {{GL_COMPUTE_SHADER, "fill.comp"}}});
    ASSERT_TRUE(p.ok()) << p.error().message;
    gl::Buffer out = gl::Buffer::create("test.fill", 32 * sizeof(uint32_t));
    out.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    p->use();
    gl::Program::dispatch(32, 1, 1, 8);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<uint32_t> back(32);
    out.download(0, back.size() * sizeof(uint32_t), back.data());
    for (uint32_t i = 0; i < 32; ++i) EXPECT_EQ(back[i], i * i + 1u);
}

TEST_F(GpuFoundationGpuTest, TimersReportNamedNonNegativePasses) {
    gl::GpuTimers timers;
    timers.beginFrame();
    {
        auto outer = timers.scope("outer");
        auto inner = timers.scope("inner");
        glFinish();
    }
    const auto passes = timers.endFrame();
    ASSERT_EQ(passes.size(), 3u);
    EXPECT_EQ(passes[0].name, "frame");
    EXPECT_EQ(passes[1].name, "outer");
    EXPECT_EQ(passes[2].name, "outer/inner");
    for (const auto& p : passes) EXPECT_GE(p.milliseconds, 0.0);
    EXPECT_GE(passes[1].milliseconds, passes[2].milliseconds);
}

// Mode::Finish charges a pass its own work: a heavy fragment pass (rasterised by llvmpipe only at the
// next flush) followed by an empty scope. With a glFinish at each boundary the heavy scope holds the
// work: it takes at least 1 ms (256^2 fragments x 2,000 iterations: tens of ms on llvmpipe, well
// over 1 ms on any GPU too) and more than 5x the empty one (which holds only two glFinish calls).
TEST_F(GpuFoundationGpuTest, FinishTimersChargeEachPassItsOwnWork) {
    ShaderDirOverride dir("finish-timers");
    dir.write("quad.vert", "void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
                           "  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0); }\n");
    dir.write("heavy.frag", "out vec4 o_colour;\nvoid main() { float x = gl_FragCoord.x;\n"
                            "  for (int i = 0; i < 2000; ++i) x = fract(x * 1.0001 + 0.37);\n"
                            "  o_colour = vec4(x); }\n");
    auto program = gl::Program::build({"heavy", {{GL_VERTEX_SHADER, "quad.vert"}, {GL_FRAGMENT_SHADER, "heavy.frag"}}});
    ASSERT_TRUE(program.ok()) << program.error().message;
    gl::Texture target = gl::Texture::create2D("test.finishTimers", 256, 256, GL_RGBA16F);
    gl::Framebuffer fbo = gl::Framebuffer::create("test.finishTimers.fbo");
    fbo.attach(GL_COLOR_ATTACHMENT0, target);
    fbo.setDrawBuffers(1);
    ASSERT_TRUE(fbo.complete());
    const auto draw = [&] {
        fbo.bind();
        glViewport(0, 0, 256, 256);
        program->use();
        gl::Context::current()->bindEmptyVertexArray();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    draw();  // llvmpipe compiles the shader variant at the first draw: not the pass's work
    glFinish();
    gl::GpuTimers timers;
    timers.setMode(gl::GpuTimers::Mode::Finish);
    timers.beginFrame();
    {
        auto heavy = timers.scope("heavy");
        draw();
    }
    { auto empty = timers.scope("empty"); }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const auto passes = timers.endFrame();
    ASSERT_EQ(passes.size(), 3u);
    EXPECT_EQ(passes[1].name, "heavy");
    EXPECT_EQ(passes[2].name, "empty");
    EXPECT_GT(passes[1].milliseconds, 1.0);
    EXPECT_GT(passes[1].milliseconds, 5.0 * passes[2].milliseconds);
    EXPECT_GE(passes[0].milliseconds, passes[1].milliseconds + passes[2].milliseconds);
}

TEST_F(GpuFoundationGpuTest, GBufferNormalsOfAKnownBox) {
    // An axis-aligned room (inward faces) seen from inside: every covered pixel's position lies on
    // one of the six planes, and its normal must be that plane's inward normal.
    Scene s;
    s.name = "room";
    Mesh m;
    m.name = "room";
    const glm::vec3 lo(-1.0f), hi(1.0f);
    // Winds each face counter-clockwise around the inward normal (towards the room's centre).
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        const glm::vec3 mid = 0.25f * (a + b + c + d);
        if (glm::dot(glm::cross(b - a, c - a), -mid) < 0.0f) std::swap(b, d);
        const uint32_t base = static_cast<uint32_t>(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c, d});
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    };
    quad({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});  // floor, +y
    quad({lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z});  // ceiling, -y
    quad({lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z});  // x = -1, +x
    quad({hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z});  // x = +1, -x
    quad({lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z});  // z = -1, +z
    quad({lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});  // z = +1, -z
    s.meshes.push_back(m);  // no normals: finalizeScene computes them from the winding
    Material mat;
    mat.name = "white";
    s.materials.push_back(mat);
    Object o;
    o.name = "room";
    s.objects.push_back(o);
    Light l;
    l.type = LightType::Point;
    l.intensity = glm::vec3(1.0f);
    s.lights.push_back(l);
    s.camera.position = {0.3f, 0.2f, 0.9f};
    s.camera.target = {-0.2f, -0.3f, -1.0f};
    s.camera.verticalFov = glm::radians(100.0f);
    ASSERT_TRUE(finalizeScene(s).ok());

    auto technique = createTechnique("direct");
    ASSERT_TRUE(technique.ok());
    auto pipeline = Pipeline::create(s, std::move(*technique), {48, 40}, render::RenderSettings{});
    ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
    (*pipeline)->renderFrame(0);
    const Image position = readTexture((*pipeline)->gbuffer().position());
    const Image normal = readTexture((*pipeline)->gbuffer().normal());
    int checked = 0;
    for (int y = 0; y < position.height(); ++y)
        for (int x = 0; x < position.width(); ++x) {
            const glm::vec3 p = position.at(x, y);
            // The face is the coordinate closest to +-1; skip pixels near edges between faces.
            int axis = 0;
            for (int a = 1; a < 3; ++a)
                if (std::abs(p[a]) > std::abs(p[axis])) axis = a;
            bool nearEdge = false;
            for (int a = 0; a < 3; ++a)
                if (a != axis && std::abs(p[a]) > 0.97f) nearEdge = true;
            if (nearEdge) continue;
            glm::vec3 expected(0.0f);
            expected[axis] = p[axis] > 0.0f ? -1.0f : 1.0f;
            // RGBA16F normals: 1e-3 is the half-float precision of values near 1.
            EXPECT_NEAR(glm::length(normal.at(x, y) - expected), 0.0f, 1e-3f) << "pixel " << x << "," << y;
            // Positions (RGBA32F) lie on the face's plane up to depth interpolation error.
            EXPECT_NEAR(std::abs(p[axis]), 1.0f, 1e-4f);
            ++checked;
        }
    EXPECT_GT(checked, 48 * 40 * 3 / 4);
}
