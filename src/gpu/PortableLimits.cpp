#include "gpu/PortableLimits.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

namespace bounce::gl {

namespace {

// Sources (docs/gpu.md "Limits" has the links):
//  GL 4.5 minimum: the OpenGL 4.5 core profile specification, Tables 23.53-23.67.
//  NVIDIA: the proprietary Linux driver (GeForce/RTX/data-centre parts, 470-550 series) as listed by
//    opengl.gpuinfo.org; GL_MAX_IMAGE_UNITS and the per-stage image uniforms are 8 on every NVIDIA
//    GL driver listed there.
//  AMD: Mesa radeonsi, from its driver constants (si_state.h: SI_NUM_SAMPLERS 32, SI_NUM_IMAGES 16,
//    SI_NUM_SHADER_BUFFERS 32, SI_NUM_CONST_BUFFERS 16 less the default uniform block).
//  Intel: Mesa iris (iris_context.h: IRIS_MAX_SAMPLERS 32, IRIS_MAX_IMAGES 64; 16 storage blocks per stage).
//  llvmpipe: measured on this project's CI machine (Mesa 22.3.6, `bounce info`).
// A vendor value not known for certain is that vendor's lowest value seen; the mode errs on the safe side.
constexpr long long kInt32Max = 2147483647;
constexpr LimitRow kTable[] = {
    // key, what, GL name, GL minimum, NVIDIA, AMD, Intel, llvmpipe
    {"imageUnits", "image units bound (highest unit + 1)", "GL_MAX_IMAGE_UNITS", 8, 8, 96, 384, 192},
    {"vertex.imageUniforms", "image uniforms in the vertex stage", "GL_MAX_VERTEX_IMAGE_UNIFORMS", 0, 8, 16, 64, 32},
    {"geometry.imageUniforms", "image uniforms in the geometry stage", "GL_MAX_GEOMETRY_IMAGE_UNIFORMS", 0, 8, 16, 64, 32},
    {"fragment.imageUniforms", "image uniforms in the fragment stage", "GL_MAX_FRAGMENT_IMAGE_UNIFORMS", 8, 8, 16, 64, 32},
    {"compute.imageUniforms", "image uniforms in the compute stage", "GL_MAX_COMPUTE_IMAGE_UNIFORMS", 8, 8, 16, 64, 32},
    {"combinedImageUniforms", "image uniforms in all stages", "GL_MAX_COMBINED_IMAGE_UNIFORMS", 8, 48, 96, 384, 192},
    {"vertex.samplers", "samplers in the vertex stage", "GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS", 16, 32, 32, 32, 32},
    {"geometry.samplers", "samplers in the geometry stage", "GL_MAX_GEOMETRY_TEXTURE_IMAGE_UNITS", 16, 32, 32, 32, 32},
    {"fragment.samplers", "samplers in the fragment stage", "GL_MAX_TEXTURE_IMAGE_UNITS", 16, 32, 32, 32, 32},
    {"compute.samplers", "samplers in the compute stage", "GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS", 16, 32, 32, 32, 32},
    {"textureUnits", "texture units bound (highest unit + 1)", "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", 80, 192, 192, 192, 192},
    {"vertex.storageBlocks", "storage blocks in the vertex stage", "GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS", 0, 16, 32, 16, 16},
    {"geometry.storageBlocks", "storage blocks in the geometry stage", "GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS", 0, 16, 32, 16, 16},
    {"fragment.storageBlocks", "storage blocks in the fragment stage", "GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS", 8, 16, 32, 16, 16},
    {"compute.storageBlocks", "storage blocks in the compute stage", "GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS", 8, 16, 32, 16, 16},
    {"combinedStorageBlocks", "storage blocks in all stages", "GL_MAX_COMBINED_SHADER_STORAGE_BLOCKS", 8, 96, 192, 96, 80},
    {"storageBindings", "storage-buffer bindings (highest binding + 1)", "GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS", 8, 96, 192, 96, 80},
    {"vertex.uniformBlocks", "uniform blocks in the vertex stage", "GL_MAX_VERTEX_UNIFORM_BLOCKS", 14, 14, 15, 15, 15},
    {"geometry.uniformBlocks", "uniform blocks in the geometry stage", "GL_MAX_GEOMETRY_UNIFORM_BLOCKS", 14, 14, 15, 15, 15},
    {"fragment.uniformBlocks", "uniform blocks in the fragment stage", "GL_MAX_FRAGMENT_UNIFORM_BLOCKS", 14, 14, 15, 15, 15},
    {"compute.uniformBlocks", "uniform blocks in the compute stage", "GL_MAX_COMPUTE_UNIFORM_BLOCKS", 14, 14, 15, 15, 15},
    {"uniformBindings", "uniform-buffer bindings (highest binding + 1)", "GL_MAX_UNIFORM_BUFFER_BINDINGS", 84, 84, 90, 90, 90},
    {"uniformBlockSize", "bytes of the largest uniform block", "GL_MAX_UNIFORM_BLOCK_SIZE", 16384, 65536, 65536, 65536, 65536},
    {"compute.invocations", "invocations of a compute work group", "GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", 1024, 1024, 1024, 1024, 1024},
    {"compute.localSizeX", "compute local size x", "GL_MAX_COMPUTE_WORK_GROUP_SIZE[0]", 1024, 1024, 1024, 1024, 1024},
    {"compute.localSizeY", "compute local size y", "GL_MAX_COMPUTE_WORK_GROUP_SIZE[1]", 1024, 1024, 1024, 1024, 1024},
    {"compute.localSizeZ", "compute local size z", "GL_MAX_COMPUTE_WORK_GROUP_SIZE[2]", 64, 64, 1024, 64, 64},
    {"geometry.outputVertices", "vertices a geometry shader emits (max_vertices)", "GL_MAX_GEOMETRY_OUTPUT_VERTICES", 256, 1024, 256, 256, 1024},
    {"geometry.invocations", "geometry shader invocations", "GL_MAX_GEOMETRY_SHADER_INVOCATIONS", 32, 32, 32, 32, 32},
    // Device limits: not properties of a program; the setup checks read them from GpuInfo, which the
    // portable mode clamps to the GL minimum.
    {"compute.sharedMemory", "bytes of shared memory of a compute program (no GL query: llvmpipe's own limit "
                             "is the GL minimum, so its linker already refuses more)",
     "GL_MAX_COMPUTE_SHARED_MEMORY_SIZE", 32768, 49152, 65536, 65536, 32768},
    {"compute.workGroupCount", "work groups per dispatch dimension (y, z; x is larger on GPUs)",
     "GL_MAX_COMPUTE_WORK_GROUP_COUNT", 65535, 65535, 65535, 65535, 65535},
    {"storageBlockSize", "bytes of a storage block", "GL_MAX_SHADER_STORAGE_BLOCK_SIZE", 134217728, kInt32Max, 134217728,
     134217728, 134217728},
    {"textureBufferSize", "texels of a buffer texture", "GL_MAX_TEXTURE_BUFFER_SIZE", 65536, 134217728, 134217728,
     134217728, 134217728},
    {"textureSize", "texels per side of a 2D texture", "GL_MAX_TEXTURE_SIZE", 16384, 32768, 16384, 16384, 16384},
    {"texture3dSize", "texels per side of a 3D texture", "GL_MAX_3D_TEXTURE_SIZE", 2048, 16384, 8192, 2048, 2048},
    {"arrayLayers", "layers of an array texture", "GL_MAX_ARRAY_TEXTURE_LAYERS", 2048, 2048, 8192, 2048, 2048},
    {"cubeMapSize", "texels per side of a cube map face", "GL_MAX_CUBE_MAP_TEXTURE_SIZE", 16384, 32768, 16384, 16384, 16384},
    {"colorTextureSamples", "samples of a multisample colour texture", "GL_MAX_COLOR_TEXTURE_SAMPLES", 1, 32, 8, 16, 4},
    {"depthTextureSamples", "samples of a multisample depth texture", "GL_MAX_DEPTH_TEXTURE_SAMPLES", 1, 32, 8, 8, 4},
    {"colorAttachments", "framebuffer colour attachments", "GL_MAX_COLOR_ATTACHMENTS", 8, 8, 8, 8, 8},
};

}  // namespace

std::string_view stageName(ShaderStage s) {
    switch (s) {
        case ShaderStage::Vertex: return "vertex";
        case ShaderStage::Geometry: return "geometry";
        case ShaderStage::Fragment: return "fragment";
        case ShaderStage::Compute: return "compute";
    }
    return "?";
}

long long LimitRow::portable() const { return std::max(glMinimum, std::min({nvidia, amd, intel})); }

std::span<const LimitRow> limitTable() { return kTable; }

const LimitRow* findLimit(std::string_view key) {
    for (const LimitRow& r : kTable)
        if (r.key == key) return &r;
    return nullptr;
}

std::vector<LimitFinding> auditProgram(std::string_view program, const ProgramUse& use) {
    std::vector<LimitFinding> out;
    auto check = [&](const std::string& key, long long value, const std::string& detail = {}) {
        const LimitRow* row = findLimit(key);
        if (!row || value <= row->glMinimum) return;
        LimitFinding f;
        f.key = key;
        f.value = value;
        f.glMinimum = row->glMinimum;
        f.portable = row->portable();
        f.pastPortable = value > f.portable;
        f.message = fmt::format("program '{}': {} {}{} ({}), {} GL 4.5's minimum {}{}", program, value, row->what,
                                detail.empty() ? "" : " " + detail, key, f.pastPortable ? "past" : "within the vendors' "
                                "values but past", row->glMinimum,
                                f.pastPortable ? fmt::format(" and the portable limit {} (NVIDIA {}, AMD {}, Intel {})",
                                                             f.portable, row->nvidia, row->amd, row->intel)
                                               : std::string());
        out.push_back(std::move(f));
    };
    for (int s = 0; s < kShaderStageCount; ++s) {
        const StageUse& st = use.stages[static_cast<size_t>(s)];
        if (!st.present) continue;
        const std::string stage(stageName(static_cast<ShaderStage>(s)));
        check(stage + ".imageUniforms", st.imageUniforms);
        check(stage + ".samplers", st.samplers);
        check(stage + ".storageBlocks", st.storageBlocks);
        check(stage + ".uniformBlocks", st.uniformBlocks);
    }
    check("imageUnits", use.imageUnits, use.imageUnits > 0 ? fmt::format("(units 0..{})", use.imageUnits - 1) : "");
    check("combinedImageUniforms", use.combinedImageUniforms);
    check("textureUnits", use.textureUnits);
    check("combinedStorageBlocks", use.combinedStorageBlocks);
    check("storageBindings", use.storageBindings);
    check("uniformBindings", use.uniformBindings);
    check("uniformBlockSize", use.largestUniformBlock,
          use.largestUniformBlockName.empty() ? "" : "('" + use.largestUniformBlockName + "')");
    if (use.stages[static_cast<size_t>(ShaderStage::Compute)].present) {
        check("compute.invocations", use.computeInvocations);
        check("compute.localSizeX", use.computeLocalSize[0]);
        check("compute.localSizeY", use.computeLocalSize[1]);
        check("compute.localSizeZ", use.computeLocalSize[2]);
    }
    if (use.stages[static_cast<size_t>(ShaderStage::Geometry)].present) {
        check("geometry.outputVertices", use.geometryOutputVertices);
        check("geometry.invocations", use.geometryInvocations);
    }
    return out;
}

GpuInfo clampToGlMinimums(GpuInfo i) {
    auto clamp = [](auto& value, std::string_view key) {
        const LimitRow* row = findLimit(key);
        if (row && value > row->glMinimum) value = static_cast<std::remove_reference_t<decltype(value)>>(row->glMinimum);
    };
    clamp(i.maxTextureSize, "textureSize");
    clamp(i.max3dTextureSize, "texture3dSize");
    clamp(i.maxArrayLayers, "arrayLayers");
    clamp(i.maxCubeMapSize, "cubeMapSize");
    clamp(i.maxColorAttachments, "colorAttachments");
    clamp(i.maxDrawBuffers, "colorAttachments");
    clamp(i.maxUniformBlockSize, "uniformBlockSize");
    clamp(i.maxShaderStorageBlockSize, "storageBlockSize");
    // Buffer textures: GL's minimum of 65,536 texels (1 MiB of RGBA32F) is reported by no GL 4.5 driver
    // (NVIDIA, AMD, Intel and llvmpipe: 2^27) and is below hisr's VPL tree at its defaults (349,184
    // texels): clamped to the vendors' lowest value instead, so the check still refuses past it.
    if (const LimitRow* row = findLimit("textureBufferSize"))
        i.maxTextureBufferSize = static_cast<int>(std::min<long long>(i.maxTextureBufferSize, row->portable()));
    clamp(i.maxComputeInvocations, "compute.invocations");
    clamp(i.maxComputeWorkGroupSize[0], "compute.localSizeX");
    clamp(i.maxComputeWorkGroupSize[1], "compute.localSizeY");
    clamp(i.maxComputeWorkGroupSize[2], "compute.localSizeZ");
    for (int& c : i.maxComputeWorkGroupCount) clamp(c, "compute.workGroupCount");
    clamp(i.maxComputeSharedMemorySize, "compute.sharedMemory");
    clamp(i.maxGeometryOutputVertices, "geometry.outputVertices");
    clamp(i.maxGeometryInvocations, "geometry.invocations");
    clamp(i.maxImageUnits, "imageUnits");
    clamp(i.maxCombinedTextureUnits, "textureUnits");
    clamp(i.maxCombinedImageUniforms, "combinedImageUniforms");
    clamp(i.maxCombinedStorageBlocks, "combinedStorageBlocks");
    for (int s = 0; s < kShaderStageCount; ++s) {
        const std::string stage(stageName(static_cast<ShaderStage>(s)));
        clamp(i.maxImageUniforms[s], stage + ".imageUniforms");
        clamp(i.maxTextureImageUnits[s], stage + ".samplers");
        clamp(i.maxStorageBlocks[s], stage + ".storageBlocks");
        clamp(i.maxUniformBlocks[s], stage + ".uniformBlocks");
    }
    // Multisample textures: GL's minimum of 1 sample is met by no GL 4.5 driver (all report at least
    // GL_MAX_SAMPLES' minimum of 4); a clamp to 1 would refuse radiosity's msaa=4 default (van de Hoef
    // 2013 sec. 5.3.1) everywhere. Clamped to 4 instead, so msaa 8 and 16 are refused as on a 4-sample GL.
    constexpr int kPortableTextureSamples = 4;  // GL 4.5 Table 23.69's minimum of GL_MAX_SAMPLES
    i.maxColorTextureSamples = std::min(i.maxColorTextureSamples, kPortableTextureSamples);
    i.maxDepthTextureSamples = std::min(i.maxDepthTextureSamples, kPortableTextureSamples);
    i.portableLimits = true;
    return i;
}

Expected<std::vector<AllowEntry>> parseAllowList(const std::string& text, const std::string& file) {
    std::vector<AllowEntry> out;
    std::istringstream in(text);
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
        ++n;
        const size_t first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream words(line);
        AllowEntry e;
        e.line = n;
        words >> e.program >> e.key >> e.finding;
        if (e.key.empty() || e.finding.size() < 2 || e.finding[0] != '#')
            return makeError("{}:{}: expected 'PROGRAM KEY #FINDING [comment]', got '{}'", file, n, line);
        if (!findLimit(e.key) && e.key != "glslang")
            return makeError("{}:{}: unknown limit '{}' (docs/gpu.md lists the keys; 'glslang' for a glslangValidator error)",
                             file, n, e.key);
        out.push_back(std::move(e));
    }
    return out;
}

const AllowEntry* findAllowed(const std::vector<AllowEntry>& list, std::string_view program, std::string_view key) {
    for (const AllowEntry& e : list)
        if (e.program == program && e.key == key) return &e;
    return nullptr;
}

}  // namespace bounce::gl
