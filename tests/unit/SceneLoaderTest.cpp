// Model files through assimp (glTF with KHR_lights_punctual and cameras, OBJ/MTL, PLY), their normals,
// and the errors bad input must give (JSON scene files: JsonSceneFileTest.cpp).
#include "core/ImageIo.h"
#include "scene/JsonLocator.h"
#include "scene/SceneLoader.h"
#include "SceneFileTestSupport.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace bounce;
using namespace bounce::scenefiletest;

namespace {

// A textured quad: 2x2 texture, top-left texel red.
void writeTexturedObj(const std::string& stem, const std::string& textureName, bool writeTexture) {
    if (writeTexture) {
        Image tex(2, 2, glm::vec3(0.0f, 0.0f, 1.0f));
        tex.at(0, 0) = glm::vec3(1.0f, 0.0f, 0.0f);
        tex.at(1, 0) = glm::vec3(0.0f, 1.0f, 0.0f);
        ASSERT_TRUE(writeImage(tempDir() / textureName, tex, ToneMap{0.0f, ToneCurve::Clamp}).ok());
    }
    writeFile(stem + ".mtl", "newmtl painted\nKd 0.5 0.6 0.7\nmap_Kd " + textureName + "\n");
    writeFile(stem + ".obj", "mtllib " + stem + ".mtl\n"
                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                             "usemtl painted\n"
                             "f 1/1 2/2 3/3 4/4\n");
}

}  // namespace

TEST(ModelLoader, ObjWithMtlAndTexture) {
    writeTexturedObj("textured", "checker.png", true);
    Expected<Scene> scene = loadScene((tempDir() / "textured.obj").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->triangleCount(), 2u);
    ASSERT_EQ(scene->objects.size(), 1u);
    const Material& m = scene->materials[scene->objects[0].material];
    EXPECT_NEAR(m.baseColor.g, 0.6f, 1e-6f);
    EXPECT_TRUE(m.twoSided);            // OBJ has no culling convention
    EXPECT_EQ(m.specularF0, 0.0f);      // Lambert
    ASSERT_EQ(m.baseColorTexture, 0);
    ASSERT_EQ(scene->textures.size(), 1u);
    const Image& img = scene->textures[0].image;
    ASSERT_EQ(img.width(), 2);
    // 8-bit sRGB round trip of 1.0 and 0.0 is exact; blue stays blue.
    EXPECT_NEAR(img.at(0, 0).r, 1.0f, 1e-6f);
    EXPECT_NEAR(img.at(0, 0).g, 0.0f, 1e-6f);
    EXPECT_NEAR(img.at(1, 1).b, 1.0f, 1e-6f);
    // OBJ's vt (0, 0) is the image's bottom-left; bounce's uv origin is the top-left (docs/scene.md).
    const Mesh& mesh = scene->meshes[scene->objects[0].mesh];
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_NEAR(mesh.uvs[i].x, mesh.positions[i].x, 1e-6f);
        EXPECT_NEAR(mesh.uvs[i].y, 1.0f - mesh.positions[i].y, 1e-6f);
    }
    // Missing normals were computed: the quad faces +z (counter-clockwise in the file).
    EXPECT_NEAR(mesh.normals[0].z, 1.0f, 1e-6f);
    // No lights in the file: the default sun; no camera: one framing the model.
    ASSERT_EQ(scene->lights.size(), 1u);
    EXPECT_EQ(scene->lights[0].type, LightType::Directional);
    EXPECT_GT(scene->camera.position.z, 1.0f);
}

// MTL's Ke and map_Ke become the emission and its texture (docs/scene.md "OBJ/MTL"); the same image as
// map_Kd is loaded once.
TEST(ModelLoader, ObjEmissionTexture) {
    writeTexturedObj("glowing", "glow.png", true);
    writeFile("glowing.mtl", "newmtl painted\nKd 0.5 0.6 0.7\nKe 2 3 4\nmap_Kd glow.png\nmap_Ke glow.png\n");
    Expected<Scene> scene = loadScene((tempDir() / "glowing.obj").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& m = scene->materials[scene->objects[0].material];
    EXPECT_NEAR(m.emission.b, 4.0f, 1e-6f);
    ASSERT_GE(m.emissionTexture, 0);
    EXPECT_EQ(m.emissionTexture, m.baseColorTexture);
    EXPECT_EQ(scene->textures.size(), 1u);
}

TEST(ModelLoader, MissingTextureWarnsAndFallsBackToBaseColour) {
    writeTexturedObj("untextured", "no-such-texture.png", false);
    LogCapture log;
    Expected<Scene> scene = loadScene((tempDir() / "untextured.obj").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& m = scene->materials[scene->objects[0].material];
    EXPECT_EQ(m.baseColorTexture, -1);
    EXPECT_NEAR(m.baseColor.b, 0.7f, 1e-6f);
    EXPECT_TRUE(scene->textures.empty());
    EXPECT_TRUE(contains(log.text(), "no-such-texture.png")) << log.text();
}

// assimp names the mesh and node of an OBJ without `o`/`g` "defaultobject"; messages and object names
// use the file the user wrote instead (issue "Reliability": warnings named 'defaultobject').
TEST(ModelLoader, ObjWithoutObjectNamesUsesTheFile) {
    const fs::path p = writeFile("plate.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 2 0 0\nf 1 2 3\nf 1 2 4\n");
    LogCapture log;
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->objects.size(), 1u);
    EXPECT_EQ(scene->objects[0].name, "plate");
    EXPECT_EQ(scene->meshes[scene->objects[0].mesh].name, "plate.obj");
    // The second triangle is degenerate (collinear): the warning names the file and the object.
    EXPECT_TRUE(contains(log.text(), "mesh 'plate.obj' (object 'plate')")) << log.text();
    EXPECT_FALSE(contains(log.text(), "defaultobject")) << log.text();
    // Placed by a JSON scene, the object is the user's.
    writeFile("plate.json", R"({"objects": [{"name": "table-top", "model": "plate.obj"}],
 "camera": {"position": [0, 1, 3], "target": [0, 0, 0]}})");
    LogCapture log2;
    Expected<Scene> placed = loadScene((tempDir() / "plate.json").string());
    ASSERT_TRUE(placed.ok()) << placed.error().message;
    EXPECT_TRUE(contains(log2.text(), "plate.json: mesh 'plate.obj' (object 'table-top')")) << log2.text();
    EXPECT_FALSE(contains(log2.text(), "defaultobject")) << log2.text();
}

// A NaN vertex is reported as such: assimp's JoinIdenticalVertices, which runs after bounce's check,
// used to merge it with another vertex and leave a "degenerate" triangle (or a wrong valid one).
TEST(ModelLoader, NanVertexIsReportedBeforeAssimpJoinsVertices) {
    for (const char* v : {"1 nan 0", "nan 1 0", "1 NaN 2"}) {
        const fs::path p = writeFile("nan-vertex.obj", std::string("v 0 0 0\nv ") + v + "\nv 1 0 0\nf 1 2 3\n");
        Expected<Scene> scene = loadScene(p.string());
        ASSERT_FALSE(scene.ok()) << v;
        EXPECT_TRUE(contains(scene.error().message, "nan-vertex.obj")) << scene.error().message;
        EXPECT_TRUE(contains(scene.error().message, "vertex 1 has a non-finite position")) << scene.error().message;
    }
}

TEST(ModelLoader, AsciiPly) {
    const fs::path p = writeFile("square.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n2 0 0\n2 0 2\n0 0 2\n3 0 3 2\n3 0 2 1\n");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->triangleCount(), 2u);
    glm::vec3 lo, hi;
    scene->bounds(0.0f, lo, hi);
    EXPECT_NEAR(hi.x - lo.x, 2.0f, 1e-6f);
    const Mesh& mesh = scene->meshes[scene->objects[0].mesh];
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    EXPECT_NEAR(mesh.normals[0].y, 1.0f, 1e-6f);  // 0 3 2 is counter-clockwise seen from +y
}

TEST(ModelLoader, GltfWithLightsCameraAndEmbeddedTexture) {
    // One triangle, a base64 buffer, an embedded PNG, KHR_lights_punctual point/spot/directional, a camera.
    Image tex(1, 1, glm::vec3(0.5f));
    const fs::path png = tempDir() / "grey.png";
    ASSERT_TRUE(writeImage(png, tex, ToneMap{0.0f, ToneCurve::Clamp}).ok());
    std::string buffer;
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    const uint16_t indices[4] = {0, 1, 2, 0};  // padded to 4-byte length
    buffer.append(reinterpret_cast<const char*>(positions), sizeof positions);
    buffer.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
    buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
    const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"name": "bulb", "type": "point", "color": [1, 0.5, 0.25], "intensity": 683},
    {"name": "torch", "type": "spot", "color": [1, 1, 1], "intensity": 68.3,
     "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}},
    {"name": "sun", "type": "directional", "color": [1, 1, 1], "intensity": 1366}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
  "nodes": [
    {"name": "tri", "mesh": 0, "translation": [0, 0, -2]},
    {"name": "bulbNode", "translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "torchNode", "translation": [0, 3, 0], "rotation": [-0.70710678, 0, 0, 0.70710678],
     "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"name": "sunNode", "extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"name": "camNode", "camera": 0, "translation": [0, 1, 5], "rotation": [0, 0.38268343, 0, 0.92387953]}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1, "zfar": 50}}],
  "meshes": [{"name": "triMesh", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
  "materials": [{"name": "paint", "doubleSided": true, "emissiveFactor": [0.1, 0.2, 0.3],
    "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0.3, "roughnessFactor": 0.7,
                             "baseColorTexture": {"index": 0}},
    "emissiveTexture": {"index": 0}}],
  "textures": [{"source": 0}],
  "images": [{"uri": "data:image/png;base64,)" + base64(readBytes(png)) + R"("}],
  "buffers": [{"byteLength": )" + std::to_string(buffer.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
                             base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                  {"buffer": 0, "byteOffset": 60, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})";
    const fs::path path = writeFile("lights.gltf", gltf);
    Expected<Scene> scene = loadScene(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    ASSERT_EQ(scene->objects.size(), 1u);
    glm::vec3 lo, hi;
    scene->bounds(0.0f, lo, hi);
    EXPECT_NEAR(lo.z, -2.0f, 1e-6f);  // node translation applied

    const Material& m = scene->materials[scene->objects[0].material];
    EXPECT_NEAR(m.baseColor.g, 0.25f, 1e-6f);
    EXPECT_NEAR(m.metallic, 0.3f, 1e-6f);
    EXPECT_NEAR(m.roughness, 0.7f, 1e-6f);
    EXPECT_NEAR(m.emission.b, 0.3f, 1e-6f);
    EXPECT_TRUE(m.twoSided);
    EXPECT_NEAR(m.specularF0, 0.04f, 1e-7f);  // glTF dielectric
    ASSERT_GE(m.baseColorTexture, 0);
    // 0.5 linear -> 8-bit sRGB 188 -> 0.5029 linear: within one 8-bit step.
    EXPECT_NEAR(scene->textures[static_cast<size_t>(m.baseColorTexture)].image.at(0, 0).r, 0.5f, 0.005f);
    EXPECT_EQ(m.emissionTexture, m.baseColorTexture) << "glTF emissiveTexture: the same image, loaded once";

    ASSERT_EQ(scene->lights.size(), 3u);
    const Light* bulb = nullptr;
    const Light* torch = nullptr;
    const Light* sun = nullptr;
    for (const Light& l : scene->lights) {
        if (l.type == LightType::Point) bulb = &l;
        if (l.type == LightType::Spot) torch = &l;
        if (l.type == LightType::Directional) sun = &l;
    }
    ASSERT_TRUE(bulb && torch && sun);
    // 683 cd of colour (1, 0.5, 0.25) is (1, 0.5, 0.25) W/sr at 683 lm/W.
    EXPECT_NEAR(bulb->intensity.r, 1.0f, 1e-5f);
    EXPECT_NEAR(bulb->intensity.b, 0.25f, 1e-5f);
    EXPECT_NEAR(glm::length(bulb->position - glm::vec3(1, 2, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(torch->intensity.g, 0.1f, 1e-6f);
    EXPECT_NEAR(torch->direction.y, -1.0f, 1e-5f);  // -90 degrees about x turns -z into -y
    EXPECT_NEAR(torch->position.y, 3.0f, 1e-5f);
    EXPECT_NEAR(torch->cutoffAngle, 0.6f, 1e-6f);
    // Matches glTF's half-intensity angle: t = 1/sqrt(2) between cos(outer) and cos(inner).
    const float cosHalf = std::cos(0.6f) + (std::cos(0.3f) - std::cos(0.6f)) / std::sqrt(2.0f);
    EXPECT_NEAR(std::pow(cosHalf, torch->falloffExponent), 0.5f, 1e-4f);
    EXPECT_NEAR(sun->irradiance.r, 2.0f, 1e-5f);  // 1366 lx
    EXPECT_NEAR(sun->direction.z, -1.0f, 1e-5f);

    const Camera& cam = scene->camera;
    EXPECT_NEAR(glm::length(cam.position - glm::vec3(0, 1, 5)), 0.0f, 1e-5f);
    EXPECT_NEAR(cam.verticalFov, 0.8f, 1e-5f);
    const glm::vec3 view = glm::normalize(cam.target - cam.position);
    // 45 degrees about +y turns -z into (-sin 45, 0, -cos 45).
    EXPECT_NEAR(view.x, -std::sqrt(0.5f), 1e-5f);
    EXPECT_NEAR(view.z, -std::sqrt(0.5f), 1e-5f);
    EXPECT_NEAR(cam.nearPlane, 0.1f, 1e-6f);
    EXPECT_NEAR(cam.farPlane, 50.0f, 1e-4f);
}

TEST(ModelLoader, BinaryGlb) {
    // GLB container: 12-byte header, a JSON chunk and a BIN chunk, each padded to 4 bytes.
    std::string bin;
    const float positions[9] = {0, 0, 0, 2, 0, 0, 0, 2, 0};
    const uint16_t indices[4] = {0, 1, 2, 0};
    bin.append(reinterpret_cast<const char*>(positions), sizeof positions);
    bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
    std::string js = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"name": "glbTri", "mesh": 0, "scale": [1, 1, 3]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "buffers": [{"byteLength": )" + std::to_string(bin.size()) + R"(}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [2, 2, 0]},
                    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
    while (js.size() % 4 != 0) js += ' ';
    const auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::string glb = "glTF" + u32(2) + u32(static_cast<uint32_t>(12 + 8 + js.size() + 8 + bin.size())) +
                            u32(static_cast<uint32_t>(js.size())) + "JSON" + js +
                            u32(static_cast<uint32_t>(bin.size())) + std::string("BIN\0", 4) + bin;
    const fs::path p = writeFile("tri.glb", glb);
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->objects.size(), 1u);
    EXPECT_EQ(scene->objects[0].name, "glbTri");
    EXPECT_EQ(scene->triangleCount(), 1u);
    glm::vec3 lo, hi;
    scene->bounds(0.0f, lo, hi);
    EXPECT_NEAR(hi.x, 2.0f, 1e-6f);
    EXPECT_NEAR(hi.z, 0.0f, 1e-6f);  // the z scale leaves a z = 0 triangle in place
}

TEST(ModelLoader, IndexOutOfRangeInAFileIsAnError) {
    const fs::path p = writeFile("badindex.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_FALSE(scene.ok());
    EXPECT_TRUE(contains(scene.error().message, "badindex.ply")) << scene.error().message;
    EXPECT_TRUE(contains(scene.error().message, "out of range")) << scene.error().message;
}

TEST(ModelLoader, AllDegenerateMeshIsAnError) {
    const fs::path p = writeFile("flat.obj", "o sliver\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_FALSE(scene.ok());
    EXPECT_TRUE(contains(scene.error().message, "degenerate")) << scene.error().message;
    EXPECT_TRUE(contains(scene.error().message, "flat.obj")) << scene.error().message;
    EXPECT_TRUE(contains(scene.error().message, "sliver")) << scene.error().message;
}

TEST(ModelLoader, MissingAndUnsupportedFiles) {
    Expected<Scene> missing = loadScene((tempDir() / "nowhere.obj").string());
    ASSERT_FALSE(missing.ok());
    EXPECT_TRUE(contains(missing.error().message, "nowhere.obj")) << missing.error().message;
    const fs::path garbage = writeFile("garbage.gltf", "this is not glTF");
    Expected<Scene> bad = loadScene(garbage.string());
    ASSERT_FALSE(bad.ok());
    EXPECT_TRUE(contains(bad.error().message, "garbage.gltf")) << bad.error().message;
    Expected<Scene> withParams = loadScene(garbage.string(), {{"triangles", "5"}});
    ASSERT_FALSE(withParams.ok());
}

// Missing normals (docs/scene.md "Model files"): OBJ is flat unless a nonzero smoothing group is active,
// glTF is flat (glTF 2.0 section 3.7.2.1), explicit normals are kept.
namespace {

// Normals closer than this are the same direction: the loaders' normals are float and normalised
// (about 1e-7 apart when equal), distinct cube normals are at least 0.5 apart.
constexpr float kSameNormal = 1e-5f;

std::vector<glm::vec3> distinctNormals(const Mesh& mesh) {
    std::vector<glm::vec3> out;
    for (const glm::vec3& n : mesh.normals) {
        bool seen = false;
        for (const glm::vec3& d : out) seen = seen || glm::length(n - d) < kSameNormal;
        if (!seen) out.push_back(n);
    }
    return out;
}

glm::vec3 triangleNormal(const Mesh& mesh, size_t t) {
    const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
    const glm::vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
    const glm::vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
    return glm::normalize(glm::cross(b - a, c - a));
}

glm::vec3 triangleCentroid(const Mesh& mesh, size_t t) {
    return (mesh.positions[mesh.indices[3 * t]] + mesh.positions[mesh.indices[3 * t + 1]] +
            mesh.positions[mesh.indices[3 * t + 2]]) / 3.0f;
}

// A unit cube centred at the origin, flat: six distinct normals, and every corner of every triangle
// carries its triangle's geometric normal (counter-clockwise winding), which points away from the centre.
void expectFlatCube(const Scene& scene) {
    ASSERT_EQ(scene.objects.size(), 1u);
    const Mesh& mesh = scene.meshes[scene.objects[0].mesh];
    ASSERT_EQ(mesh.indices.size(), 36u);
    EXPECT_EQ(distinctNormals(mesh).size(), 6u);
    for (size_t t = 0; t < 12; ++t) {
        const glm::vec3 geometric = triangleNormal(mesh, t);
        // Outward: along the face's centroid direction, which for a cube face is its axis.
        EXPECT_GT(glm::dot(geometric, glm::normalize(triangleCentroid(mesh, t))), 0.7f) << "triangle " << t;
        for (int k = 0; k < 3; ++k)
            EXPECT_LT(glm::length(mesh.normals[mesh.indices[3 * t + k]] - geometric), kSameNormal)
                << "triangle " << t << " corner " << k;
    }
}

std::string cubeGltf(bool withNormals) {
    // Eight shared vertices and 36 indices (the same winding as kCubeObj): smooth if normals were
    // averaged over shared vertices, as bounce did before.
    const float p[24] = {-0.5f, -0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, -0.5f, -0.5f, 0.5f, -0.5f,
                         -0.5f, -0.5f, 0.5f,  0.5f, -0.5f, 0.5f,  0.5f, 0.5f, 0.5f,  -0.5f, 0.5f, 0.5f};
    const uint16_t quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
    std::vector<uint16_t> indices;
    for (const auto& q : quads) indices.insert(indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    std::string buffer(reinterpret_cast<const char*>(p), sizeof p);
    if (withNormals) {
        std::vector<float> n(p, p + 24);  // corner directions: smooth normals given explicitly
        for (float& x : n) x /= std::sqrt(0.75f);
        buffer.append(reinterpret_cast<const char*>(n.data()), n.size() * sizeof(float));
    }
    const size_t indexOffset = buffer.size();
    buffer.append(reinterpret_cast<const char*>(indices.data()), indices.size() * sizeof(uint16_t));
    const std::string normalAttribute = withNormals ? R"(, "NORMAL": 2)" : "";
    const std::string normalView = withNormals ? R"(, {"buffer": 0, "byteOffset": 96, "byteLength": 96})" : "";
    const std::string normalAccessor =
        withNormals ? R"(, {"bufferView": 2, "componentType": 5126, "count": 8, "type": "VEC3"})" : "";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"name": "cube", "mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0)" + normalAttribute + R"(}, "indices": 1}]}],
      "buffers": [{"byteLength": )" + std::to_string(buffer.size()) +
           R"(, "uri": "data:application/octet-stream;base64,)" + base64(buffer) + R"("}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                      {"buffer": 0, "byteOffset": )" + std::to_string(indexOffset) + R"(, "byteLength": 72})" +
           normalView + R"(],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                     "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
                    {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"})" +
           normalAccessor + "]}";
}

}  // namespace

TEST(ModelNormals, ObjWithoutNormalsIsFlat) {
    Expected<Scene> scene = loadScene(writeFile("normals/flat.obj", kCubeObj).string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    expectFlatCube(*scene);
    // Each face's two triangles share its four corners: 24 vertices, not 36.
    EXPECT_EQ(scene->meshes[0].positions.size(), 24u);
}

TEST(ModelNormals, ObjSmoothingGroupOffIsFlat) {
    // "s 0" and "s off" both mean no smoothing group.
    Expected<Scene> zero = loadScene(writeFile("normals/s0.obj", std::string("s 0\n") + kCubeObj).string());
    ASSERT_TRUE(zero.ok()) << zero.error().message;
    expectFlatCube(*zero);
    Expected<Scene> off = loadScene(writeFile("normals/soff.obj", std::string("s off\n") + kCubeObj).string());
    ASSERT_TRUE(off.ok()) << off.error().message;
    expectFlatCube(*off);
}

TEST(ModelNormals, ObjSmoothingGroupIsSmooth) {
    Expected<Scene> scene = loadScene(writeFile("normals/smooth.obj", std::string("s 1\n") + kCubeObj).string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[scene->objects[0].mesh];
    // One normal per corner: the three faces meeting there, weighted by their equal 90-degree angles,
    // average to the corner's diagonal.
    EXPECT_EQ(distinctNormals(mesh).size(), 8u);
    EXPECT_EQ(mesh.positions.size(), 8u);
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        EXPECT_LT(glm::length(mesh.normals[i] - glm::normalize(mesh.positions[i])), kSameNormal) << "vertex " << i;
}

TEST(ModelNormals, ObjMixesSmoothingGroupsAndFlatFaces) {
    // The three faces at corner (-,-,-) in group 1, then smoothing off for the other three, which are flat.
    const std::string obj =
        "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
        "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
        "s 1\nf 1 4 3 2\nf 1 5 8 4\nf 1 2 6 5\n"
        "s off\nf 5 6 7 8\nf 2 3 7 6\nf 4 8 7 3\n";
    Expected<Scene> scene = loadScene(writeFile("normals/mixed.obj", obj).string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[scene->objects[0].mesh];
    ASSERT_EQ(mesh.indices.size(), 36u);
    size_t flatTriangles = 0;
    for (size_t t = 0; t < 12; ++t) {
        const glm::vec3 geometric = triangleNormal(mesh, t);
        const bool positiveFace = glm::dot(geometric, glm::vec3(1.0f)) > 0.0f;  // +x, +y or +z
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = mesh.indices[3 * t + k];
            if (positiveFace) {
                EXPECT_LT(glm::length(mesh.normals[v] - geometric), kSameNormal) << "triangle " << t;
            } else {
                // Smooth: the mean of the group-1 faces (-x, -y, -z, all meeting the vertex at 90
                // degrees) the vertex lies on; the flat faces it also lies on do not count.
                const glm::vec3 p = mesh.positions[v];
                const glm::vec3 expected = glm::normalize(-glm::vec3(p.x < 0.0f, p.y < 0.0f, p.z < 0.0f));
                EXPECT_LT(glm::length(mesh.normals[v] - expected), kSameNormal) << "triangle " << t << " corner " << k;
            }
        }
        flatTriangles += positiveFace;
    }
    EXPECT_EQ(flatTriangles, 6u);
}

TEST(ModelNormals, ObjExplicitNormalsAreKept) {
    // Corner normals given with vn (the smooth cube's), no smoothing group: kept, not made flat.
    std::string obj =
        "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
        "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
        "vn -1 -1 -1\nvn 1 -1 -1\nvn 1 1 -1\nvn -1 1 -1\nvn -1 -1 1\nvn 1 -1 1\nvn 1 1 1\nvn -1 1 1\n"
        "f 1//1 4//4 3//3 2//2\nf 5//5 6//6 7//7 8//8\nf 1//1 5//5 8//8 4//4\n"
        "f 2//2 3//3 7//7 6//6\nf 1//1 2//2 6//6 5//5\nf 4//4 8//8 7//7 3//3\n";
    Expected<Scene> scene = loadScene(writeFile("normals/explicit.obj", obj).string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[scene->objects[0].mesh];
    EXPECT_EQ(distinctNormals(mesh).size(), 8u);
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        EXPECT_LT(glm::length(mesh.normals[i] - glm::normalize(mesh.positions[i])), kSameNormal) << "vertex " << i;
}

TEST(ModelNormals, ObjRewriteKeepsUvsRelativeIndicesAndContinuations) {
    // A face written with negative (relative) indices and texture coordinates, continued over two lines,
    // and a face that already has normals next to it: the rewrite must keep the first's uvs and the
    // second's normal.
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "vn 0 0 -1\n"
        "o flat\nf -4/-4 -3/-3 \\\n -2/-2 -1/-1\n"
        "o given\nf 1/1/1 3/3/1 2/2/1\n";
    Expected<Scene> scene = loadScene(writeFile("normals/relative.obj", obj).string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Object* flat = findObject(*scene, "flat");
    const Object* given = findObject(*scene, "given");
    ASSERT_TRUE(flat && given);
    const Mesh& quad = scene->meshes[flat->mesh];
    EXPECT_EQ(quad.indices.size(), 6u);
    ASSERT_EQ(quad.uvs.size(), quad.positions.size());
    for (size_t i = 0; i < quad.positions.size(); ++i) {
        EXPECT_NEAR(quad.normals[i].z, 1.0f, 1e-6f);  // counter-clockwise seen from +z
        EXPECT_NEAR(quad.uvs[i].x, quad.positions[i].x, 1e-6f);
        EXPECT_NEAR(quad.uvs[i].y, 1.0f - quad.positions[i].y, 1e-6f);  // FlipUVs
    }
    const Mesh& tri = scene->meshes[given->mesh];
    for (const glm::vec3& n : tri.normals) EXPECT_NEAR(n.z, -1.0f, 1e-6f);
}

TEST(ModelNormals, GltfWithoutNormalsIsFlat) {
    Expected<Scene> scene = loadScene(writeFile("normals/flat.gltf", cubeGltf(false)).string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    expectFlatCube(*scene);
    EXPECT_EQ(scene->meshes[0].positions.size(), 24u);  // corners shared within a face only
}

TEST(ModelNormals, GltfExplicitNormalsAreKept) {
    Expected<Scene> scene = loadScene(writeFile("normals/smooth.gltf", cubeGltf(true)).string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[scene->objects[0].mesh];
    EXPECT_EQ(mesh.positions.size(), 8u);
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        EXPECT_LT(glm::length(mesh.normals[i] - glm::normalize(mesh.positions[i])), kSameNormal) << "vertex " << i;
}
