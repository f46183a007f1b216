#include "render/SceneDrawer.h"

#include "gpu/Bindings.h"

#include <glm/gtc/matrix_transform.hpp>

namespace bounce::render {

View cameraView(const Camera& camera, glm::ivec2 viewport) {
    View v;
    v.viewFromWorld = camera.viewFromWorld();
    v.clipFromView = camera.clipFromView(static_cast<float>(viewport.x) / static_cast<float>(viewport.y));
    v.eye = camera.position;
    v.nearPlane = camera.nearPlane;
    v.farPlane = camera.farPlane;
    v.viewport = viewport;
    return v;
}

View cubeFaceView(glm::vec3 eye, int face, float nearPlane, float farPlane, int size) {
    // GL cube map face orientations (OpenGL 4.5 spec, Table 8.19).
    static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    View v;
    v.viewFromWorld = glm::lookAt(eye, eye + dirs[face], ups[face]);
    v.clipFromView = glm::perspective(glm::radians(90.0f), 1.0f, nearPlane, farPlane);
    v.eye = eye;
    v.nearPlane = nearPlane;
    v.farPlane = farPlane;
    v.viewport = {size, size};
    return v;
}

void beginDepthTestedPass(int clipDistances) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    for (int k = 0; k < clipDistances; ++k) glEnable(GL_CLIP_DISTANCE0 + static_cast<GLenum>(k));
}

void endDepthTestedPass(int clipDistances) {
    for (int k = 0; k < clipDistances; ++k) glDisable(GL_CLIP_DISTANCE0 + static_cast<GLenum>(k));
}

SceneDrawer::SceneDrawer(const SceneGpu& scene)
    : m_scene(&scene), m_viewUbo(gl::Buffer::create("scene.view", sizeof(gpu::ViewUniforms))) {}

void SceneDrawer::draw(const View& view, DrawFilter filter) { drawWith(view, filter, nullptr); }

void SceneDrawer::draw(const View& view, DrawFilter filter, const gl::Buffer& objects) { drawWith(view, filter, &objects); }

void SceneDrawer::drawWith(const View& view, DrawFilter filter, const gl::Buffer* objects) {
    gpu::ViewUniforms u;
    u.clipFromWorld = view.clipFromWorld();
    u.viewFromWorld = view.viewFromWorld;
    u.eyePosition = glm::vec4(view.eye, view.farPlane);
    u.params = glm::vec4(static_cast<float>(view.viewport.x), static_cast<float>(view.viewport.y), view.nearPlane,
                         static_cast<float>(filter));
    m_viewUbo.upload(0, sizeof(u), &u);
    m_viewUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_VIEW);
    glViewport(0, 0, view.viewport.x, view.viewport.y);
    m_scene->bindGeometry();
    if (objects) objects->bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_OBJECTS);
    m_scene->drawIndirect(filter);
    if (objects) m_scene->objects().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_OBJECTS);
    ++m_drawCalls;
}

}  // namespace bounce::render
