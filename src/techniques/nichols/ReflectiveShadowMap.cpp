#include "techniques/nichols/ReflectiveShadowMap.h"

#include "core/Check.h"
#include "gpu/Bindings.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace bounce::nichols {

namespace {

// Spots up to this half-angle get one perspective map (a 120-degree frustum); wider cones would
// waste most texels near the frustum edge, so they use the cube like point lights.
constexpr float kMaxPerspectiveCutoff = 1.0471976f;  // radians (60 degrees)
// Near plane as a fraction of the scene diagonal (as render/LightSet.cpp: no clipping, fine depth).
constexpr float kNearFraction = 1e-3f;
// Projection kinds of rsm.frag (u_projection).
constexpr int kPerspective = 0, kOrthographic = 1;
constexpr float kFourPi = 12.566371f;  // sr, the full sphere (a cube face spans a sixth of it)

glm::vec3 anyPerpendicular(glm::vec3 d) {
    return std::abs(d.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
}

}  // namespace

gl::TextureDesc texelArrayDesc(int size, int layers) {
    gl::TextureDesc d;
    d.target = GL_TEXTURE_2D_ARRAY;
    d.width = d.height = size;
    d.depth = layers;
    d.format = GL_RGBA32F;
    d.minFilter = d.magFilter = GL_NEAREST;
    return d;
}

Expected<ReflectiveShadowMap> ReflectiveShadowMap::create() {
    ReflectiveShadowMap r;
    BOUNCE_TRY(r.m_program, gl::Program::build({"nichols.rsm",
                                                {{GL_VERTEX_SHADER, "render/scene.vert"},
                                                 {GL_FRAGMENT_SHADER, "techniques/nichols/rsm.frag"}}}));
    r.m_fbo = gl::Framebuffer::create("nichols.rsm.fbo");
    return r;
}

int ReflectiveShadowMap::layersFor(const Light& light) {
    const bool single = light.type == LightType::Directional ||
                        (light.type == LightType::Spot && light.cutoffAngle <= kMaxPerspectiveCutoff);
    return single ? 1 : 6;
}

bool ReflectiveShadowMap::render(FrameContext& ctx, int size, bool equalSolidAngle) {
    const std::vector<Light>& lights = ctx.sceneGpu.lights();
    m_valid = false;
    if (lights.empty() || ctx.lights.count() == 0) return false;
    const Light& light = lights.front();
    const int layers = layersFor(light);
    const bool single = layers == 1;
    if (size != m_size || layers != m_layers) {
        m_size = size;
        m_layers = layers;
        gl::TextureDesc d = texelArrayDesc(size, layers);
        m_position = gl::Texture::create("nichols.rsm.position", d);
        m_normal = gl::Texture::create("nichols.rsm.normal", d);
        m_flux = gl::Texture::create("nichols.rsm.flux", d);
        d.format = GL_DEPTH_COMPONENT32F;
        m_depth = gl::Texture::create("nichols.rsm.depth", d);
    }

    glm::vec3 lo, hi;
    ctx.scene.bounds(ctx.time, lo, hi);
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    const float nearPlane = kNearFraction * 2.0f * radius;
    const float farPlane = glm::length(light.position - centre) + radius;

    ctx.lights.bind(0);
    m_program.use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    for (int layer = 0; layer < layers; ++layer) {
        render::View view;
        if (light.type == LightType::Directional) {
            const glm::vec3 d = glm::normalize(light.direction);
            const glm::vec3 eye = centre - d * (radius * 2.0f);
            view.viewFromWorld = glm::lookAt(eye, centre, anyPerpendicular(d));
            view.clipFromView = glm::ortho(-radius, radius, -radius, radius, radius, radius * 3.0f);
            view.eye = eye;
            view.nearPlane = radius;
            view.farPlane = 3.0f * radius;
            view.viewport = {size, size};
            m_program.set("u_projection", kOrthographic);
            m_program.set("u_equalSolidAngle", 0.0f);  // parallel light: texel areas are equal already
            m_program.set("u_texelArea", (2.0f * radius / size) * (2.0f * radius / size));
            m_program.set("u_axis", d);
        } else if (single) {
            const glm::vec3 d = glm::normalize(light.direction);
            view.viewFromWorld = glm::lookAt(light.position, light.position + d, anyPerpendicular(d));
            view.clipFromView = glm::perspective(2.0f * light.cutoffAngle, 1.0f, nearPlane, farPlane);
            view.eye = light.position;
            view.nearPlane = nearPlane;
            view.farPlane = farPlane;
            view.viewport = {size, size};
            const float texel = 2.0f * std::tan(light.cutoffAngle) / size;
            m_program.set("u_projection", kPerspective);
            m_program.set("u_texelArea", texel * texel);
            m_program.set("u_axis", d);
            // Solid angle of a square frustum of half-angle a: 4 asin(sin^2 a) (Eq. 4.4's omega_frustum).
            const float s = std::sin(light.cutoffAngle);
            m_program.set("u_equalSolidAngle", equalSolidAngle ? 4.0f * std::asin(s * s) / (size * size) : 0.0f);
        } else {
            view = render::cubeFaceView(light.position, layer, nearPlane, farPlane, size);
            const float texel = 2.0f / size;  // a 90-degree face spans [-1, 1] at unit distance
            m_program.set("u_projection", kPerspective);
            m_program.set("u_texelArea", texel * texel);
            m_program.set("u_axis", -glm::vec3(glm::transpose(view.viewFromWorld)[2]));
            m_program.set("u_equalSolidAngle", equalSolidAngle ? kFourPi / 6.0f / (size * size) : 0.0f);
        }
        m_fbo.attachLayer(GL_COLOR_ATTACHMENT0, m_position, layer);
        m_fbo.attachLayer(GL_COLOR_ATTACHMENT1, m_normal, layer);
        m_fbo.attachLayer(GL_COLOR_ATTACHMENT2, m_flux, layer);
        m_fbo.attachLayer(GL_DEPTH_ATTACHMENT, m_depth, layer);
        m_fbo.setDrawBuffers(3);
        BOUNCE_CHECK(m_fbo.complete(), "nichols.rsm framebuffer (layer {})", layer);
        m_fbo.bind();
        for (int i = 0; i < 3; ++i) glClearNamedFramebufferfv(m_fbo.id(), GL_COLOR, i, zero);
        glClearNamedFramebufferfv(m_fbo.id(), GL_DEPTH, 0, &one);
        m_program.use();
        ctx.drawer.draw(view);
    }
    m_valid = true;
    return true;
}

void ReflectiveShadowMap::debugViews(std::vector<DebugView>& out) const {
    if (!m_position) return;
    out.push_back({"rsm.position", &m_position, DebugEncoding::Position});
    out.push_back({"rsm.normal", &m_normal, DebugEncoding::Normal});
    out.push_back({"rsm.flux", &m_flux, DebugEncoding::Radiance, static_cast<float>(m_size) * static_cast<float>(m_size)});
}

glm::vec3 ReflectiveShadowMap::totalFlux() const {
    if (!m_valid) return glm::vec3(0.0f);
    std::vector<glm::vec4> texels(static_cast<size_t>(m_size) * m_size * m_layers);
    glGetTextureImage(m_flux.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)),
                      texels.data());
    glm::dvec3 sum(0.0);
    for (const glm::vec4& t : texels) sum += glm::dvec3(glm::vec3(t));
    return glm::vec3(sum);
}

}  // namespace bounce::nichols
