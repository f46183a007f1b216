#include "render/LightSet.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "scene/AreaTexture.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace bounce::render {

namespace {

// Wider spots would need a degenerate perspective frustum; they use a cube map instead.
constexpr float kMaxPerspectiveSpotAngle = glm::radians(80.0f);
// Near plane of light frusta as a fraction of the scene diagonal: small enough not to clip
// geometry next to the light, large enough to keep 32-bit float depth precise.
constexpr float kNearFraction = 1e-3f;

// glPolygonOffset of shadow maps (the values before issue 30): the depth slope's factor (not for
// directional maps since issue 30: theirs is the receiver-plane bias, see update()) and depth units.
constexpr float kSlopeBias = 1.5f, kConstantBias = 2.0f;

// LightGpu::edgeU.w: which shadow map a light has (matches common/lighting.glsl).
constexpr float k2D = 1.0f, kCube = 2.0f;

bool sameLight(const Light& a, const Light& b) {
    return a.position == b.position && a.direction == b.direction && a.edgeU == b.edgeU && a.edgeV == b.edgeV &&
           a.cutoffAngle == b.cutoffAngle && a.twoSided == b.twoSided;
}

glm::vec3 anyPerpendicular(glm::vec3 d) {
    return std::abs(d.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
}

}  // namespace

gpu::LightGpu toGpu(const Light& l) {
    gpu::LightGpu g{};
    int type = LIGHT_POINT;
    glm::vec3 emission = l.intensity;
    switch (l.type) {
        case LightType::Point: type = LIGHT_POINT; break;
        case LightType::Spot: type = LIGHT_SPOT; break;
        case LightType::Directional: type = LIGHT_DIRECTIONAL; emission = l.irradiance; break;
        case LightType::Area: type = LIGHT_AREA; emission = l.radiance; break;
    }
    g.position = glm::vec4(l.position, static_cast<float>(type));
    g.direction = glm::vec4(glm::normalize(l.direction), std::cos(l.cutoffAngle));
    g.emission = glm::vec4(emission, l.falloffExponent);
    g.edgeU = glm::vec4(l.edgeU, 0.0f);
    g.edgeV = glm::vec4(l.edgeV, 0.0f);
    g.shadowClipFromWorld = glm::mat4(1.0f);
    if (l.type == LightType::Area) {
        const float flags = (l.texture.textured() ? AREA_TEXTURED : 0) | (l.twoSided ? AREA_TWO_SIDED : 0);
        g.area = glm::vec4(l.radiance, flags);
    }
    return g;
}

Expected<LightSet> LightSet::create() {
    LightSet s;
    BOUNCE_TRY(s.m_depthProgram, gl::Program::build({"shadow.depth",
                                                     {{GL_VERTEX_SHADER, "render/scene.vert"},
                                                      {GL_FRAGMENT_SHADER, "render/shadow_depth.frag"}}}));
    BOUNCE_TRY(s.m_distanceProgram, gl::Program::build({"shadow.distance",
                                                        {{GL_VERTEX_SHADER, "render/scene.vert"},
                                                         {GL_FRAGMENT_SHADER, "render/shadow_distance.frag"}}}));
    s.m_dummy2D = gl::Texture::create2D("shadow.dummy2D", 1, 1, GL_DEPTH_COMPONENT32F);
    s.m_dummy2D.setCompareMode(true);
    gl::TextureDesc cube;
    cube.target = GL_TEXTURE_CUBE_MAP;
    cube.format = GL_R32F;
    s.m_dummyCube = gl::Texture::create("shadow.dummyCube", cube);
    const float one = 1.0f;
    glClearTexImage(s.m_dummy2D.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
    glClearTexImage(s.m_dummyCube.id(), 0, GL_RED, GL_FLOAT, &one);
    s.m_white = gl::Texture::create2D("light.areaTexture.white", 1, 1, GL_RGBA32F);
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearTexImage(s.m_white.id(), 0, GL_RGBA, GL_FLOAT, white);
    return s;
}

void LightSet::bind(size_t i) const {
    const Entry& e = m_entries[i];
    e.ubo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_LIGHT);
    (e.gpu.edgeU.w == kCube ? e.distance : m_dummyCube).bind(BINDING_TEX_SHADOW_CUBE);
    (e.gpu.edgeU.w == k2D ? e.depth : m_dummy2D).bind(BINDING_TEX_SHADOW);
    areaTexture(i).bind(BINDING_TEX_AREA_LIGHT);
}

const gl::Texture& LightSet::areaTexture(size_t i) const {
    const Entry& e = m_entries[i];
    return e.emission ? e.emission : m_white;
}

void LightSet::updateAreaTexture(Entry& e, const Scene& scene, const Light& light, float time) {
    if (light.type != LightType::Area || !light.texture.textured()) {
        e.emission = gl::Texture();
        e.emissionKey = -1;
        e.emissionMean = glm::vec3(1.0f);
        return;
    }
    const int64_t key = light.texture.kind == AreaTexture::Kind::Images
                            ? static_cast<int64_t>(areaTextureFrame(light.texture, time))
                            : -1 - static_cast<int64_t>(std::llround(static_cast<double>(time) * 1e6));
    if (e.emission && key == e.emissionKey) return;
    Image scratch;
    const Image* image = areaTextureAt(scene, light, time, scratch);
    BOUNCE_CHECK(image != nullptr && !image->empty(), "textured area light has an image");
    const int w = image->width(), h = image->height();
    if (!e.emission || e.emission.width() != w || e.emission.height() != h) {
        int levels = 1;
        while ((std::max(w, h) >> levels) > 0) ++levels;
        e.emission = gl::Texture::create2D("light.areaTexture", w, h, GL_RGBA32F, levels);
        e.emission.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    }
    // GL row 0 is t = 0, the image's last row (Scene.h: image row 0 is v = 1).
    std::vector<glm::vec4> texels(static_cast<size_t>(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            texels[static_cast<size_t>(y) * w + x] = glm::vec4(image->at(x, h - 1 - y), 1.0f);
    glTextureSubImage2D(e.emission.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, texels.data());
    e.emission.generateMipmaps();
    e.emissionKey = key;
    e.emissionMean = imageMean(*image);
    ++m_areaTextureUploads;
}

void LightSet::bindShadowMaps(size_t i, unsigned unit2D, unsigned unitCube) const {
    const Entry& e = m_entries[i];
    (e.gpu.edgeU.w == kCube ? e.distance : m_dummyCube).bind(unitCube);
    (e.gpu.edgeU.w == k2D ? e.depth : m_dummy2D).bind(unit2D);
}

void LightSet::update(SceneDrawer& drawer, const RenderSettings& settings, const View& camera) {
    const SceneGpu& scene = drawer.scene();
    const std::vector<Light>& lights = scene.lights();
    if (m_entries.size() != lights.size()) m_entries.resize(lights.size());
    glm::vec3 lo, hi;
    scene.scene().bounds(scene.time(), lo, hi);
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    const float diagonal = 2.0f * radius;

    GLint previousFbo = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previousFbo);
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& light = lights[i];
        Entry& e = m_entries[i];
        gpu::LightGpu g = toGpu(light);
        updateAreaTexture(e, scene.scene(), light, scene.time());
        if (light.type == LightType::Area)  // what untextured shading of this light sees: the mean radiance
            g.emission = glm::vec4(light.radiance * e.emissionMean, g.emission.w);
        const bool wideSpot = light.type == LightType::Spot && light.cutoffAngle > kMaxPerspectiveSpotAngle;
        const bool cube = light.type == LightType::Point || light.type == LightType::Area || wideSpot;
        const int size = light.type == LightType::Directional && settings.cascadeMapSize > 0 ? settings.cascadeMapSize
                                                                                             : settings.shadowMapSize;
        // Cube maps of one-sided area lights sit a hair in front of the emitter, so that a surface in
        // its plane (a ceiling around a recessed light) does not shadow the room. A two-sided light
        // lights both half-spaces, so its map sits at its centre: the emitter itself is not scene
        // geometry and never enters the map, so it cannot shadow itself.
        glm::vec3 origin = light.position;
        if (light.type == LightType::Area && !light.twoSided) origin += light.areaNormal() * (kNearFraction * diagonal);
        const float farPlane = glm::length(origin - centre) + radius;
        const float nearPlane = kNearFraction * diagonal;
        g.edgeU.w = cube ? kCube : k2D;
        g.edgeV.w = light.type == LightType::Directional ? settings.sunShadowBias : settings.shadowBias;
        ShadowCascades cascades;
        if (!cube) {
            glm::mat4 viewFromWorld, clipFromView;
            if (light.type == LightType::Directional) {
                // The whole-scene map: the scene's bounding sphere seen along the light; the cascades
                // in front of it are sub-squares of its [0,1]^2, at the same depth range.
                const glm::vec3 d = glm::normalize(light.direction);
                const glm::vec3 eye = centre - d * (radius * 2.0f);
                viewFromWorld = glm::lookAt(eye, centre, anyPerpendicular(d));
                clipFromView = glm::ortho(-radius, radius, -radius, radius, radius, radius * 3.0f);
                cascades = fitShadowCascades(clipFromView * viewFromWorld, radius, camera, lo, hi,
                                             settings.shadowCascades, size);
            } else {
                const glm::vec3 d = glm::normalize(light.direction);
                viewFromWorld = glm::lookAt(light.position, light.position + d, anyPerpendicular(d));
                clipFromView = glm::perspective(2.0f * light.cutoffAngle, 1.0f, nearPlane, farPlane);
                // One texel at distance r from the light spans 2 r tan(cutoff) / size metres.
                cascades.cascades[0] = glm::vec4(0.0f, 0.0f, 1.0f, 2.0f * std::tan(light.cutoffAngle) / size);
            }
            g.shadowClipFromWorld = clipFromView * viewFromWorld;
        }
        const int tiles = shadowAtlasTiles(cascades.count);
        for (int c = 0; c < SHADOW_MAX_CASCADES; ++c) g.shadowCascades[c] = cascades.cascades[c];
        g.shadowParams = glm::vec4(farPlane, static_cast<float>(size), static_cast<float>(settings.pcfRadius),
                                   static_cast<float>(cascades.count));

        const bool dynamicOccluders = scene.hasDynamicObjects();
        const bool refit = !cube && (cascades.count != e.cascades.count || cascades.cascades != e.cascades.cascades);
        const bool needsRender = !e.valid || e.size != size || e.tiles != tiles || !sameLight(e.rendered, light) ||
                                 dynamicOccluders || refit || (e.gpu.edgeU.w != g.edgeU.w);
        if (!e.ubo) e.ubo = gl::Buffer::create("light.uniforms", sizeof(gpu::LightGpu));
        if (needsRender) {
            if (e.size != size || e.tiles != tiles || e.gpu.edgeU.w != g.edgeU.w || !e.valid) {
                e.fbo = gl::Framebuffer::create("shadow.fbo");
                if (cube) {
                    gl::TextureDesc d;
                    d.target = GL_TEXTURE_CUBE_MAP;
                    d.width = d.height = size;
                    d.format = GL_R32F;
                    e.distance = gl::Texture::create("shadow.cubeDistance", d);
                    d.format = GL_DEPTH_COMPONENT32F;
                    d.minFilter = d.magFilter = GL_NEAREST;
                    e.depth = gl::Texture::create("shadow.cubeDepth", d);
                } else {
                    e.depth = gl::Texture::create2D("shadow.depth", size * tiles, size * tiles, GL_DEPTH_COMPONENT32F);
                    e.depth.setCompareMode(true);
                    e.distance = gl::Texture();
                }
            }
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LESS);
            glDisable(GL_BLEND);
            glDisable(GL_CULL_FACE);
            // Directional maps' slope-scaled bias is the receiver plane's, in the shader
            // (common/lighting.glsl): a slope factor on top only lifts occluders off their contacts (light
            // leaks under courtyard's arches; docs/rendering.md), so they keep the constant units alone
            // (depth quantization where the receiver plane's slope is 0). Spot maps keep both (their
            // shadows were right before issue 30: cornell-box lost 0.2 % of its light with the receiver
            // plane, at the box's concave corners), cube maps too, for their z-test.
            glEnable(GL_POLYGON_OFFSET_FILL);
            glPolygonOffset(light.type == LightType::Directional ? 0.0f : kSlopeBias, kConstantBias);
            if (cube) {
                m_distanceProgram.use();
                for (int face = 0; face < 6; ++face) {
                    e.fbo.attachLayer(GL_COLOR_ATTACHMENT0, e.distance, face);
                    e.fbo.attachLayer(GL_DEPTH_ATTACHMENT, e.depth, face);
                    e.fbo.setDrawBuffers(1);
                    BOUNCE_CHECK(e.fbo.complete(), "cube shadow framebuffer");
                    e.fbo.bind();
                    // GL_COLOR clears read four floats whatever the format (issue 29 #24); depth one.
                    const float clearDistance[4] = {1.0f, 1.0f, 1.0f, 1.0f};
                    const float clearDepth = 1.0f;
                    glClearNamedFramebufferfv(e.fbo.id(), GL_COLOR, 0, clearDistance);
                    glClearNamedFramebufferfv(e.fbo.id(), GL_DEPTH, 0, &clearDepth);
                    drawer.draw(cubeFaceView(origin, face, nearPlane, farPlane, size));
                }
            } else {
                m_depthProgram.use();
                e.fbo.attach(GL_DEPTH_ATTACHMENT, e.depth);
                e.fbo.setDrawBuffers(0);
                BOUNCE_CHECK(e.fbo.complete(), "2D shadow framebuffer");
                e.fbo.bind();
                const float clear = 1.0f;
                glClearNamedFramebufferfv(e.fbo.id(), GL_DEPTH, 0, &clear);
                // Each cascade into its tile: the whole atlas is the viewport, the scissor keeps the
                // cascade's triangles out of its neighbours' tiles.
                if (tiles > 1) glEnable(GL_SCISSOR_TEST);
                for (int c = 0; c < cascades.count; ++c) {
                    glScissor((c % 2) * size, (c / 2) * size, size, size);
                    View v;
                    v.viewFromWorld = glm::mat4(1.0f);
                    v.clipFromView = tiles > 1 ? cascadeAtlasClipFromWorld(g.shadowClipFromWorld, cascades, c)
                                               : g.shadowClipFromWorld;
                    v.eye = light.position;
                    v.nearPlane = nearPlane;
                    v.farPlane = farPlane;
                    v.viewport = {size * tiles, size * tiles};
                    drawer.draw(v);
                }
                glDisable(GL_SCISSOR_TEST);
            }
            glDisable(GL_POLYGON_OFFSET_FILL);
            e.rendered = light;
            e.size = size;
            e.tiles = tiles;
            e.cascades = cascades;
            e.valid = true;
            ++m_mapsRendered;
        }
        // The texel-scaled normal offset (common/lighting.glsl), in texels: shadowNormalOffset kernel reaches.
        g.shadowOrigin = glm::vec4(origin, settings.shadowNormalOffset * (settings.pcfRadius + 1.0f) * std::sqrt(2.0f));
        e.gpu = g;
        e.ubo.upload(0, sizeof(g), &g);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previousFbo));
}

}  // namespace bounce::render
