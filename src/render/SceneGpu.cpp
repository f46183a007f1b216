#include "render/SceneGpu.h"

#include "core/Check.h"
#include "gpu/Bindings.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <stb/stb_image_resize.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace bounce::render {

namespace {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};
static_assert(sizeof(Vertex) == 32);

struct DrawCommand {  // DrawElementsIndirectCommand
    GLuint count, instanceCount, firstIndex;
    GLint baseVertex;
    GLuint baseInstance;
};

// Textures share one array texture, so they are resampled to a common size: the largest width and
// height among them, capped (kMaxTextureSize texels) to bound memory. Identical-size textures, the
// usual case, are uploaded untouched.
constexpr int kMaxTextureSize = 2048;

gpu::ObjectGpu objectData(const Object& o, uint32_t index, float t) {
    gpu::ObjectGpu d;
    d.worldFromObject = o.worldFromObject(t);
    d.normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(d.worldFromObject)));
    d.info = glm::uvec4(o.material, o.isDynamic() ? 1u : 0u, index, 0u);
    return d;
}

}  // namespace

SceneGpu::SceneGpu(const Scene& scene) : m_scene(&scene) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<GLint> meshBaseVertex;
    std::vector<GLuint> meshFirstIndex;
    // Tangents (normal maps) live in their own stream so the 32-byte Vertex, which some passes pull
    // themselves, keeps its layout; without any normal-mapped mesh it is one zero tangent, stride 0.
    bool anyTangents = false;
    for (const Mesh& mesh : scene.meshes) anyTangents = anyTangents || !mesh.tangents.empty();
    std::vector<glm::vec4> tangents;
    for (const Mesh& mesh : scene.meshes) {
        if (anyTangents)
            for (size_t i = 0; i < mesh.positions.size(); ++i)
                tangents.push_back(i < mesh.tangents.size() ? mesh.tangents[i] : glm::vec4(0.0f));
        meshBaseVertex.push_back(static_cast<GLint>(vertices.size()));
        meshFirstIndex.push_back(static_cast<GLuint>(indices.size()));
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            Vertex v;
            v.position = mesh.positions[i];
            v.normal = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f, 1.0f, 0.0f);
            v.uv = i < mesh.uvs.size() ? mesh.uvs[i] : glm::vec2(0.0f);
            vertices.push_back(v);
        }
        indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    }
    BOUNCE_CHECK(!vertices.empty() && !indices.empty(), "scene '{}' has no geometry", scene.name);
    m_vertices = gl::Buffer::create("scene.vertices", vertices.size() * sizeof(Vertex), vertices.data(), 0);
    m_indices = gl::Buffer::create("scene.indices", indices.size() * sizeof(uint32_t), indices.data(), 0);
    if (tangents.empty()) tangents.emplace_back(0.0f);
    m_tangents = gl::Buffer::create("scene.tangents", tangents.size() * sizeof(glm::vec4), tangents.data(), 0);

    std::vector<uint32_t> ids(scene.objects.size());
    for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
    m_instanceIds = gl::Buffer::create("scene.objectIds", std::max<size_t>(ids.size(), 1) * sizeof(uint32_t), ids.data(), 0);

    // Commands grouped [all | static | dynamic] so each filter is one contiguous range.
    std::vector<DrawCommand> commands[3];
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        const Object& o = scene.objects[i];
        const Mesh& mesh = scene.meshes[o.mesh];
        DrawCommand c{static_cast<GLuint>(mesh.indices.size()), 1, meshFirstIndex[o.mesh], meshBaseVertex[o.mesh], i};
        const int group = o.isDynamic() ? 2 : 1;
        commands[0].push_back(c);
        commands[group].push_back(c);
        m_triangleCount[0] += mesh.triangleCount();
        m_triangleCount[group] += mesh.triangleCount();
    }
    std::vector<DrawCommand> all;
    for (int f = 0; f < 3; ++f) {
        m_commandOffset[f] = all.size() * sizeof(DrawCommand);
        m_commandCount[f] = commands[f].size();
        all.insert(all.end(), commands[f].begin(), commands[f].end());
    }
    m_commands = gl::Buffer::create("scene.drawCommands", all.size() * sizeof(DrawCommand), all.data(), 0);

    m_vao = gl::VertexArray::create("scene.vao");
    const GLuint vao = m_vao.id();
    glVertexArrayVertexBuffer(vao, 0, m_vertices.id(), 0, sizeof(Vertex));
    glVertexArrayVertexBuffer(vao, 1, m_instanceIds.id(), 0, sizeof(uint32_t));
    glVertexArrayBindingDivisor(vao, 1, 1);
    glVertexArrayVertexBuffer(vao, 2, m_tangents.id(), 0, anyTangents ? sizeof(glm::vec4) : 0);
    glVertexArrayElementBuffer(vao, m_indices.id());
    auto attrib = [&](GLuint loc, GLint n, GLuint offset) {
        glEnableVertexArrayAttrib(vao, loc);
        glVertexArrayAttribFormat(vao, loc, n, GL_FLOAT, GL_FALSE, offset);
        glVertexArrayAttribBinding(vao, loc, 0);
    };
    attrib(ATTR_POSITION, 3, offsetof(Vertex, position));
    attrib(ATTR_NORMAL, 3, offsetof(Vertex, normal));
    attrib(ATTR_UV, 2, offsetof(Vertex, uv));
    glEnableVertexArrayAttrib(vao, ATTR_TANGENT);
    glVertexArrayAttribFormat(vao, ATTR_TANGENT, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, ATTR_TANGENT, 2);
    glEnableVertexArrayAttrib(vao, ATTR_OBJECT_INDEX);
    glVertexArrayAttribIFormat(vao, ATTR_OBJECT_INDEX, 1, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao, ATTR_OBJECT_INDEX, 1);

    // Materials and the texture array. Only textures a material uses are layers (in order of first
    // use): area lights' emission images live in Scene::textures too, but LightSet uploads them itself,
    // and a long video sequence must neither fill the array nor force every material texture to be
    // resampled to its size.
    std::vector<int> layerOf(scene.textures.size(), -1);
    std::vector<size_t> layers;  // texture index of each layer
    const auto useTexture = [&](int index) {
        if (index < 0) return -1.0f;
        if (layerOf[static_cast<size_t>(index)] < 0) {
            layerOf[static_cast<size_t>(index)] = static_cast<int>(layers.size());
            layers.push_back(static_cast<size_t>(index));
        }
        return static_cast<float>(layerOf[static_cast<size_t>(index)]);
    };
    std::vector<gpu::MaterialGpu> materials;
    for (const Material& m : scene.materials) {
        gpu::MaterialGpu g;
        g.baseColor = glm::vec4(m.baseColor, useTexture(m.baseColorTexture));
        g.emission = glm::vec4(m.emission, useTexture(m.emissionTexture));
        g.params = glm::vec4(m.roughness, m.metallic, m.specularF0, m.twoSided ? 1.0f : 0.0f);
        g.alpha = glm::vec4(m.masked() ? m.alphaCutoff : 0.0f, m.alpha, m.masked() ? useTexture(m.alphaTexture) : -1.0f, 0.0f);
        g.maps = glm::vec4(useTexture(m.normalTexture), m.normalScale, useTexture(m.metallicRoughnessTexture), 0.0f);
        materials.push_back(g);
    }
    int texW = 1, texH = 1;
    for (size_t index : layers) {
        const Image& image = scene.textures[index].image;
        texW = std::max(texW, std::min(image.width(), kMaxTextureSize));
        texH = std::max(texH, std::min(image.height(), kMaxTextureSize));
    }
    gl::TextureDesc td;
    td.target = GL_TEXTURE_2D_ARRAY;
    td.format = GL_RGBA16F;
    td.width = texW;
    td.height = texH;
    td.depth = std::max<int>(1, static_cast<int>(layers.size()));
    td.wrap = GL_REPEAT;
    m_textures = gl::Texture::create("scene.materialTextures", td);
    for (size_t layer = 0; layer < layers.size(); ++layer) {
        const TextureImage& texture = scene.textures[layers[layer]];
        const Image& src = texture.image;
        std::vector<float> rgb(static_cast<size_t>(texW) * texH * 3);
        if (src.width() == texW && src.height() == texH) {
            std::memcpy(rgb.data(), src.data(), rgb.size() * sizeof(float));
        } else {
            spdlog::debug("texture '{}' resampled {}x{} -> {}x{}", texture.name, src.width(), src.height(), texW, texH);
            stbir_resize_float(reinterpret_cast<const float*>(src.data()), src.width(), src.height(), 0, rgb.data(),
                               texW, texH, 0, 3);
        }
        glTextureSubImage3D(m_textures.id(), 0, 0, 0, static_cast<GLint>(layer), texW, texH, 1, GL_RGB, GL_FLOAT,
                            rgb.data());
    }
    if (materials.empty()) materials.emplace_back();
    m_materials = gl::Buffer::create("scene.materials", materials.size() * sizeof(gpu::MaterialGpu), materials.data(), 0);

    m_objectData.resize(std::max<size_t>(scene.objects.size(), 1));
    m_objects = gl::Buffer::create("scene.objects", m_objectData.size() * sizeof(gpu::ObjectGpu));
    m_time = -1.0f;
    update(0.0f);
}

void SceneGpu::update(float time) {
    // Lights are re-evaluated every call: the viewer edits them in place between frames.
    m_lights.clear();
    for (const Light& l : m_scene->lights) m_lights.push_back(l.at(time));
    const bool first = m_time < 0.0f;
    if (!first && time == m_time) return;
    m_time = time;
    bool changed = first;
    for (uint32_t i = 0; i < m_scene->objects.size(); ++i) {
        const Object& o = m_scene->objects[i];
        if (first || o.isDynamic()) {
            m_objectData[i] = objectData(o, i, time);
            changed = true;
        }
    }
    if (changed) m_objects.upload(0, m_objectData.size() * sizeof(gpu::ObjectGpu), m_objectData.data());
}

void SceneGpu::bindGeometry() const {
    m_vao.bind();
    m_objects.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_OBJECTS);
    m_materials.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_MATERIALS);
    m_textures.bind(BINDING_TEX_BASECOLOR);
}

void SceneGpu::drawIndirect(DrawFilter filter) const {
    const int f = static_cast<int>(filter);
    if (m_commandCount[f] == 0) return;
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_commands.id());
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, reinterpret_cast<const void*>(m_commandOffset[f]),
                                static_cast<GLsizei>(m_commandCount[f]), 0);
}

}  // namespace bounce::render
