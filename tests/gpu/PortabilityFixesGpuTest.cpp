// Issue 29's remaining findings, fixed after part 1 (docs/gpu.md "Fixed findings"): each test fails on
// the code before its fix. Limits are made testable on llvmpipe with a GpuInfo copy set to a smaller
// driver's values (what BOUNCE_PORTABLE_LIMITS=1 does to the context's own).
#include "GpuTestSupport.h"
#include "gpu/Bindings.h"
#include "techniques/nichols/VplWindow.h"
#include "techniques/radiosity/RadiositySystem.h"

using namespace bounce;

namespace {
class PortabilityFixesGpuTest : public gputest::GpuTest {};
}  // namespace

TEST_F(PortabilityFixesGpuTest, RadiosityMsaaIsCheckedAgainstDepthSamplesToo) {
    // #11: the hemicubes are multisample colour and depth arrays; many AMD/Intel drivers have 8 depth
    // samples and more colour samples. The old check read GL_MAX_COLOR_TEXTURE_SAMPLES only.
    gl::GpuInfo info = gputest::sharedContext()->info();
    info.maxColorTextureSamples = 16;
    info.maxDepthTextureSamples = 8;
    EXPECT_TRUE(radiosity::RadiositySystem::checkMsaa(8, info).ok());
    auto refused = radiosity::RadiositySystem::checkMsaa(16, info);
    ASSERT_FALSE(refused.ok());
    const std::string& m = refused.error().message;
    EXPECT_NE(m.find("msaa=16"), std::string::npos) << m;
    EXPECT_NE(m.find("GL_MAX_DEPTH_TEXTURE_SAMPLES"), std::string::npos) << m;
    EXPECT_NE(m.find(" 8 "), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    info.maxColorTextureSamples = 2;
    EXPECT_NE(radiosity::RadiositySystem::checkMsaa(4, info).error().message.find("GL_MAX_COLOR_TEXTURE_SAMPLES"), std::string::npos);
    // The context's own limits accept the default (van de Hoef's 4 samples), also when clamped.
    EXPECT_TRUE(radiosity::RadiositySystem::checkMsaa(4, gputest::sharedContext()->info()).ok());
}

TEST_F(PortabilityFixesGpuTest, EveryVplWindowBindsAWholeWindow) {
    // #13: the last window of a cache was bound with the range left in the buffer, shorter than the
    // block's data size (undefined in GL). Caches are now padded (VplWindow::paddedRecords) and every
    // bound range is the whole window.
    const int window = nichols::VplWindow::size();
    const GLint64 windowBytes = static_cast<GLint64>(window) * static_cast<GLint64>(sizeof(nichols::VplRecord));
    for (int records : {1, 16, 17, window - 1, window, window + 1, 3 * window + 40}) {
        const int padded = nichols::VplWindow::paddedRecords(records);
        EXPECT_GE(padded, records);
        EXPECT_LT(padded, records + window + nichols::VplWindow::kAlignRecords) << "padding is at most one window";
        gl::Buffer cache = gl::Buffer::create("test.vplCache", static_cast<size_t>(padded) * sizeof(nichols::VplRecord));
        for (int first = 0; first < records; first += nichols::VplWindow::kAlignRecords) {
            const int count = std::min(records - first, nichols::VplWindow::kAlignRecords);
            const int windowFirst = nichols::VplWindow::bind(cache, first, count);
            GLint64 size = 0, offset = 0;
            glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, BINDING_UBO_VPL_WINDOW, &size);
            glGetInteger64i_v(GL_UNIFORM_BUFFER_START, BINDING_UBO_VPL_WINDOW, &offset);
            EXPECT_EQ(size, windowBytes) << records << " records, window at " << windowFirst;
            EXPECT_EQ(offset, static_cast<GLint64>(windowFirst) * static_cast<GLint64>(sizeof(nichols::VplRecord)));
        }
    }
}
