// gl::outOfMemoryMessage (src/gpu/MemoryCheck.h, issue 29 #21): an allocation past the video memory the
// driver reports free (NVX_gpu_memory_info / ATI_meminfo) is refused in one line like a
// GL_OUT_OF_MEMORY; without the report (llvmpipe) only GL's error refuses.
#include "gpu/MemoryCheck.h"

#include <gtest/gtest.h>

using bounce::gl::outOfMemoryMessage;

TEST(MemoryCheck, RefusesPastTheReportedFreeMemoryInOneLine) {
    constexpr uint64_t kMiB = 1024u * 1024u;
    EXPECT_EQ(outOfMemoryMessage("texture", "vct.iso", 600 * kMiB, false, std::nullopt), "");
    EXPECT_EQ(outOfMemoryMessage("texture", "vct.iso", 600 * kMiB, false, 601 * kMiB), "");
    const std::string past = outOfMemoryMessage("texture", "vct.iso", 600 * kMiB, false, 599 * kMiB);
    EXPECT_NE(past.find("out of GPU memory allocating texture 'vct.iso' (629.1 MB)"), std::string::npos) << past;
    EXPECT_NE(past.find("628.1 MB of video memory free"), std::string::npos) << past;
    EXPECT_EQ(past.find('\n'), std::string::npos);
    const std::string error = outOfMemoryMessage("buffer", "b", 1000000, true, std::nullopt);
    EXPECT_NE(error.find("out of GPU memory allocating buffer 'b' (1.0 MB)"), std::string::npos) << error;
}
