#pragma once
// Small scenes built in code for the reference tests, so that they know their answer exactly and do
// not depend on the scene loader.
#include "scene/Scene.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <utility>

namespace bounce::testscenes {

// Appends a parallelogram centred at `centre` with full edges u, v; its front side (counter-
// clockwise winding) faces cross(u, v).
inline void addQuad(Mesh& mesh, glm::vec3 centre, glm::vec3 u, glm::vec3 v) {
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    const glm::vec3 c0 = centre - 0.5f * u - 0.5f * v;
    mesh.positions.insert(mesh.positions.end(), {c0, c0 + u, c0 + u + v, c0 + v});
    mesh.normals.insert(mesh.normals.end(), {n, n, n, n});
    mesh.uvs.insert(mesh.uvs.end(), {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// Appends `mesh` drawn with `material` to `scene` as one more object, named after the mesh.
inline void addObject(Scene& scene, Mesh mesh, Material material) {
    Object o;
    o.name = mesh.name;
    o.mesh = static_cast<uint32_t>(scene.meshes.size());
    o.material = static_cast<uint32_t>(scene.materials.size());
    scene.meshes.push_back(std::move(mesh));
    scene.materials.push_back(std::move(material));
    scene.objects.push_back(o);
}

// The six faces of the cube [-h, h]^3, facing inwards.
inline Mesh roomMesh(float h) {
    Mesh m;
    m.name = "room";
    const float s = 2.0f * h;
    addQuad(m, {0, -h, 0}, {0, 0, s}, {s, 0, 0});  // floor, +y
    addQuad(m, {0, h, 0}, {s, 0, 0}, {0, 0, s});   // ceiling, -y
    addQuad(m, {-h, 0, 0}, {0, s, 0}, {0, 0, s});  // +x
    addQuad(m, {h, 0, 0}, {0, 0, s}, {0, s, 0});   // -x
    addQuad(m, {0, 0, -h}, {s, 0, 0}, {0, s, 0});  // +z
    addQuad(m, {0, 0, h}, {0, s, 0}, {s, 0, 0});   // -z
    return m;
}

// Furnace room: a closed cube of half-size 1 m whose inner faces have albedo rho and emit Le;
// camera at the centre looking down -z with a 90 degree field of view.
inline Scene furnaceRoom(float rho, float emitted, bool twoSided = false) {
    Scene scene;
    scene.name = "test-furnace";
    scene.source = "test";
    scene.meshes.push_back(roomMesh(1.0f));
    Material m;
    m.name = "glowing";
    m.baseColor = glm::vec3(rho);
    m.emission = glm::vec3(emitted);
    m.twoSided = twoSided;
    scene.materials.push_back(m);
    Object o;
    o.name = "room";
    scene.objects.push_back(o);
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.target = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.verticalFov = 1.5707964f;
    return scene;
}

// Sphere furnace (analytic-tests.md): a closed sphere of radius 1 m and albedo rho, tessellated
// into 2 * slices * (stacks - 1) triangles facing inwards, with a point light of intensity I at its
// centre and the camera there too, looking down -z with a 90 degree field of view.
inline Scene sphereFurnace(float rho, float intensity, int slices, int stacks) {
    Scene scene;
    scene.name = "test-sphere-furnace";
    scene.source = "test";
    Mesh m;
    m.name = "sphere";
    for (int j = 0; j <= stacks; ++j) {
        const float theta = 3.14159265f * static_cast<float>(j) / static_cast<float>(stacks);
        for (int i = 0; i <= slices; ++i) {
            const float phi = 6.28318531f * static_cast<float>(i) / static_cast<float>(slices);
            const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            m.positions.push_back(p);
            m.normals.push_back(-p);  // inwards
        }
    }
    const auto index = [&](int i, int j) { return static_cast<uint32_t>(j * (slices + 1) + i); };
    for (int j = 0; j < stacks; ++j)
        for (int i = 0; i < slices; ++i) {
            // Counter-clockwise seen from the centre (the front side faces inwards). The pole rows
            // produce one degenerate triangle per quad, which Embree never hits and NEE never samples.
            const uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
            if (j != 0) m.indices.insert(m.indices.end(), {a, c, b});
            if (j != stacks - 1) m.indices.insert(m.indices.end(), {a, d, c});
        }
    scene.meshes.push_back(m);
    Material mat;
    mat.name = "grey";
    mat.baseColor = glm::vec3(rho);
    scene.materials.push_back(mat);
    Object o;
    o.name = "sphere";
    scene.objects.push_back(o);
    Light light;
    light.name = "centre";
    light.type = LightType::Point;
    light.intensity = glm::vec3(intensity);
    scene.lights.push_back(light);
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.target = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.verticalFov = 1.5707964f;
    return scene;
}

// A large horizontal plane y = 0 (facing +y) of albedo rho, seen from straight above by an
// orthographic camera whose view is `viewSize` metres wide and centred on the origin. Image column
// x maps to world x, image row y to world z (row 0 at z = -viewSize/2).
inline Scene planeUnderOrthoCamera(float rho, float viewSize) {
    Scene scene;
    scene.name = "test-plane";
    scene.source = "test";
    Mesh mesh;
    mesh.name = "plane";
    addQuad(mesh, {0, 0, 0}, {0, 0, 40}, {40, 0, 0});
    scene.meshes.push_back(mesh);
    Material m;
    m.name = "grey";
    m.baseColor = glm::vec3(rho);
    scene.materials.push_back(m);
    Object o;
    o.name = "plane";
    scene.objects.push_back(o);
    scene.camera.position = {0.0f, 10.0f, 0.0f};
    scene.camera.target = {0.0f, 0.0f, 0.0f};
    scene.camera.up = {0.0f, 0.0f, -1.0f};
    scene.camera.projection = Projection::Orthographic;
    scene.camera.orthoHeight = viewSize;
    scene.camera.nearPlane = 0.1f;
    scene.camera.farPlane = 20.0f;
    return scene;
}

}  // namespace bounce::testscenes
