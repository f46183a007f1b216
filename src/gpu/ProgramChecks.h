#pragma once
// What Program::build does with a linked program besides linking it (gpu/Program.cpp):
// - the portable-limits audit (gpu/PortableLimits.h): the program's active resources per stage from
//   GL's program interface queries, against the limits table; logged at info level normally, a link
//   error past a portable limit under BOUNCE_PORTABLE_LIMITS=1 unless BOUNCE_PORTABLE_ALLOW's list names
//   it; each finding once per process to BOUNCE_PORTABLE_REPORT (a file, tab-separated) if set.
// - BOUNCE_SHADER_DUMP=DIR: the assembled source of every stage (the text the driver compiles, includes
//   and defines resolved) is written to DIR/LABEL-HASH/, for glslangValidator (tests/portable/).
#include "core/Error.h"
#include "gpu/PortableLimits.h"

#include <epoxy/gl.h>

#include <string>
#include <string_view>
#include <vector>

namespace bounce::gl {

struct StageSource {
    GLenum stage = 0;
    std::string file;  // relative to shaders/
    std::string text;  // as compiled
};

ProgramUse queryProgramUse(GLuint program, const std::vector<StageSource>& sources);
Expected<void> auditLinkedProgram(std::string_view label, GLuint program, const std::vector<StageSource>& sources);
void dumpShaderSources(std::string_view label, const std::vector<StageSource>& sources);
// GL_TYPE of an active uniform: an image or a sampler type (also used by gpu/BarrierTracker).
bool isImageType(GLenum type);
bool isSamplerType(GLenum type);

}  // namespace bounce::gl
