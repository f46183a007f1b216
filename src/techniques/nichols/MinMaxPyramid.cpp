#include "techniques/nichols/MinMaxPyramid.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/PortableLimits.h"

#include <algorithm>

namespace bounce::nichols {

namespace {
constexpr int kLocalSize = 8;  // local_size_x/y of the pyramid compute shaders
static_assert(MinMaxPyramid::kTextureUnits == BINDING_TEX_PYRAMID4 + 1, "pyramid texture units");
static_assert(MinMaxPyramid::kImageUniforms == BINDING_IMG6 + 1, "pyramid_flag.comp's highest image unit");

void dispatch2D(glm::ivec2 size, int layers) {
    glDispatchCompute(static_cast<GLuint>((size.x + kLocalSize - 1) / kLocalSize),
                      static_cast<GLuint>((size.y + kLocalSize - 1) / kLocalSize), static_cast<GLuint>(layers));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}
}  // namespace

void visitEyeSettings(SettingsVisitor& v, PyramidThresholds& t, int& indirectSize) {
    v.field("linearDepth", t.linearDepth,
            "§3.2.2.1: eye-space depth test on a linear-depth min-max mipmap, (max - min) / min > depthThreshold, instead "
            "of the depth-derivative max-mipmap (off: the derivative, chs. 3-5's choice)");
    v.field("indirectSize", indirectSize, kIndirectSizeHelp, 0, 8192);
}

Expected<void> checkIndirectSize(int indirectSize, glm::ivec2 output) {
    const int larger = std::max(output.x, output.y);
    if (indirectSize != 0 && (indirectSize < 0 || (indirectSize & (indirectSize - 1)) != 0 || indirectSize > larger))
        return makeError("indirectSize={} must be 0 (output size) or a power of two no larger than the output's larger side {}",
                         indirectSize, larger);
    const int scale = indirectScale(indirectSize, output);
    return checkAtlasSize((output + glm::ivec2(scale - 1)) / scale,
                          fmt::format("output {}x{} with indirectSize={}", output.x, output.y, indirectSize),
                          gl::Context::current()->info());
}

Expected<void> checkAtlasSize(glm::ivec2 base, const std::string& settings, const gl::GpuInfo& info) {
    const int width = base.x + std::max(base.x / 2, 1);  // MultiresBuffer: base level + level 1's column
    if (width > info.maxTextureSize || base.y > info.maxTextureSize)
        return makeError("{}: the multiresolution illumination atlas is {}x{} texels (1.5x the indirect base {}x{}), past this GL's "
                         "GL_MAX_TEXTURE_SIZE of {}; lower the output size or set indirectSize",
                         settings, width, base.y, base.x, base.y, info.maxTextureSize);
    return {};
}

int indirectScale(int indirectSize, glm::ivec2 output) {
    int scale = 1;
    if (indirectSize <= 0) return scale;
    const int larger = std::max(output.x, output.y);
    while ((larger + scale - 1) / scale > indirectSize) scale *= 2;
    return scale;
}

Expected<void> MinMaxPyramid::checkLimits(const gl::GpuInfo& info) {
    const int compute = static_cast<int>(gl::ShaderStage::Compute);
    if (info.maxImageUniforms[compute] < kImageUniforms || info.maxImageUnits < kImageUniforms)
        return makeError("the min-max pyramid's compute passes need {} image uniforms on units 0..{}; this GL has {} compute image "
                         "uniforms and {} image units (GL_MAX_COMPUTE_IMAGE_UNIFORMS, GL_MAX_IMAGE_UNITS)",
                         kImageUniforms, kImageUniforms - 1, info.maxImageUniforms[compute], info.maxImageUnits);
    if (info.maxCombinedTextureUnits < kTextureUnits)
        return makeError("the min-max pyramid reads level k-1 on texture units up to {}; this GL has {} "
                         "(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS)",
                         kTextureUnits - 1, info.maxCombinedTextureUnits);
    return {};
}

Expected<MinMaxPyramid> MinMaxPyramid::create() {
    BOUNCE_TRY_VOID(checkLimits(gl::Context::current()->info()));
    MinMaxPyramid p;
    BOUNCE_TRY(p.m_baseEye, gl::Program::build({"nichols.pyramidBaseEye",
                                                {{GL_COMPUTE_SHADER, "techniques/nichols/pyramid_base_eye.comp"}}}));
    BOUNCE_TRY(p.m_baseLight, gl::Program::build({"nichols.pyramidBaseLight",
                                                  {{GL_COMPUTE_SHADER, "techniques/nichols/pyramid_base_light.comp"}}}));
    BOUNCE_TRY(p.m_reduce, gl::Program::build({"nichols.pyramidReduce",
                                               {{GL_COMPUTE_SHADER, "techniques/nichols/pyramid_reduce.comp"}}}));
    BOUNCE_TRY(p.m_flag, gl::Program::build({"nichols.pyramidFlag",
                                             {{GL_COMPUTE_SHADER, "techniques/nichols/pyramid_flag.comp"}}}));
    return p;
}

void MinMaxPyramid::allocate(glm::ivec2 size, int layers, int coarsestSize, bool flux) {
    if (size == m_baseSize && layers == m_layers && flux == m_hasFlux && coarsestSize == m_coarsest) return;
    m_coarsest = coarsestSize;
    m_sizes.clear();
    glm::ivec2 s = size;
    m_sizes.push_back(s);
    while (std::max(s.x, s.y) > coarsestSize && (s.x > 1 || s.y > 1)) {
        s = glm::max(s / 2, glm::ivec2(1));
        m_sizes.push_back(s);
    }
    m_levels = static_cast<int>(m_sizes.size());
    m_baseSize = size;
    m_layers = layers;
    m_hasFlux = flux;
    gl::TextureDesc d;
    d.target = GL_TEXTURE_2D_ARRAY;
    d.width = size.x;
    d.height = size.y;
    d.depth = layers;
    d.levels = m_levels;
    d.format = GL_RGBA32F;
    d.minFilter = GL_NEAREST_MIPMAP_NEAREST;
    d.magFilter = GL_NEAREST;
    m_geometry = gl::Texture::create("nichols.pyramid.geometry", d);
    m_normal = gl::Texture::create("nichols.pyramid.normal", d);
    m_normalMin = gl::Texture::create("nichols.pyramid.normalMin", d);
    m_normalMax = gl::Texture::create("nichols.pyramid.normalMax", d);
    if (flux) m_flux = gl::Texture::create("nichols.pyramid.flux", d);
    // RGBA32F like the other chains so that pyramid_reduce.comp's fifth image unit has one format.
    if (!flux) m_curvature = gl::Texture::create("nichols.pyramid.curvature", d);
    d.format = GL_R32F;
    m_refine = gl::Texture::create("nichols.pyramid.refine", d);
    BOUNCE_CHECK(glm::ivec2(m_sizes.back()) == glm::max(size >> (m_levels - 1), glm::ivec2(1)),
                 "pyramid level sizes follow GL mip sizes");
}

std::vector<glm::ivec2> MinMaxPyramid::levelSizes(int count) const {
    BOUNCE_CHECK(m_levels <= count, "pyramid of {} levels, shader array of {}", m_levels, count);
    std::vector<glm::ivec2> sizes(static_cast<size_t>(count), glm::ivec2(0));
    for (int k = 0; k < m_levels; ++k) sizes[static_cast<size_t>(k)] = m_sizes[static_cast<size_t>(k)];
    return sizes;
}

void MinMaxPyramid::buildEye(const render::GBuffer& gbuffer, int coarsestSize, const PyramidThresholds& t,
                             std::optional<float> curvatureThreshold, int scale) {
    BOUNCE_CHECK(scale >= 1 && (scale & (scale - 1)) == 0, "eye pyramid scale {} is a power of two", scale);
    const glm::ivec2 full = gbuffer.size();
    allocate((full + glm::ivec2(scale - 1)) / scale, 1, coarsestSize, false);
    m_scale = scale;
    gbuffer.bind();
    m_geometry.bindImage(BINDING_IMG0, GL_WRITE_ONLY, 0, true);
    m_normal.bindImage(BINDING_IMG1, GL_WRITE_ONLY, 0, true);
    m_normalMin.bindImage(BINDING_IMG2, GL_WRITE_ONLY, 0, true);
    m_normalMax.bindImage(BINDING_IMG3, GL_WRITE_ONLY, 0, true);
    m_curvature.bindImage(BINDING_IMG4, GL_WRITE_ONLY, 0, true);
    m_baseEye.set("u_size", m_sizes[0]);
    m_baseEye.set("u_curvature", curvatureThreshold ? 1 : 0);
    m_baseEye.set("u_scale", scale);
    m_baseEye.set("u_gbufferSize", full);
    m_baseEye.set("u_linearDepth", t.linearDepth ? 1 : 0);
    m_baseEye.use();
    dispatch2D(m_sizes[0], 1);
    reduceAndFlag(t, false, curvatureThreshold, t.linearDepth);
}

void MinMaxPyramid::buildLight(const ReflectiveShadowMap& rsm, int coarsestSize, const PyramidThresholds& t) {
    allocate({rsm.size(), rsm.size()}, rsm.layers(), coarsestSize, true);
    rsm.position().bind(BINDING_TEX_TECH0);
    rsm.normal().bind(BINDING_TEX_TECH1);
    rsm.flux().bind(BINDING_TEX_TECH2);
    m_geometry.bindImage(BINDING_IMG0, GL_WRITE_ONLY, 0, true);
    m_normal.bindImage(BINDING_IMG1, GL_WRITE_ONLY, 0, true);
    m_normalMin.bindImage(BINDING_IMG2, GL_WRITE_ONLY, 0, true);
    m_normalMax.bindImage(BINDING_IMG3, GL_WRITE_ONLY, 0, true);
    m_flux.bindImage(BINDING_IMG4, GL_WRITE_ONLY, 0, true);
    m_baseLight.set("u_size", m_sizes[0]);
    m_baseLight.use();
    dispatch2D(m_sizes[0], m_layers);
    m_scale = 1;
    reduceAndFlag(t, true, std::nullopt, false);  // the light pyramid keeps its distance derivative
}

void MinMaxPyramid::reduceAndFlag(const PyramidThresholds& t, bool flux, std::optional<float> curvatureThreshold,
                                  bool linearDepth) {
    const bool curvature = curvatureThreshold.has_value();
    // The fifth chain: summed flux (light), max curvature (eye, optional), else unused.
    const gl::Texture* fifth = flux ? &m_flux : curvature ? &m_curvature : &m_geometry;
    const gl::Texture* chains[5] = {&m_geometry, &m_normal, &m_normalMin, &m_normalMax, fifth};
    // Level 0 has no refine flag of its own (the finest level is always valid under a refined parent).
    const float zero = 0.0f;
    glClearTexImage(m_refine.id(), 0, GL_RED, GL_FLOAT, &zero);
    for (int level = 1; level < m_levels; ++level) {
        const glm::ivec2 child = m_sizes[static_cast<size_t>(level - 1)], size = m_sizes[static_cast<size_t>(level)];
        // Level k-1 by texelFetch, level k as images: 5 image units (issue 29 finding #1).
        for (int i = 0; i < 5; ++i) {
            chains[i]->bind(BINDING_TEX_PYRAMID0 + i);
            chains[i]->bindImage(BINDING_IMG0 + i, GL_WRITE_ONLY, level, true);
        }
        m_reduce.set("u_childLevel", level - 1);
        m_reduce.set("u_childSize", child);
        m_reduce.set("u_size", size);
        m_reduce.set("u_hasFlux", flux ? 1 : 0);
        m_reduce.set("u_hasCurvature", curvature ? 1 : 0);
        m_reduce.set("u_linearDepth", linearDepth ? 1 : 0);
        m_reduce.use();
        dispatch2D(size, m_layers);

        for (int i = 0; i < 4; ++i) chains[i]->bindImage(BINDING_IMG0 + i, GL_READ_ONLY, level, true);
        m_refine.bindImage(BINDING_IMG4, GL_READ_ONLY, level - 1, true);
        m_refine.bindImage(BINDING_IMG5, GL_WRITE_ONLY, level, true);
        if (curvature) m_curvature.bindImage(BINDING_IMG6, GL_READ_ONLY, level, true);
        m_flag.set("u_size", size);
        m_flag.set("u_childSize", child);
        m_flag.set("u_childHasFlags", level >= 2 ? 1 : 0);
        m_flag.set("u_depthThreshold", t.depth);
        m_flag.set("u_normalThreshold", t.normal);
        m_flag.set("u_edgeNeighbours", t.edgeNeighbours ? 1 : 0);
        m_flag.set("u_curvature", curvature ? 1 : 0);
        m_flag.set("u_curvatureThreshold", curvatureThreshold.value_or(0.0f));
        m_flag.set("u_linearDepth", linearDepth ? 1 : 0);
        m_flag.use();
        dispatch2D(size, m_layers);
    }
}

}  // namespace bounce::nichols
