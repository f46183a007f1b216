// The checks Program::build runs on a linked program (gpu/ProgramChecks.h): the portable-limits audit
// over GL's program interface queries, and the shader dump for glslangValidator.
#include "gpu/ProgramChecks.h"

#include "core/FileIo.h"
#include "gpu/BarrierTracker.h"
#include "gpu/Context.h"
#include "gpu/GlslScan.h"
#include "gpu/PortableLimits.h"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>

namespace bounce::gl {

bool isImageType(GLenum t) {
    switch (t) {
        case GL_IMAGE_1D: case GL_IMAGE_2D: case GL_IMAGE_3D: case GL_IMAGE_2D_RECT: case GL_IMAGE_CUBE:
        case GL_IMAGE_BUFFER: case GL_IMAGE_1D_ARRAY: case GL_IMAGE_2D_ARRAY: case GL_IMAGE_CUBE_MAP_ARRAY:
        case GL_IMAGE_2D_MULTISAMPLE: case GL_IMAGE_2D_MULTISAMPLE_ARRAY:
        case GL_INT_IMAGE_1D: case GL_INT_IMAGE_2D: case GL_INT_IMAGE_3D: case GL_INT_IMAGE_2D_RECT: case GL_INT_IMAGE_CUBE:
        case GL_INT_IMAGE_BUFFER: case GL_INT_IMAGE_1D_ARRAY: case GL_INT_IMAGE_2D_ARRAY: case GL_INT_IMAGE_CUBE_MAP_ARRAY:
        case GL_INT_IMAGE_2D_MULTISAMPLE: case GL_INT_IMAGE_2D_MULTISAMPLE_ARRAY:
        case GL_UNSIGNED_INT_IMAGE_1D: case GL_UNSIGNED_INT_IMAGE_2D: case GL_UNSIGNED_INT_IMAGE_3D:
        case GL_UNSIGNED_INT_IMAGE_2D_RECT: case GL_UNSIGNED_INT_IMAGE_CUBE: case GL_UNSIGNED_INT_IMAGE_BUFFER:
        case GL_UNSIGNED_INT_IMAGE_1D_ARRAY: case GL_UNSIGNED_INT_IMAGE_2D_ARRAY: case GL_UNSIGNED_INT_IMAGE_CUBE_MAP_ARRAY:
        case GL_UNSIGNED_INT_IMAGE_2D_MULTISAMPLE: case GL_UNSIGNED_INT_IMAGE_2D_MULTISAMPLE_ARRAY: return true;
        default: return false;
    }
}

bool isSamplerType(GLenum t) {
    switch (t) {
        case GL_SAMPLER_1D: case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE: case GL_SAMPLER_1D_SHADOW:
        case GL_SAMPLER_2D_SHADOW: case GL_SAMPLER_1D_ARRAY: case GL_SAMPLER_2D_ARRAY: case GL_SAMPLER_1D_ARRAY_SHADOW:
        case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_SAMPLER_2D_MULTISAMPLE: case GL_SAMPLER_2D_MULTISAMPLE_ARRAY:
        case GL_SAMPLER_CUBE_SHADOW: case GL_SAMPLER_BUFFER: case GL_SAMPLER_2D_RECT: case GL_SAMPLER_2D_RECT_SHADOW:
        case GL_SAMPLER_CUBE_MAP_ARRAY: case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW:
        case GL_INT_SAMPLER_1D: case GL_INT_SAMPLER_2D: case GL_INT_SAMPLER_3D: case GL_INT_SAMPLER_CUBE:
        case GL_INT_SAMPLER_1D_ARRAY: case GL_INT_SAMPLER_2D_ARRAY: case GL_INT_SAMPLER_2D_MULTISAMPLE:
        case GL_INT_SAMPLER_2D_MULTISAMPLE_ARRAY: case GL_INT_SAMPLER_BUFFER: case GL_INT_SAMPLER_2D_RECT:
        case GL_INT_SAMPLER_CUBE_MAP_ARRAY:
        case GL_UNSIGNED_INT_SAMPLER_1D: case GL_UNSIGNED_INT_SAMPLER_2D: case GL_UNSIGNED_INT_SAMPLER_3D:
        case GL_UNSIGNED_INT_SAMPLER_CUBE: case GL_UNSIGNED_INT_SAMPLER_1D_ARRAY: case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
        case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE: case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE_ARRAY:
        case GL_UNSIGNED_INT_SAMPLER_BUFFER: case GL_UNSIGNED_INT_SAMPLER_2D_RECT:
        case GL_UNSIGNED_INT_SAMPLER_CUBE_MAP_ARRAY: return true;
        default: return false;
    }
}

namespace {

int stageIndex(GLenum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER: return static_cast<int>(ShaderStage::Vertex);
        case GL_GEOMETRY_SHADER: return static_cast<int>(ShaderStage::Geometry);
        case GL_FRAGMENT_SHADER: return static_cast<int>(ShaderStage::Fragment);
        case GL_COMPUTE_SHADER: return static_cast<int>(ShaderStage::Compute);
        default: return -1;  // tessellation: bounce has none
    }
}

constexpr GLenum kReferencedBy[kShaderStageCount] = {GL_REFERENCED_BY_VERTEX_SHADER, GL_REFERENCED_BY_GEOMETRY_SHADER,
                                                     GL_REFERENCED_BY_FRAGMENT_SHADER, GL_REFERENCED_BY_COMPUTE_SHADER};

std::string resourceName(GLuint program, GLenum interface, GLuint index) {
    GLint length = 0;
    const GLenum prop = GL_NAME_LENGTH;
    glGetProgramResourceiv(program, interface, index, 1, &prop, 1, nullptr, &length);
    std::string name(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramResourceName(program, interface, index, length, nullptr, name.data());
    while (!name.empty() && name.back() == '\0') name.pop_back();
    return name;
}

// The stages referencing block `index` of `interface`. Mesa 22.3 reports no stage for storage blocks
// (REFERENCED_BY_* all 0, issue 29 review): then a block counts in every stage whose source declares
// a buffer block of that name.
std::array<bool, kShaderStageCount> blockStages(GLuint program, GLenum interface, GLuint index, const std::string& name,
                                               const std::vector<StageSource>& sources) {
    std::array<bool, kShaderStageCount> out{};
    GLint refs[kShaderStageCount] = {};
    glGetProgramResourceiv(program, interface, index, kShaderStageCount, kReferencedBy, kShaderStageCount, nullptr, refs);
    bool any = false;
    for (int s = 0; s < kShaderStageCount; ++s) any |= (out[static_cast<size_t>(s)] = refs[s] != 0);
    if (any || interface != GL_SHADER_STORAGE_BLOCK) return out;
    const std::string base = name.substr(0, name.find('['));
    for (const StageSource& src : sources) {
        const int s = stageIndex(src.stage);
        if (s >= 0 && declaresBufferBlock(src.text, base)) out[static_cast<size_t>(s)] = true;
    }
    return out;
}

}  // namespace

ProgramUse queryProgramUse(GLuint program, const std::vector<StageSource>& sources) {
    ProgramUse use;
    for (const StageSource& src : sources)
        if (const int s = stageIndex(src.stage); s >= 0) use.stages[static_cast<size_t>(s)].present = true;
    // Opaque uniforms: images and samplers, per stage, and the units they are bound to.
    GLint count = 0;
    glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    for (GLint u = 0; u < count; ++u) {
        const GLenum props[] = {GL_TYPE, GL_ARRAY_SIZE, GL_BLOCK_INDEX, GL_REFERENCED_BY_VERTEX_SHADER,
                                GL_REFERENCED_BY_GEOMETRY_SHADER, GL_REFERENCED_BY_FRAGMENT_SHADER,
                                GL_REFERENCED_BY_COMPUTE_SHADER};
        GLint v[7] = {};
        glGetProgramResourceiv(program, GL_UNIFORM, static_cast<GLuint>(u), 7, props, 7, nullptr, v);
        const GLenum type = static_cast<GLenum>(v[0]);
        const bool image = isImageType(type), sampler = isSamplerType(type);
        if (v[2] != -1 || (!image && !sampler)) continue;
        const int elements = std::max(v[1], 1);
        for (int s = 0; s < kShaderStageCount; ++s) {
            if (!v[3 + s]) continue;
            (image ? use.stages[static_cast<size_t>(s)].imageUniforms : use.stages[static_cast<size_t>(s)].samplers) += elements;
        }
        if (image) use.combinedImageUniforms += elements;
        const std::string name = resourceName(program, GL_UNIFORM, static_cast<GLuint>(u));
        const std::string base = name.substr(0, name.find('['));
        for (int e = 0; e < elements; ++e) {
            const std::string element = v[1] > 1 || name.find('[') != std::string::npos ? fmt::format("{}[{}]", base, e) : base;
            const GLint location = glGetUniformLocation(program, element.c_str());
            if (location < 0) continue;
            GLint unit = 0;
            glGetUniformiv(program, location, &unit);
            int& highest = image ? use.imageUnits : use.textureUnits;
            highest = std::max(highest, unit + 1);
        }
    }
    // Storage and uniform blocks, per stage, their bindings and the largest uniform block.
    for (const GLenum interface : {GL_SHADER_STORAGE_BLOCK, GL_UNIFORM_BLOCK}) {
        glGetProgramInterfaceiv(program, interface, GL_ACTIVE_RESOURCES, &count);
        for (GLint b = 0; b < count; ++b) {
            const GLenum props[] = {GL_BUFFER_BINDING, GL_BUFFER_DATA_SIZE};
            GLint v[2] = {};
            glGetProgramResourceiv(program, interface, static_cast<GLuint>(b), 2, props, 2, nullptr, v);
            const std::string name = resourceName(program, interface, static_cast<GLuint>(b));
            const auto stages = blockStages(program, interface, static_cast<GLuint>(b), name, sources);
            const bool storage = interface == GL_SHADER_STORAGE_BLOCK;
            for (int s = 0; s < kShaderStageCount; ++s)
                if (stages[static_cast<size_t>(s)])
                    ++(storage ? use.stages[static_cast<size_t>(s)].storageBlocks : use.stages[static_cast<size_t>(s)].uniformBlocks);
            if (storage) {
                ++use.combinedStorageBlocks;
                use.storageBindings = std::max(use.storageBindings, v[0] + 1);
            } else {
                use.uniformBindings = std::max(use.uniformBindings, v[0] + 1);
                if (v[1] > use.largestUniformBlock) {
                    use.largestUniformBlock = v[1];
                    use.largestUniformBlockName = name;
                }
            }
        }
    }
    if (use.stages[static_cast<size_t>(ShaderStage::Compute)].present) {
        glGetProgramiv(program, GL_COMPUTE_WORK_GROUP_SIZE, use.computeLocalSize);
        use.computeInvocations = use.computeLocalSize[0] * use.computeLocalSize[1] * use.computeLocalSize[2];
    }
    if (use.stages[static_cast<size_t>(ShaderStage::Geometry)].present) {
        glGetProgramiv(program, GL_GEOMETRY_VERTICES_OUT, &use.geometryOutputVertices);
        glGetProgramiv(program, GL_GEOMETRY_SHADER_INVOCATIONS, &use.geometryInvocations);
    }
    return use;
}

namespace {

std::mutex g_mutex;  // the report file and the once-per-program logs
std::set<std::string> g_reported;

Expected<const std::vector<AllowEntry>*> allowList() {
    static std::optional<Expected<std::vector<AllowEntry>>> list;
    if (!list) {
        const char* file = std::getenv("BOUNCE_PORTABLE_ALLOW");
        if (!file || !*file) list.emplace(std::vector<AllowEntry>{});
        else if (auto text = readTextFile(file); !text.ok()) list.emplace(Error{"BOUNCE_PORTABLE_ALLOW: " + text.error().message});
        else list.emplace(parseAllowList(*text, file));
    }
    if (!list->ok()) return list->error();
    return &list->value();
}

void report(const std::string& status, std::string_view program, const LimitFinding& f) {
    const char* file = std::getenv("BOUNCE_PORTABLE_REPORT");
    if (!file || !*file) return;
    std::ofstream out(file, std::ios::app);
    out << status << '\t' << program << '\t' << f.key << '\t' << f.value << '\t' << f.glMinimum << '\t' << f.portable << '\n';
}

}  // namespace

Expected<void> auditLinkedProgram(std::string_view label, GLuint program, const std::vector<StageSource>& sources) {
    if (barrierCheckRequested() || barrierTracking()) {
        std::vector<std::string> texts;
        for (const auto& s : sources) texts.push_back(s.text);
        detail::barrierNoteProgramSources(program, texts);
    }
    const bool portable = portableLimitsMode();
    const std::vector<LimitFinding> findings = auditProgram(label, queryProgramUse(program, sources));
    if (findings.empty()) return {};
    BOUNCE_TRY(const std::vector<AllowEntry>* allowed, allowList());
    std::lock_guard lock(g_mutex);
    if (portable) {
        // Every resource past its portable limit, in one line: the program cannot link on some vendor's driver.
        std::string refused;
        const std::string prefix = fmt::format("program '{}': ", label);
        for (const LimitFinding& f : findings) {
            if (!f.pastPortable || findAllowed(*allowed, label, f.key)) continue;
            // One line: the program named once, then each resource.
            refused += refused.empty() ? f.message
                                       : "; " + (f.message.rfind(prefix, 0) == 0 ? f.message.substr(prefix.size()) : f.message);
        }
        if (!refused.empty()) return makeError("{} (BOUNCE_PORTABLE_LIMITS=1; docs/gpu.md \"Limits\")", refused);
    }
    for (const LimitFinding& f : findings) {
        const AllowEntry* entry = findAllowed(*allowed, label, f.key);
        const std::string status = !f.pastPortable ? "warn" : entry ? "allowed" : "error";
        if (!g_reported.insert(std::string(label) + "/" + f.key).second) continue;  // once per program and resource
        report(status, label, f);
        const std::string line = entry ? f.message + fmt::format(" [known: finding {}]", entry->finding) : f.message;
        if (portable) spdlog::warn("{}", line);
        else spdlog::info("{}", line);
    }
    return {};
}

void dumpShaderSources(std::string_view label, const std::vector<StageSource>& sources) {
    const char* dir = std::getenv("BOUNCE_SHADER_DUMP");
    if (!dir || !*dir) return;
    namespace fs = std::filesystem;
    std::string all;
    for (const StageSource& s : sources) all += s.file + '\n' + s.text;
    // One folder per program and define combination: LABEL-HASH (the hash of the assembled sources).
    const fs::path folder = fs::path(dir) / fmt::format("{}-{:016x}", label, std::hash<std::string>{}(all));
    std::error_code ec;
    if (fs::exists(folder, ec)) return;
    fs::create_directories(folder, ec);
    for (const StageSource& s : sources) {
        const char* ext = s.stage == GL_VERTEX_SHADER ? "vert" : s.stage == GL_GEOMETRY_SHADER ? "geom"
                          : s.stage == GL_FRAGMENT_SHADER ? "frag" : s.stage == GL_COMPUTE_SHADER ? "comp" : "glsl";
        std::string name = fs::path(s.file).stem().string();
        std::ofstream(folder / fmt::format("{}.{}", name, ext)) << s.text;
    }
    std::ofstream(folder / "program.txt") << label << '\n';
}

}  // namespace bounce::gl
