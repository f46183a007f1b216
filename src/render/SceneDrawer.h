#pragma once
// "Draw the scene from this view into the bound target." Techniques never walk meshes: they bind
// their program and framebuffer and call draw() with a View, as often as they need (camera, light,
// cube faces, hemicube faces). One multi-draw-indirect call per view; no per-object state changes.
#include "render/SceneGpu.h"

#include <glm/mat4x4.hpp>

namespace bounce::render {

struct View {
    glm::mat4 viewFromWorld{1.0f};
    glm::mat4 clipFromView{1.0f};
    glm::vec3 eye{0.0f};
    float nearPlane = 0.01f, farPlane = 100.0f;  // metres
    glm::ivec2 viewport{1, 1};                   // pixels; draw() sets glViewport to it

    glm::mat4 clipFromWorld() const { return clipFromView * viewFromWorld; }
};

View cameraView(const Camera& camera, glm::ivec2 viewport);
// The +X,-X,+Y,-Y,+Z,-Z faces of a cube map centred at `eye` (90-degree frusta, GL cube conventions).
View cubeFaceView(glm::vec3 eye, int face, float nearPlane, float farPlane, int size);

// The GL state of a depth-tested scene pass into the bound framebuffer: depth test GL_LESS with depth
// writes, both faces drawn, no blending, and gl_ClipDistance[0 .. clipDistances-1] enabled (the
// paraboloid maps' hemisphere, the hemicubes' near side). endDepthTestedPass disables the clip planes.
void beginDepthTestedPass(int clipDistances = 0);
void endDepthTestedPass(int clipDistances = 0);

class SceneDrawer {
public:
    explicit SceneDrawer(const SceneGpu& scene);
    // Uploads the view (BINDING_UBO_VIEW), binds the geometry and draws. The caller has bound its
    // program and framebuffer and set depth/cull state.
    void draw(const View& view, DrawFilter filter = DrawFilter::All);
    // The same with other object transforms bound in place of the scene's (an array of ObjectGpu in
    // scene order): hemicube radiosity draws the scene as it was before objects moved.
    void draw(const View& view, DrawFilter filter, const gl::Buffer& objects);
    const SceneGpu& scene() const { return *m_scene; }
    size_t drawCalls() const { return m_drawCalls; }

private:
    void drawWith(const View& view, DrawFilter filter, const gl::Buffer* objects);

    const SceneGpu* m_scene;
    gl::Buffer m_viewUbo;
    size_t m_drawCalls = 0;
};

}  // namespace bounce::render
