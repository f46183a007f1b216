#include "techniques/screen_voxels/ScreenVoxels.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"

#include <algorithm>
#include <bit>
#include <limits>

namespace bounce::voxels {

namespace {
// Smallest depth range of the grid, metres: a scene flat in view depth (one plane facing the camera)
// would otherwise divide by zero. Engineering choice; any value far below a scene's size works.
constexpr float kMinDepthRange = 1e-3f;
}  // namespace

Expected<void> checkGrid(const GridSize& size, std::string_view columnsName, std::string_view bitsName) {
    if (size.columns.x <= 0 || size.columns.y <= 0)
        return makeError("{}={}x{}: the voxel grid needs at least one column", columnsName, size.columns.x, size.columns.y);
    GLint drawBuffers = 8;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    const int maxBits = SV_BITS_PER_LAYER * std::min<int>(drawBuffers, SV_MAX_LAYERS);
    if (size.bits <= 0 || size.bits % SV_BITS_PER_LAYER != 0 || size.bits > maxBits)
        return makeError("{}={}: depth bits must be a multiple of {} between {} and {} (one RGBA32UI target per 128 bits)",
                         bitsName, size.bits, SV_BITS_PER_LAYER, SV_BITS_PER_LAYER, maxBits);
    return {};
}

Expected<ScreenVoxels> ScreenVoxels::create() {
    ScreenVoxels v;
    BOUNCE_TRY(v.m_program, gl::Program::build({"screenVoxels.voxelize",
                                                {{GL_VERTEX_SHADER, "render/scene.vert"},
                                                 {GL_GEOMETRY_SHADER, "techniques/screen_voxels/voxelize.geom"},
                                                 {GL_FRAGMENT_SHADER, "techniques/screen_voxels/voxelize.frag"}}}));
    v.m_fbo = gl::Framebuffer::create("screenVoxels.fbo");
    v.m_ubo = gl::Buffer::create("screenVoxels.uniforms", sizeof(gpu::ScreenVoxelsGpu));
    return v;
}

void ScreenVoxels::build(render::SceneDrawer& drawer, const render::View& camera, const GridSize& size) {
    const int layers = size.bits / SV_BITS_PER_LAYER;
    BOUNCE_CHECK(layers >= 1 && layers <= SV_MAX_LAYERS && size.bits % SV_BITS_PER_LAYER == 0, "voxel bits checked");
    if (size.columns != m_allocated.columns || size.bits != m_allocated.bits) {
        gl::TextureDesc d;
        d.target = GL_TEXTURE_2D_ARRAY;
        d.width = size.columns.x;
        d.height = size.columns.y;
        d.depth = layers;
        d.format = GL_RGBA32UI;
        d.minFilter = d.magFilter = GL_NEAREST;
        m_bits = gl::Texture::create("screenVoxels.bits", d);
        m_fbo = gl::Framebuffer::create("screenVoxels.fbo");
        for (int k = 0; k < layers; ++k) m_fbo.attachLayer(GL_COLOR_ATTACHMENT0 + k, m_bits, k);
        m_fbo.setDrawBuffers(layers);
        BOUNCE_CHECK(m_fbo.complete(), "screen voxel framebuffer");
        m_allocated = size;
    }
    // Depth range: the scene's bounding box in view space, within the camera's planes.
    const render::SceneGpu& scene = drawer.scene();
    glm::vec3 lo, hi;
    scene.scene().bounds(scene.time(), lo, hi);
    float zMin = std::numeric_limits<float>::max(), zMax = 0.0f;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
        const float z = -(camera.viewFromWorld * glm::vec4(p, 1.0f)).z;
        zMin = std::min(zMin, z);
        zMax = std::max(zMax, z);
    }
    // The bounds' near and far faces sit at the centres of the first and last slices. Spanning exactly
    // [zMin, zMax] put a surface on a face (a wall perpendicular to the view at the scene's far end) at
    // slice `bits`, just outside the grid, so it was never voxelized and rays passed through it
    // (ScreenVoxelsGpuTest.MarchSeesTheVoxelizedOccludersOnly). A scene flat in view depth still gets
    // a range of kMinDepthRange.
    const float halfSlice = 0.5f * std::max(zMax - zMin, kMinDepthRange) / static_cast<float>(size.bits - 1);
    const float nearZ = std::max(camera.nearPlane, zMin - halfSlice);
    const float farZ = std::max(std::min(camera.farPlane, zMax + halfSlice), nearZ + kMinDepthRange);
    m_uniforms.clipFromWorld = camera.clipFromWorld();
    m_uniforms.viewFromWorld = camera.viewFromWorld;
    m_uniforms.grid = glm::vec4(size.columns.x, size.columns.y, size.bits, layers);
    m_uniforms.depth = glm::vec4(nearZ, farZ, static_cast<float>(size.bits) / (farZ - nearZ),
                                 (farZ - nearZ) / static_cast<float>(size.bits));
    m_ubo.upload(0, sizeof(m_uniforms), &m_uniforms);
    m_ubo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_VOXELS);

    const GLuint zero[4] = {0, 0, 0, 0};
    for (int k = 0; k < layers; ++k) glClearNamedFramebufferuiv(m_fbo.id(), GL_COLOR, k, zero);
    m_fbo.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glEnable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_OR);
    m_program.set("u_footprint", size.footprint ? 1 : 0);
    m_program.use();
    render::View v = camera;
    v.viewport = size.columns;
    drawer.draw(v);
    glDisable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_COPY);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

void ScreenVoxels::bind(unsigned uboBinding, unsigned textureUnit) const {
    m_ubo.bindBase(GL_UNIFORM_BUFFER, uboBinding);
    m_bits.bind(textureUnit);
}

uint64_t ScreenVoxels::countOccupied() const {
    const int w = m_allocated.columns.x, h = m_allocated.columns.y, layers = m_allocated.bits / SV_BITS_PER_LAYER;
    std::vector<glm::uvec4> texels(static_cast<size_t>(w) * h * layers);
    glGetTextureImage(m_bits.id(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                      static_cast<GLsizei>(texels.size() * sizeof(glm::uvec4)), texels.data());
    uint64_t n = 0;
    for (const glm::uvec4& t : texels)
        for (int c = 0; c < 4; ++c) n += static_cast<uint64_t>(std::popcount(t[c]));
    return n;
}

}  // namespace bounce::voxels
