// gl::mapShaderLog (src/gpu/ShaderLog.h): each driver's compiler-log prefix mapped to file:line.
// AMD's proprietary driver (and Intel's on Windows) write "ERROR: 0:12:", which the old pattern
// (Mesa and NVIDIA only) left as assembled-text positions (issue 29 #23).
#include "gpu/ShaderLog.h"

#include <gtest/gtest.h>

using bounce::gl::LineOrigin;
using bounce::gl::mapShaderLog;

namespace {
const std::vector<LineOrigin> kOrigins = {{"(prelude)", 1}, {"(host define)", 1}, {"techniques/x/a.comp", 7}, {"common/b.glsl", 40}};
}

TEST(ShaderLog, MesaNvidiaAndAmdPrefixesMapToFileAndLine) {
    EXPECT_EQ(mapShaderLog("0:3(5): error: `foo' undeclared\n", kOrigins), "techniques/x/a.comp:7: error: `foo' undeclared");
    EXPECT_EQ(mapShaderLog("0(4) : error C1008: undefined variable \"foo\"", kOrigins),
              "common/b.glsl:40: error C1008: undefined variable \"foo\"");
    EXPECT_EQ(mapShaderLog("ERROR: 0:3: 'foo' : undeclared identifier\nERROR: 1 compilation errors.", kOrigins),
              "ERROR: techniques/x/a.comp:7: 'foo' : undeclared identifier\nERROR: 1 compilation errors.");
    EXPECT_EQ(mapShaderLog("WARNING: 0:4: 'x' : unused", kOrigins), "WARNING: common/b.glsl:40: 'x' : unused");
    // Several lines, and a number past the table left alone.
    EXPECT_EQ(mapShaderLog("ERROR: 0:3: a\nERROR: 0:99: b", kOrigins), "ERROR: techniques/x/a.comp:7: a\nERROR: 0:99: b");
}
