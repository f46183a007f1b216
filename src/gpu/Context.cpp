#include "gpu/Context.h"

#include <spdlog/spdlog.h>

#include <atomic>

namespace bounce::gl {

namespace {
std::atomic<int> g_debugErrors{0};
thread_local Context* t_current = nullptr;

const char* sourceName(GLenum source) {
    switch (source) {
        case GL_DEBUG_SOURCE_API: return "api";
        case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader-compiler";
        case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window-system";
        case GL_DEBUG_SOURCE_THIRD_PARTY: return "third-party";
        case GL_DEBUG_SOURCE_APPLICATION: return "application";
        default: return "other";
    }
}

void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                              const void*) {
    // Shader compile messages are reported with file names by ShaderLibrary; do not double-count.
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
    if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
        ++g_debugErrors;
        spdlog::error("GL {} error {}: {}", sourceName(source), id, message);
    } else if (severity == GL_DEBUG_SEVERITY_MEDIUM) {
        spdlog::warn("GL {} {}: {}", sourceName(source), id, message);
    } else {
        spdlog::debug("GL {} {}: {}", sourceName(source), id, message);
    }
}

int getInt(GLenum name) {
    GLint v = 0;
    glGetIntegerv(name, &v);
    return v;
}
}  // namespace

Context::~Context() {
    if (t_current == this) t_current = nullptr;
}

int Context::debugErrorCount() { return g_debugErrors.load(); }
void Context::resetDebugErrorCount() { g_debugErrors = 0; }
Context* Context::current() { return t_current; }

void Context::initialise(const ContextConfig& config, std::string platform) {
    t_current = this;
    if (config.debugOutput && epoxy_has_gl_extension("GL_KHR_debug")) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, nullptr);
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    }
    GpuInfo& i = m_info;
    i.platform = std::move(platform);
    i.vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    i.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    i.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    i.glslVersion = reinterpret_cast<const char*>(glGetString(GL_SHADING_LANGUAGE_VERSION));
    i.maxTextureSize = getInt(GL_MAX_TEXTURE_SIZE);
    i.max3dTextureSize = getInt(GL_MAX_3D_TEXTURE_SIZE);
    i.maxArrayLayers = getInt(GL_MAX_ARRAY_TEXTURE_LAYERS);
    i.maxCubeMapSize = getInt(GL_MAX_CUBE_MAP_TEXTURE_SIZE);
    i.maxColorAttachments = getInt(GL_MAX_COLOR_ATTACHMENTS);
    i.maxDrawBuffers = getInt(GL_MAX_DRAW_BUFFERS);
    i.maxUniformBlockSize = getInt(GL_MAX_UNIFORM_BLOCK_SIZE);
    i.maxShaderStorageBlockSize = getInt(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
    i.maxComputeInvocations = getInt(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    for (GLuint k = 0; k < 3; ++k) {
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, k, &i.maxComputeWorkGroupSize[k]);
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, k, &i.maxComputeWorkGroupCount[k]);
    }
    i.maxGeometryOutputVertices = getInt(GL_MAX_GEOMETRY_OUTPUT_VERTICES);
    i.maxGeometryInvocations = getInt(GL_MAX_GEOMETRY_SHADER_INVOCATIONS);
    i.maxTransformFeedbackBuffers = getInt(GL_MAX_TRANSFORM_FEEDBACK_BUFFERS);
    i.maxImageUnits = getInt(GL_MAX_IMAGE_UNITS);
    i.maxCombinedTextureUnits = getInt(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS);
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &i.timerQueryBits);
    for (const char* ext : {"GL_NV_shader_atomic_float", "GL_ARB_shader_draw_parameters", "GL_ARB_indirect_parameters",
                            "GL_ARB_bindless_texture", "GL_NV_conservative_raster", "GL_ARB_shader_atomic_counter_ops",
                            "GL_ARB_gpu_shader_int64"})
        i.extensions.emplace_back(ext, epoxy_has_gl_extension(ext));
    m_emptyVao = VertexArray::create("empty-vao");
}

std::string formatInfo(const GpuInfo& i) {
    std::string s = fmt::format(
        "platform  {}\nvendor    {}\nrenderer  {}\nversion   {}\nglsl      {}\n"
        "limits\n  max texture size            {}\n  max 3D texture size         {}\n  max array layers            {}\n"
        "  max cube map size           {}\n  max colour attachments      {}\n  max uniform block (bytes)   {}\n"
        "  max storage block (bytes)   {}\n  compute invocations         {}\n  compute work group size     {} x {} x {}\n"
        "  compute work group count    {} x {} x {}\n  geometry output vertices    {}\n  geometry invocations        {}\n"
        "  transform feedback buffers  {}\n  image units                 {}\n  texture units (combined)    {}\n"
        "  timer query bits            {}\nextensions\n",
        i.platform, i.vendor, i.renderer, i.version, i.glslVersion, i.maxTextureSize, i.max3dTextureSize,
        i.maxArrayLayers, i.maxCubeMapSize, i.maxColorAttachments, i.maxUniformBlockSize, i.maxShaderStorageBlockSize,
        i.maxComputeInvocations, i.maxComputeWorkGroupSize[0], i.maxComputeWorkGroupSize[1], i.maxComputeWorkGroupSize[2],
        i.maxComputeWorkGroupCount[0], i.maxComputeWorkGroupCount[1], i.maxComputeWorkGroupCount[2],
        i.maxGeometryOutputVertices, i.maxGeometryInvocations, i.maxTransformFeedbackBuffers, i.maxImageUnits,
        i.maxCombinedTextureUnits, i.timerQueryBits);
    for (const auto& [name, present] : i.extensions) s += fmt::format("  {:34} {}\n", name, present ? "yes" : "no");
    return s;
}

}  // namespace bounce::gl
