// Issue 29 #5: 1D compute jobs past GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] (65,535 in GL 4.5, on llvmpipe
// and on AMD/Intel) dispatched as a 2D grid of groups (src/gpu/DispatchGrid.h, shaders/common/dispatch.glsl).
// llvmpipe's limit is the minimum itself, so the probe passes it for real; the techniques' jobs are
// llvmpipe-sized, so their grids wrap at a lowered limit (gl::setMaxGroupsXForTests) and must give the
// same image as one row.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "core/Error.h"
#include "gpu/DispatchGrid.h"
#include "metrics/ErrorMetrics.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <unistd.h>

using namespace bounce;
namespace fs = std::filesystem;

namespace {
class DispatchGridGpuTest : public gputest::GpuTest {};

// A lowered x limit for one scope.
struct LoweredGroupLimit {
    explicit LoweredGroupLimit(uint32_t limit) { gl::setMaxGroupsXForTests(limit); }
    ~LoweredGroupLimit() { gl::setMaxGroupsXForTests(0); }
};

// A temporary shader tree (BOUNCE_SHADER_DIR) with the real common/dispatch.glsl and a probe that
// counts each linear invocation below u_count once.
struct DispatchProbeShaders {
    fs::path root;
    std::optional<std::string> old;
    DispatchProbeShaders() {
        root = fs::temp_directory_path() / ("bounce-dispatch-grid-" + std::to_string(::getpid()));
        fs::create_directories(root / "shaders" / "common");
        fs::create_directories(root / "src" / "gpu");
        fs::copy_file(fs::path(BOUNCE_SOURCE_DIR) / "src/gpu/Bindings.h", root / "src/gpu/Bindings.h", fs::copy_options::overwrite_existing);
        fs::copy_file(fs::path(BOUNCE_SOURCE_DIR) / "shaders/common/dispatch.glsl", root / "shaders/common/dispatch.glsl",
                      fs::copy_options::overwrite_existing);
        std::ofstream out(root / "shaders" / "probe.comp");
        out << "layout(local_size_x = 2) in;\n"
               "#include \"common/dispatch.glsl\"\n"
               "layout(std430, binding = 0) buffer Hits { uint u_hits[]; };\n"
               "uniform uint u_count;\n"
               "void main() { uint i = linearInvocation(); if (i < u_count) atomicAdd(u_hits[i], 1u); }\n";
        out.close();
        if (const char* v = std::getenv("BOUNCE_SHADER_DIR")) old = v;
        ::setenv("BOUNCE_SHADER_DIR", (root / "shaders").c_str(), 1);
    }
    ~DispatchProbeShaders() {
        if (old) ::setenv("BOUNCE_SHADER_DIR", old->c_str(), 1);
        else ::unsetenv("BOUNCE_SHADER_DIR");
        std::error_code ec;
        fs::remove_all(root, ec);
    }
};
}  // namespace

TEST_F(DispatchGridGpuTest, AJobPastTheGroupLimitRunsEveryInvocationOnce) {
    // 150,001 invocations at 2 per group: 75,001 groups, past llvmpipe's and GL's 65,535 (a plain
    // glDispatchCompute of them is GL_INVALID_VALUE, which fails a GPU test); on a GPU whose x limit is
    // 2^31 - 1 it is one row, so the lowered limit below makes both devices wrap.
    constexpr uint32_t kInvocations = 150001;
    constexpr uint32_t kPad = 4096;  // room for the last row's extra invocations, which must write nothing
    gl::Program program;
    {
        DispatchProbeShaders shaders;
        auto p = gl::Program::build({"test.dispatchGrid", {{GL_COMPUTE_SHADER, "probe.comp"}}});
        ASSERT_TRUE(p.ok()) << p.error().message;
        program = std::move(*p);
    }
    gl::Buffer hits = gl::Buffer::create("test.dispatchGrid.hits", (kInvocations + kPad) * sizeof(uint32_t));
    for (uint32_t limit : {0u, 4096u}) {  // the device's limit, then rows of 4096 groups (19 rows)
        LoweredGroupLimit lowered(limit);
        hits.clearZero();
        hits.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
        program.set("u_count", kInvocations);
        program.use();
        const gl::GroupGrid grid = gl::groupGrid((kInvocations + 1) / 2, gl::maxGroupsX());
        EXPECT_GT(grid.y, 1u) << "the job must outgrow one row";
        gl::dispatchLinear(kInvocations, 2);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<uint32_t> h(kInvocations + kPad);
        hits.download(0, h.size() * sizeof(uint32_t), h.data());
        size_t once = 0, beyond = 0;
        for (uint32_t i = 0; i < kInvocations; ++i) once += h[i] == 1u;
        for (uint32_t i = kInvocations; i < h.size(); ++i) beyond += h[i];
        EXPECT_EQ(once, kInvocations) << "limit " << limit;
        EXPECT_EQ(beyond, 0u) << "limit " << limit;
    }
}

TEST_F(DispatchGridGpuTest, MultiresSplatRefineListsWrapIntoRowsAndGiveTheSameImage) {
    // refine.comp's indirect dispatches (list length / 64 groups in x, lists in y) now grow rows in z.
    // With rows of 2 groups (128 subsplats) a 48^2 frame's lists (hundreds to thousands of subsplats)
    // span many rows; a shader that read only the first row would drop most subsplats.
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    const Image one = nicholstest::renderIndirect(*scene, "multires-splat", {}, 48);
    Image rows;
    {
        LoweredGroupLimit lowered(2);
        rows = nicholstest::renderIndirect(*scene, "multires-splat", {}, 48);
    }
    ASSERT_GT(nicholstest::totalRadiance(one), 0.0);
    // Same subsplats, appended in another order (atomics): equal up to float summation order, as
    // between two runs (measured relative RMS 0 to 1e-7 here).
    EXPECT_LT(relativeRmsError(rows, one), 1e-5);
}

// vct's indirect image after three frames (the second and third clear through last frame's lists).
Image vctAfterThreeFrames(const Scene& scene, const std::map<std::string, std::string>& settings) {
    auto p = nicholstest::makePipeline(scene, "vct", settings, 48);
    for (uint32_t f = 0; f < 3; ++f) p->renderFrame(f);
    return p->readback(Component::Indirect);
}

TEST_F(DispatchGridGpuTest, VctSparseListPassesWrapIntoRowsAndGiveTheSameImage) {
    // vct's sparse passes (post-voxelization, mips, the sparse clear) are compute jobs over the
    // active-voxel lists, dispatched from the lists' counts by common/list_args.comp (issue 29 #17;
    // they were point lists drawn by a vertex shader). With rows of 2 groups (128 voxels) the 32^3
    // Cornell box's lists (thousands of voxels at level 0) span many rows; a job that read only the
    // first row would leave most voxels unprocessed and the indirect light dark. Three frames: the
    // second and third clear sparsely through last frame's lists.
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    const std::map<std::string, std::string> settings{{"resolution", "32"}, {"sparseMip", "true"}};
    const Image one = vctAfterThreeFrames(*scene, settings);
    Image rows;
    {
        LoweredGroupLimit lowered(2);
        rows = vctAfterThreeFrames(*scene, settings);
    }
    ASSERT_GT(nicholstest::totalRadiance(one), 0.0);
    const double rms = relativeRmsError(rows, one);
    std::printf("vct sparse, rows of 2 groups against one row: relative RMS %.3g\n", rms);
    // The same voxels in another list order (atomics, the CAS average): measured 0; bound 1e-5 as the
    // multires-splat case. A job reading only the first row: 0.80; list_args.comp giving one group: the
    // sparse-equals-dense test fails (1.07).
    EXPECT_LT(rms, 1e-5);
}

TEST_F(DispatchGridGpuTest, RadiosityPassesWrapIntoRowsAndGiveTheSameImage) {
    // RadiositySystem's 1D passes (resolve, the mip integration's multiply, placement, lights,
    // reconstruction, per-quad statistics) through gl::dispatchLinear: with rows of 3 groups, every
    // pass of 32^2 hemicubes spans several rows.
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    const std::vector<std::pair<std::string, std::map<std::string, std::string>>> runs = {
        {"radiosity-gather", {{"elementSize", "0.25"}, {"hemicubeSize", "32"}, {"integration", "mipmap"}, {"bounces", "2"}}},
        {"radiosity-cross", {{"elementSize", "0.25"}, {"hemicubeSize", "32"}}},
    };
    for (const auto& run : runs) {
        // Named, not a structured binding: clang 14 (the sanitizer build) cannot capture bindings in a lambda.
        const std::string& method = run.first;
        const std::map<std::string, std::string>& settings = run.second;
        auto render = [&] {
            auto p = nicholstest::makePipeline(*scene, method, settings, 32);
            for (uint32_t f : {0u, 1u}) p->renderFrame(f);
            return p->readback(Component::Indirect);
        };
        const Image one = render();
        Image rows;
        {
            LoweredGroupLimit lowered(3);
            rows = render();
        }
        ASSERT_GT(nicholstest::totalRadiance(one), 0.0) << method;
        // The same invocations in the same per-element order: bit-identical up to llvmpipe's noise.
        EXPECT_LT(relativeRmsError(rows, one), 1e-5) << method;
    }
}
