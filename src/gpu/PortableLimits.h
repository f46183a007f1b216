#pragma once
// Portable GL limits: what a program may use so that it links and runs on every OpenGL 4.5 driver
// bounce's users have, not only on llvmpipe (which grants 32 image uniforms per stage, 192 image
// units and 16 storage blocks in every stage). GL-free, so the table and the audit are unit-tested.
//
// Every row gives the GL 4.5 core specification's minimum maximum (Table 23.53 ff., "Implementation
// Dependent Values"), typical NVIDIA, AMD (Mesa radeonsi) and Intel (Mesa iris) values, and llvmpipe's
// measured one (Mesa 22.3). A program whose use exceeds the GL minimum but not the lowest vendor
// value gets a warning; one past the lowest vendor value ("portable limit") cannot run on that vendor's
// driver. docs/gpu.md "Limits" prints the table with its sources.
//
// Program::build audits every linked program (gpu/Program.cpp). Normally a finding is logged at info
// level; with BOUNCE_PORTABLE_LIMITS=1 (the portable-limits mode CI runs) GpuInfo is clamped to the
// GL minimums (so setup checks answer as on a minimal driver) and a program past a portable limit
// fails to link with a one-line error naming the program, the resource and the limit, unless an
// allow-list (BOUNCE_PORTABLE_ALLOW=file, tests/portable/allow-list.txt) names it as a known finding.
#include "gpu/GpuInfo.h"

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace bounce::gl {

enum class ShaderStage { Vertex, Geometry, Fragment, Compute };
inline constexpr int kShaderStageCount = 4;
std::string_view stageName(ShaderStage s);

// One row of the limits table: a resource, its GL enum name and the values.
struct LimitRow {
    std::string_view key;     // "compute.imageUniforms", used in messages and allow-lists
    std::string_view what;    // "image uniforms in the compute stage"
    std::string_view glName;  // "GL_MAX_COMPUTE_IMAGE_UNIFORMS"
    long long glMinimum;      // GL 4.5 core, Table 23.53 ff.
    long long nvidia, amd, intel, llvmpipe;
    // The value a program may reach and still link on all three vendors: their lowest value.
    long long portable() const;
};

// The table (docs/gpu.md prints it). Keys are "<stage>.<resource>" or a program-wide name.
std::span<const LimitRow> limitTable();
const LimitRow* findLimit(std::string_view key);

// What one linked program uses, from GL's program interface queries (gpu/Program.cpp).
struct StageUse {
    bool present = false;
    int imageUniforms = 0;   // image variables (array elements counted)
    int samplers = 0;        // sampler variables (array elements counted)
    int storageBlocks = 0;
    int uniformBlocks = 0;
};
struct ProgramUse {
    std::array<StageUse, kShaderStageCount> stages;
    int imageUnits = 0;            // highest image unit bound by a uniform, + 1
    int textureUnits = 0;          // highest texture unit, + 1
    int combinedImageUniforms = 0;
    int combinedStorageBlocks = 0;
    int storageBindings = 0;       // highest storage-buffer binding + 1
    int uniformBindings = 0;       // highest uniform-buffer binding + 1
    long long largestUniformBlock = 0;  // bytes
    std::string largestUniformBlockName;
    int combinedOutputResources = 0;   // fragment: images + storage blocks + colour outputs
    int computeLocalSize[3] = {0, 0, 0};
    int computeInvocations = 0;
    int geometryOutputVertices = 0;
    int geometryInvocations = 0;
};

struct LimitFinding {
    std::string key;
    long long value = 0;
    long long glMinimum = 0;
    long long portable = 0;
    bool pastPortable = false;  // past the lowest vendor value: fails on a real driver
    std::string message;        // one line: "program 'x': 10 image units (units 0..9), past ..."
};

// Every resource of `use` past its GL minimum.
std::vector<LimitFinding> auditProgram(std::string_view program, const ProgramUse& use);

// GpuInfo with every limit lowered to the GL 4.5 minimum (BOUNCE_PORTABLE_LIMITS=1).
GpuInfo clampToGlMinimums(GpuInfo info);

// An allow-list of known findings: lines "PROGRAM KEY #FINDING [comment]"; '#' alone starts a comment line.
struct AllowEntry {
    std::string program, key, finding;
    int line = 0;
};
Expected<std::vector<AllowEntry>> parseAllowList(const std::string& text, const std::string& file);
const AllowEntry* findAllowed(const std::vector<AllowEntry>& list, std::string_view program, std::string_view key);

}  // namespace bounce::gl
