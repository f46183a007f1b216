#pragma once
// The scene uploaded once: one vertex and one index buffer for all meshes, per-object and
// per-material storage buffers, the materials' textures (base colour and emission) in one array texture, and indirect draw
// commands for every object, the static ones and the dynamic ones. Per frame only the dynamic
// objects' transforms and the lights change (update()).
#include "common/shared.h"
#include "gpu/Objects.h"
#include "scene/Scene.h"

#include <vector>

namespace bounce::render {

enum class DrawFilter { All = 0, Static = 1, Dynamic = 2 };

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);

    // Re-evaluates animated objects and lights at time t (seconds) and uploads what changed.
    void update(float time);
    // The next update() re-uploads every object even at the same time (the viewer moved one in place).
    void invalidateObjects() { m_time = -1.0f; }

    const Scene& scene() const { return *m_scene; }
    float time() const { return m_time; }
    // Lights at the current time, and their GPU form (shadow fields are filled by ShadowMaps).
    const std::vector<Light>& lights() const { return m_lights; }
    Camera camera() const { return m_scene->camera.at(m_time); }

    // Draws the selected objects with the bound program and view (SceneDrawer binds the rest).
    void bindGeometry() const;
    void drawIndirect(DrawFilter filter) const;
    size_t drawCount(DrawFilter filter) const { return m_commandCount[static_cast<int>(filter)]; }
    size_t triangleCount(DrawFilter filter) const { return m_triangleCount[static_cast<int>(filter)]; }
    bool hasDynamicObjects() const { return m_commandCount[static_cast<int>(DrawFilter::Dynamic)] > 0; }

    const gl::Buffer& objects() const { return m_objects; }
    // All meshes' vertices (32 bytes each: position, normal, uv; SceneGpu.cpp's Vertex), for passes
    // that pull vertices themselves.
    const gl::Buffer& vertices() const { return m_vertices; }
    const gl::Buffer& materials() const { return m_materials; }
    // The material texture array: its layers are the ones MaterialGpu::baseColor.a and emission.a name
    // (materials' textures only, not Scene::textures indices).
    const gl::Texture& baseColorTextures() const { return m_textures; }

private:
    const Scene* m_scene;
    float m_time = -1.0f;
    std::vector<Light> m_lights;
    std::vector<gpu::ObjectGpu> m_objectData;
    gl::Buffer m_vertices, m_tangents, m_indices, m_instanceIds, m_objects, m_materials, m_commands;
    gl::VertexArray m_vao;
    gl::Texture m_textures;
    size_t m_commandOffset[3] = {0, 0, 0};
    size_t m_commandCount[3] = {0, 0, 0};
    size_t m_triangleCount[3] = {0, 0, 0};
};

}  // namespace bounce::render
