// The portable-limits table, the audit of a program's resources and the GL-minimum clamp
// (issue 29; gpu/PortableLimits.h). The GPU side (GL's program interface queries on real programs)
// is tests/gpu/PortabilityGpuTest.cpp.
#include "gpu/PortableLimits.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace bounce;
using namespace bounce::gl;

TEST(PortableLimits, TableRowsAreConsistent) {
    std::set<std::string_view> keys;
    for (const LimitRow& r : limitTable()) {
        EXPECT_TRUE(keys.insert(r.key).second) << "duplicate " << r.key;
        // Every conformant driver reaches the GL minimum: a vendor value below it is a typo.
        EXPECT_GE(r.nvidia, r.glMinimum) << r.key;
        EXPECT_GE(r.amd, r.glMinimum) << r.key;
        EXPECT_GE(r.intel, r.glMinimum) << r.key;
        EXPECT_GE(r.llvmpipe, r.glMinimum) << r.key;
        EXPECT_GE(r.portable(), r.glMinimum) << r.key;
        EXPECT_EQ(r.glName.rfind("GL_MAX_", 0), 0u) << r.key;
    }
    // The values the findings rest on (GL 4.5 Table 23.63; NVIDIA's 8 image units, finding #1).
    EXPECT_EQ(findLimit("imageUnits")->glMinimum, 8);
    EXPECT_EQ(findLimit("imageUnits")->portable(), 8);
    EXPECT_EQ(findLimit("compute.imageUniforms")->portable(), 8);
    EXPECT_EQ(findLimit("fragment.samplers")->glMinimum, 16);
    EXPECT_EQ(findLimit("fragment.samplers")->portable(), 32);
    EXPECT_EQ(findLimit("vertex.storageBlocks")->glMinimum, 0);
}

TEST(PortableLimits, TenImageUnitsFailAndSeventeenSamplersWarn) {
    ProgramUse use;
    use.stages[static_cast<size_t>(ShaderStage::Compute)] = {true, 10, 0, 0, 0};
    use.imageUnits = 10;
    use.combinedImageUniforms = 10;
    use.computeLocalSize[0] = use.computeLocalSize[1] = 8;
    use.computeLocalSize[2] = 1;
    use.computeInvocations = 64;
    const auto f = auditProgram("nichols.pyramidReduce", use);
    std::set<std::string> failing, warning;
    for (const auto& x : f) (x.pastPortable ? failing : warning).insert(x.key);
    EXPECT_EQ(failing, (std::set<std::string>{"imageUnits", "compute.imageUniforms"}));
    EXPECT_EQ(warning, (std::set<std::string>{"combinedImageUniforms"}));  // 10 > 8 but NVIDIA has 48
    for (const auto& x : f) {
        EXPECT_EQ(x.message.find('\n'), std::string::npos);
        EXPECT_NE(x.message.find("nichols.pyramidReduce"), std::string::npos);
    }
    const auto units = std::find_if(f.begin(), f.end(), [](const LimitFinding& x) { return x.key == "imageUnits"; });
    EXPECT_NE(units->message.find("units 0..9"), std::string::npos) << units->message;

    ProgramUse sh;  // finding #15: vct's sh-f32 trace.frag with 17 samplers
    sh.stages[static_cast<size_t>(ShaderStage::Vertex)] = {true, 0, 0, 0, 1};
    sh.stages[static_cast<size_t>(ShaderStage::Fragment)] = {true, 0, 17, 2, 1};
    sh.textureUnits = 17;
    const auto g = auditProgram("vct.trace", sh);
    ASSERT_EQ(g.size(), 1u);
    EXPECT_EQ(g[0].key, "fragment.samplers");
    EXPECT_FALSE(g[0].pastPortable);
    sh.stages[static_cast<size_t>(ShaderStage::Fragment)].samplers = 33;
    EXPECT_TRUE(auditProgram("vct.trace", sh)[0].pastPortable);
}

TEST(PortableLimits, AProgramWithinTheMinimumsHasNoFinding) {
    ProgramUse use;
    use.stages[static_cast<size_t>(ShaderStage::Vertex)] = {true, 0, 2, 0, 2};
    use.stages[static_cast<size_t>(ShaderStage::Fragment)] = {true, 8, 16, 8, 14};
    use.imageUnits = 8;
    use.textureUnits = 16;
    use.combinedImageUniforms = 8;
    use.largestUniformBlock = 16384;
    EXPECT_TRUE(auditProgram("p", use).empty());
    use.largestUniformBlock = 16385;  // one byte past: a warning (every vendor has 64 KiB)
    const auto f = auditProgram("p", use);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].key, "uniformBlockSize");
    EXPECT_FALSE(f[0].pastPortable);
}

TEST(PortableLimits, ClampLowersEveryLimitToTheGlMinimum) {
    GpuInfo llvmpipe;
    llvmpipe.maxImageUnits = 192;
    llvmpipe.maxUniformBlockSize = 65536;
    llvmpipe.maxShaderStorageBlockSize = 134217728;
    llvmpipe.maxTextureBufferSize = 134217728;
    llvmpipe.maxDepthTextureSamples = 4;
    llvmpipe.maxGeometryOutputVertices = 1024;
    llvmpipe.maxComputeWorkGroupSize[2] = 1024;
    for (int s = 0; s < 4; ++s) llvmpipe.maxImageUniforms[s] = 32;
    llvmpipe.maxTextureSize = 8192;  // below the minimum stays (a clamp never raises)
    const GpuInfo c = clampToGlMinimums(llvmpipe);
    EXPECT_TRUE(c.portableLimits);
    EXPECT_EQ(c.maxImageUnits, 8);
    EXPECT_EQ(c.maxUniformBlockSize, 16384);
    EXPECT_EQ(c.maxTextureBufferSize, 134217728);  // the vendors' lowest, not GL's 65,536 (see the clamp)
    EXPECT_EQ(c.maxDepthTextureSamples, 4);  // GL_MAX_SAMPLES' minimum, not the texture minimum of 1 (see the clamp)
    EXPECT_EQ(c.maxGeometryOutputVertices, 256);
    EXPECT_EQ(c.maxComputeWorkGroupSize[2], 64);
    EXPECT_EQ(c.maxImageUniforms[0], 0);  // vertex
    EXPECT_EQ(c.maxImageUniforms[3], 8);  // compute
    EXPECT_EQ(c.maxTextureSize, 8192);
}

TEST(PortableLimits, AllowListParsesAndRejectsUnknownKeys) {
    auto list = parseAllowList("# comment\n\nnichols.pyramidReduce imageUnits #1 ten units\nvct.trace glslang #15\n", "a.txt");
    ASSERT_TRUE(list.ok()) << list.error().message;
    ASSERT_EQ(list->size(), 2u);
    EXPECT_NE(findAllowed(*list, "nichols.pyramidReduce", "imageUnits"), nullptr);
    EXPECT_EQ(findAllowed(*list, "nichols.pyramidReduce", "compute.imageUniforms"), nullptr);
    EXPECT_EQ((*list)[0].finding, "#1");
    auto bad = parseAllowList("p imageUnitz #1\n", "a.txt");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("a.txt:1"), std::string::npos);
    EXPECT_FALSE(parseAllowList("p imageUnits\n", "a.txt").ok());  // no finding number
}

TEST(PortableLimits, DocsTableShowsTheCodesValues) {
    // docs/gpu.md "Limits" prints the table; a value changed in one place and not the other fails here.
    std::ifstream in(std::string(BOUNCE_SOURCE_DIR) + "/docs/gpu.md");
    ASSERT_TRUE(in) << "docs/gpu.md";
    std::map<std::string, std::vector<long long>> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("| `", 0) != 0) continue;
        std::vector<std::string> cells;
        std::stringstream ss(line.substr(1));
        for (std::string cell; std::getline(ss, cell, '|');) cells.push_back(cell);
        if (cells.size() < 9) continue;
        const std::string key = cells[0].substr(cells[0].find('`') + 1, cells[0].rfind('`') - cells[0].find('`') - 1);
        std::vector<long long> values;
        for (size_t c = 3; c < 9; ++c) values.push_back(std::stoll(cells[c]));
        rows[key] = values;
    }
    for (const LimitRow& r : limitTable()) {
        const auto it = rows.find(std::string(r.key));
        ASSERT_NE(it, rows.end()) << r.key << " missing from docs/gpu.md";
        const std::vector<long long> expected = {r.glMinimum, r.nvidia, r.amd, r.intel, r.llvmpipe, r.portable()};
        EXPECT_EQ(it->second, expected) << r.key;
    }
    EXPECT_EQ(rows.size(), limitTable().size());
}
