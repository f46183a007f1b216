#include "gpu/Context.h"

#include "gpu/PortableLimits.h"
#include "gpu/ShaderLimits.h"

#include <spdlog/spdlog.h>

#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

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

ContextConfig measuredContextConfig() {
    ContextConfig c;
    c.debugOutput = false;
    return c;
}

int shaderLoopIterationBudget() { return shaderLoopIterationBudget(currentProfile()); }

std::string resetStatusMessage(GLenum status) {
    switch (status) {
        case GL_NO_ERROR: return {};
        case GL_GUILTY_CONTEXT_RESET:
            return "the GPU was reset and this context lost (GL_GUILTY_CONTEXT_RESET: bounce's own work caused it, typically a draw "
                   "past the driver's watchdog); try smaller settings or a smaller --size";
        case GL_INNOCENT_CONTEXT_RESET:
            return "the GPU was reset and this context lost (GL_INNOCENT_CONTEXT_RESET: another process caused it); run again";
        default:
            return "the GPU was reset and this context lost (GL_UNKNOWN_CONTEXT_RESET); run again, with smaller settings if it recurs";
    }
}

void throwIfContextReset() {
    const Context* c = Context::current();
    if (!c || !c->info().resetNotification) return;
    const std::string m = resetStatusMessage(glGetGraphicsResetStatus());
    if (!m.empty()) throw std::runtime_error(m);
}

bool portableLimitsMode() {
    const char* v = std::getenv("BOUNCE_PORTABLE_LIMITS");
    return v && std::string_view(v) == "1";
}

DeviceProfile currentProfile() {
    const Context* c = Context::current();
    return c ? c->info().profile : DeviceProfile::Llvmpipe;
}

Expected<void> Context::initialise(const ContextConfig& config, std::string platform, int deviceIndex,
                                   std::string deviceName) {
    t_current = this;
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    GpuInfo& i = m_info;
    i.debugContext = config.debugOutput && (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
    if (config.debugOutput && epoxy_has_gl_extension("GL_KHR_debug")) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, nullptr);
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    }
    // Point-light distance maps are R32F cube maps filtered LINEAR (render/LightSet.cpp): without
    // seamless filtering a lookup near a face edge clamps to that face, and drivers differ in what
    // they do by default (issue 29 #14). GL 4.5 core always supports it; it is global state.
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    i.platform = std::move(platform);
    i.deviceIndex = deviceIndex;
    i.deviceName = std::move(deviceName);
    i.vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    i.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    i.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    i.glslVersion = reinterpret_cast<const char*>(glGetString(GL_SHADING_LANGUAGE_VERSION));
    const char* profileOverride = std::getenv("BOUNCE_PROFILE");
    BOUNCE_TRY(i.profile, resolveProfile(i.renderer, profileOverride ? profileOverride : ""));
    i.profileOverridden = profileOverride && *profileOverride;
    i.maxTextureSize = getInt(GL_MAX_TEXTURE_SIZE);
    i.max3dTextureSize = getInt(GL_MAX_3D_TEXTURE_SIZE);
    i.maxArrayLayers = getInt(GL_MAX_ARRAY_TEXTURE_LAYERS);
    i.maxCubeMapSize = getInt(GL_MAX_CUBE_MAP_TEXTURE_SIZE);
    i.maxColorAttachments = getInt(GL_MAX_COLOR_ATTACHMENTS);
    i.maxDrawBuffers = getInt(GL_MAX_DRAW_BUFFERS);
    i.maxUniformBlockSize = getInt(GL_MAX_UNIFORM_BLOCK_SIZE);
    GLint64 storageBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &storageBlock);
    i.maxShaderStorageBlockSize = storageBlock;
    i.maxTextureBufferSize = getInt(GL_MAX_TEXTURE_BUFFER_SIZE);
    i.maxComputeInvocations = getInt(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    for (GLuint k = 0; k < 3; ++k) {
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, k, &i.maxComputeWorkGroupSize[k]);
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, k, &i.maxComputeWorkGroupCount[k]);
    }
    i.maxComputeSharedMemorySize = getInt(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
    i.maxGeometryOutputVertices = getInt(GL_MAX_GEOMETRY_OUTPUT_VERTICES);
    i.maxGeometryInvocations = getInt(GL_MAX_GEOMETRY_SHADER_INVOCATIONS);
    i.maxTransformFeedbackBuffers = getInt(GL_MAX_TRANSFORM_FEEDBACK_BUFFERS);
    i.maxImageUnits = getInt(GL_MAX_IMAGE_UNITS);
    i.maxCombinedTextureUnits = getInt(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS);
    i.maxCombinedImageUniforms = getInt(GL_MAX_COMBINED_IMAGE_UNIFORMS);
    i.maxCombinedStorageBlocks = getInt(GL_MAX_COMBINED_SHADER_STORAGE_BLOCKS);
    const GLenum images[] = {GL_MAX_VERTEX_IMAGE_UNIFORMS, GL_MAX_GEOMETRY_IMAGE_UNIFORMS, GL_MAX_FRAGMENT_IMAGE_UNIFORMS,
                             GL_MAX_COMPUTE_IMAGE_UNIFORMS};
    const GLenum textures[] = {GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, GL_MAX_GEOMETRY_TEXTURE_IMAGE_UNITS,
                               GL_MAX_TEXTURE_IMAGE_UNITS, GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS};
    const GLenum storage[] = {GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS,
                              GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS};
    const GLenum uniform[] = {GL_MAX_VERTEX_UNIFORM_BLOCKS, GL_MAX_GEOMETRY_UNIFORM_BLOCKS, GL_MAX_FRAGMENT_UNIFORM_BLOCKS,
                              GL_MAX_COMPUTE_UNIFORM_BLOCKS};
    for (int s = 0; s < 4; ++s) {
        i.maxImageUniforms[s] = getInt(images[s]);
        i.maxTextureImageUnits[s] = getInt(textures[s]);
        i.maxStorageBlocks[s] = getInt(storage[s]);
        i.maxUniformBlocks[s] = getInt(uniform[s]);
    }
    i.maxColorTextureSamples = getInt(GL_MAX_COLOR_TEXTURE_SAMPLES);
    i.maxDepthTextureSamples = getInt(GL_MAX_DEPTH_TEXTURE_SAMPLES);
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &i.timerQueryBits);
    i.resetNotification = getInt(GL_RESET_NOTIFICATION_STRATEGY) == GL_LOSE_CONTEXT_ON_RESET;
    for (const char* ext : {"GL_NV_shader_atomic_float", "GL_ARB_shader_draw_parameters", "GL_ARB_indirect_parameters",
                            "GL_ARB_bindless_texture", "GL_NV_conservative_raster", "GL_ARB_shader_atomic_counter_ops",
                            "GL_ARB_gpu_shader_int64"})
        i.extensions.emplace_back(ext, epoxy_has_gl_extension(ext));
    if (portableLimitsMode()) {
        m_info = clampToGlMinimums(std::move(m_info));
        spdlog::info("BOUNCE_PORTABLE_LIMITS=1: limits clamped to the GL 4.5 minimums, programs audited (docs/gpu.md)");
    }
    m_emptyVao = VertexArray::create("empty-vao");
    return {};
}

std::string formatInfo(const GpuInfo& i) {
    const std::string device =
        i.deviceIndex >= 0 ? fmt::format("EGL device {} ({})", i.deviceIndex, i.deviceName) : std::string("none (") + i.platform + ")";
    std::string s = fmt::format(
        "platform  {}\ndevice    {}\nvendor    {}\nrenderer  {}\nversion   {}\nglsl      {}\n"
        "profile   {} ({})\ncontext   {}{}\n",
        i.platform, device, i.vendor, i.renderer, i.version, i.glslVersion, profileName(i.profile),
        i.profileOverridden ? "BOUNCE_PROFILE" : "from the renderer", i.debugContext ? "debug (synchronous KHR_debug)" : "no debug",
        i.portableLimits ? ", limits clamped to the GL 4.5 minimums (BOUNCE_PORTABLE_LIMITS=1)" : "");
    s += fmt::format(
        "limits\n  max texture size            {}\n  max 3D texture size         {}\n  max array layers            {}\n"
        "  max cube map size           {}\n  max colour attachments      {}\n  max uniform block (bytes)   {}\n"
        "  max storage block (bytes)   {}\n  max texture buffer (texels) {}\n  compute invocations         {}\n"
        "  compute work group size     {} x {} x {}\n  compute work group count    {} x {} x {}\n"
        "  compute shared memory       {}\n  geometry output vertices    {}\n  geometry invocations        {}\n"
        "  transform feedback buffers  {}\n  image units                 {}\n  texture units (combined)    {}\n"
        "  msaa samples colour/depth   {} / {}\n  timer query bits            {}\n",
        i.maxTextureSize, i.max3dTextureSize, i.maxArrayLayers, i.maxCubeMapSize, i.maxColorAttachments,
        i.maxUniformBlockSize, i.maxShaderStorageBlockSize, i.maxTextureBufferSize, i.maxComputeInvocations,
        i.maxComputeWorkGroupSize[0], i.maxComputeWorkGroupSize[1], i.maxComputeWorkGroupSize[2],
        i.maxComputeWorkGroupCount[0], i.maxComputeWorkGroupCount[1], i.maxComputeWorkGroupCount[2],
        i.maxComputeSharedMemorySize, i.maxGeometryOutputVertices, i.maxGeometryInvocations,
        i.maxTransformFeedbackBuffers, i.maxImageUnits, i.maxCombinedTextureUnits, i.maxColorTextureSamples,
        i.maxDepthTextureSamples, i.timerQueryBits);
    s += "  per stage (vertex/geometry/fragment/compute)\n";
    s += fmt::format("    image uniforms            {} / {} / {} / {}\n", i.maxImageUniforms[0], i.maxImageUniforms[1],
                     i.maxImageUniforms[2], i.maxImageUniforms[3]);
    s += fmt::format("    samplers                  {} / {} / {} / {}\n", i.maxTextureImageUnits[0],
                     i.maxTextureImageUnits[1], i.maxTextureImageUnits[2], i.maxTextureImageUnits[3]);
    s += fmt::format("    storage blocks            {} / {} / {} / {}\n", i.maxStorageBlocks[0], i.maxStorageBlocks[1],
                     i.maxStorageBlocks[2], i.maxStorageBlocks[3]);
    s += fmt::format("    uniform blocks            {} / {} / {} / {}\n", i.maxUniformBlocks[0], i.maxUniformBlocks[1],
                     i.maxUniformBlocks[2], i.maxUniformBlocks[3]);
    s += fmt::format("  reset notification          {}\n", i.resetNotification ? "lose context on reset" : "none");
    s += "extensions\n";
    for (const auto& [name, present] : i.extensions) s += fmt::format("  {:34} {}\n", name, present ? "yes" : "no");
    return s;
}

}  // namespace bounce::gl
