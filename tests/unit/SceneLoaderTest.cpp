// Scene files: models through assimp (glTF with KHR_lights_punctual and cameras, OBJ/MTL, PLY), JSON
// scene files, the committed example, and the errors bad input must give.
#include "core/ImageIo.h"
#include "scene/JsonLocator.h"
#include "scene/SceneLoader.h"

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

namespace {

fs::path tempDir() {
    static const fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("bounce-scene-loader-test-" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

fs::path writeFile(const std::string& name, const std::string& text) {
    const fs::path p = tempDir() / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string base64(const std::string& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8) | uint8_t(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
    }
    if (i + 1 == bytes.size()) {
        const uint32_t v = uint8_t(bytes[i]) << 16;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == bytes.size()) {
        const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8);
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

// Routes spdlog's default logger into a buffer for the lifetime of the object.
class LogCapture {
public:
    LogCapture() : m_sink(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(128)), m_previous(spdlog::default_logger()) {
        spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", m_sink));
    }
    ~LogCapture() { spdlog::set_default_logger(m_previous); }
    std::string text() const {
        std::string out;
        for (const std::string& line : m_sink->last_formatted()) out += line;
        return out;
    }

private:
    std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> m_sink;
    std::shared_ptr<spdlog::logger> m_previous;
};

const Object* findObject(const Scene& s, const std::string& name) {
    for (const Object& o : s.objects)
        if (o.name == name) return &o;
    return nullptr;
}

const Material* findMaterial(const Scene& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

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

namespace {
const char* kCubeObj =
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 1 2 6 5\nf 4 8 7 3\n";
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

TEST(JsonScene, PlacesModelsLightsCameraAndAnimations) {
    writeFile("json/models/cube.obj", kCubeObj);
    const fs::path p = writeFile("json/scene.json", R"({
  "name": "test",
  "frameRate": 24,
  "settings": {"vpl.count": 128, "vct.enabled": true, "rsm.mode": "splat"},
  "materials": {"gold": {"baseColor": [0.9, 0.7, 0.2], "metallic": 1, "roughness": 0.3}},
  "objects": [
    {"name": "box", "model": "models/cube.obj", "material": "gold",
     "transform": {"translation": [1, 0.5, 0], "rotation": {"axis": [0, 1, 0], "degrees": 90}, "scale": [2, 1, 1]}},
    {"name": "mover", "model": "models/cube.obj", "material": {"baseColor": 0.5, "emission": [1, 2, 3]},
     "animation": {"interpolation": "catmull-rom", "loop": false,
                   "keys": [{"time": 0, "translation": [0, 0, 0]}, {"time": 2, "translation": [4, 0, 0]}]}}
  ],
  "lights": [
    {"name": "lamp", "type": "spot", "position": [0, 3, 0], "target": [0, 0, 0], "intensity": [1, 2, 3],
     "cutoffDegrees": 30, "falloffExponent": 2},
    {"name": "panel", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 0.5], "radiance": 4}
  ],
  "camera": {"position": [0, 1, 5], "target": [0, 1, 0], "fovDegrees": 50, "near": 0.05, "far": 80,
             "animation": {"keys": [{"time": 0}, {"time": 1, "translation": [0, 1, 0]}]}}
})");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->name, "test");
    EXPECT_EQ(scene->source, p.string());
    EXPECT_FLOAT_EQ(scene->frameRate, 24.0f);
    EXPECT_EQ(scene->settings.at("vpl.count"), "128");
    EXPECT_EQ(scene->settings.at("vct.enabled"), "true");
    EXPECT_EQ(scene->settings.at("rsm.mode"), "splat");

    const Object* box = findObject(*scene, "box");
    const Object* mover = findObject(*scene, "mover");
    ASSERT_TRUE(box && mover);
    EXPECT_EQ(scene->materials[box->material].name, "gold");
    EXPECT_FLOAT_EQ(scene->materials[box->material].metallic, 1.0f);
    EXPECT_EQ(scene->materials[mover->material].emission, glm::vec3(1, 2, 3));
    // Scale 2 along x, then 90 degrees about y puts that length along z; translated by (1, 0.5, 0).
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& q : scene->meshes[box->mesh].positions) {
        const glm::vec3 w(box->worldFromObject(0.0f) * glm::vec4(q, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    EXPECT_NEAR(hi.z - lo.z, 2.0f, 1e-5f);
    EXPECT_NEAR(hi.x - lo.x, 1.0f, 1e-5f);
    EXPECT_NEAR(0.5f * (lo.x + hi.x), 1.0f, 1e-5f);
    EXPECT_NEAR(lo.y, 0.0f, 1e-5f);

    EXPECT_FALSE(box->isDynamic());
    ASSERT_TRUE(mover->isDynamic());
    EXPECT_EQ(mover->animation.interpolation, Interpolation::CatmullRom);
    EXPECT_FALSE(mover->animation.loop);
    EXPECT_NEAR(mover->worldFromObject(1.0f)[3].x, 2.0f, 1e-5f);  // two keys: Catmull-Rom is linear between them
    EXPECT_NEAR(mover->worldFromObject(5.0f)[3].x, 4.0f, 1e-5f);  // held after the end (no loop)

    ASSERT_EQ(scene->lights.size(), 2u);
    const Light& lamp = scene->lights[0];
    EXPECT_EQ(lamp.type, LightType::Spot);
    EXPECT_NEAR(lamp.direction.y, -1.0f, 1e-6f);
    EXPECT_NEAR(lamp.cutoffAngle, glm::radians(30.0f), 1e-6f);
    EXPECT_EQ(lamp.intensity, glm::vec3(1, 2, 3));
    const Light& panel = scene->lights[1];
    EXPECT_NEAR(panel.area(), 0.5f, 1e-6f);
    EXPECT_NEAR(panel.areaNormal().y, -1.0f, 1e-6f);  // cross(+x, +z) = -y

    EXPECT_NEAR(scene->camera.verticalFov, glm::radians(50.0f), 1e-6f);
    // Looping by default: halfway through the key range the camera has risen by half of 1 m.
    EXPECT_NEAR(scene->camera.at(0.5f).position.y, 1.5f, 1e-5f);
}

TEST(JsonScene, CommittedExampleLoads) {
    const fs::path example = fs::path(BOUNCE_SOURCE_DIR) / "scenes" / "example.json";
    Expected<Scene> scene = loadScene(example.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->name, "example");
    EXPECT_EQ(scene->objects.size(), 3u);
    EXPECT_EQ(scene->lights.size(), 4u);  // one of each type
    EXPECT_EQ(scene->triangleCount(), 2u + 12u + 12u);
    EXPECT_TRUE(findObject(*scene, "spinner")->isDynamic());
    EXPECT_FALSE(findObject(*scene, "crate")->isDynamic());
    // The crate keeps its MTL colour; the spinner's is overridden.
    EXPECT_NEAR(scene->materials[findObject(*scene, "crate")->material].baseColor.b, 0.7f, 1e-6f);
    EXPECT_EQ(scene->materials[findObject(*scene, "spinner")->material].name, "orange");
    const Light& key = scene->lights[0];
    ASSERT_TRUE(key.isDynamic());
    EXPECT_GT(glm::length(key.at(1.0f).position - key.at(0.0f).position), 0.5f);  // moves on its loop
    EXPECT_EQ(scene->settings.at("rsm.vplGrid"), "16");
}

TEST(JsonScene, MalformedJsonReportsLineAndColumn) {
    const fs::path p = writeFile("bad/syntax.json", "{\n  \"name\": \"x\",\n  \"objects\": [\n    {\"model\": \"a.obj\"\n  ]\n}\n");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_FALSE(scene.ok());
    EXPECT_TRUE(contains(scene.error().message, "syntax.json:5:")) << scene.error().message;
}

TEST(JsonScene, UnknownKeyNamesItAndTheKnownKeys) {
    writeFile("bad/models/cube.obj", kCubeObj);
    const fs::path p = writeFile("bad/typo.json", "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                                                  "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
                                                  "  \"lihgts\": []\n}\n");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_FALSE(scene.ok());
    const std::string& msg = scene.error().message;
    EXPECT_TRUE(contains(msg, "typo.json:4:")) << msg;
    EXPECT_TRUE(contains(msg, "\"lihgts\"")) << msg;
    EXPECT_TRUE(contains(msg, "lights")) << msg;
    EXPECT_TRUE(contains(msg, "camera")) << msg;

    const fs::path q = writeFile("bad/lightkey.json", "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                                                      "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
                                                      "  \"lights\": [\n    {\"name\": \"k\", \"type\": \"point\",\n"
                                                      "     \"position\": [0, 1, 0], \"intensity\": 1, \"radius\": 2}\n  ]\n}\n");
    Expected<Scene> light = loadScene(q.string());
    ASSERT_FALSE(light.ok());
    EXPECT_TRUE(contains(light.error().message, "lightkey.json:6:")) << light.error().message;
    EXPECT_TRUE(contains(light.error().message, "light 'k'")) << light.error().message;
    EXPECT_TRUE(contains(light.error().message, "intensity")) << light.error().message;
}

TEST(JsonScene, NonFiniteLightValues) {
    writeFile("nan/models/cube.obj", kCubeObj);
    const std::string head = "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                             "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n  \"lights\": [\n";
    // JSON has no NaN literal: it is a syntax error at its line.
    const fs::path literal = writeFile("nan/literal.json", head + "    {\"name\": \"k\", \"type\": \"point\", \"position\": [0, 1, 0],\n"
                                                                  "     \"intensity\": NaN}\n  ]\n}\n");
    Expected<Scene> a = loadScene(literal.string());
    ASSERT_FALSE(a.ok());
    EXPECT_TRUE(contains(a.error().message, "literal.json:6:")) << a.error().message;
    // An overflowing number parses to infinity and is rejected where it stands.
    const fs::path overflow = writeFile("nan/overflow.json", head + "    {\"name\": \"k\", \"type\": \"point\", \"position\": [0, 1, 0],\n"
                                                                    "     \"intensity\": [1, 1e999, 1]}\n  ]\n}\n");
    Expected<Scene> b = loadScene(overflow.string());
    ASSERT_FALSE(b.ok());
    EXPECT_TRUE(contains(b.error().message, "overflow.json:6:")) << b.error().message;
    EXPECT_TRUE(contains(b.error().message, "finite")) << b.error().message;
}

TEST(JsonScene, MissingFilesAndReferences) {
    Expected<Scene> none = loadScene((tempDir() / "absent.json").string());
    ASSERT_FALSE(none.ok());
    EXPECT_TRUE(contains(none.error().message, "absent.json")) << none.error().message;

    const fs::path p = writeFile("refs/scene.json", "{\n  \"objects\": [\n    {\"name\": \"ghost\", \"model\": \"models/ghost.obj\"}\n  ],\n"
                                                    "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    Expected<Scene> model = loadScene(p.string());
    ASSERT_FALSE(model.ok());
    EXPECT_TRUE(contains(model.error().message, "scene.json:3:")) << model.error().message;
    EXPECT_TRUE(contains(model.error().message, "ghost.obj")) << model.error().message;

    writeFile("refs/models/cube.obj", kCubeObj);
    const fs::path m = writeFile("refs/material.json", "{\n  \"objects\": [\n    {\"model\": \"models/cube.obj\", \"material\": \"steel\"}\n  ],\n"
                                                       "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    Expected<Scene> material = loadScene(m.string());
    ASSERT_FALSE(material.ok());
    EXPECT_TRUE(contains(material.error().message, "\"steel\"")) << material.error().message;

    // A missing texture is a warning, not an error.
    const fs::path t = writeFile("refs/texture.json", "{\n  \"materials\": {\"wood\": {\"baseColor\": 0.4, \"baseColorTexture\": \"wood.png\"}},\n"
                                                      "  \"objects\": [{\"model\": \"models/cube.obj\", \"material\": \"wood\"}],\n"
                                                      "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    LogCapture log;
    Expected<Scene> textured = loadScene(t.string());
    ASSERT_TRUE(textured.ok()) << textured.error().message;
    EXPECT_EQ(textured->materials[0].baseColorTexture, -1);
    EXPECT_TRUE(contains(log.text(), "wood.png")) << log.text();

    // An emission texture loads like a base-colour texture; missing, it is a warning too.
    ASSERT_TRUE(writeImage(tempDir() / "refs/glow.exr", Image(2, 1, glm::vec3(0.5f))).ok());
    const fs::path e = writeFile("refs/emission.json", "{\n  \"materials\": {\"lamp\": {\"emission\": 2, \"emissionTexture\": \"glow.exr\"},\n"
                                                       "    \"dud\": {\"emission\": 2, \"emissionTexture\": \"none.png\"}},\n"
                                                       "  \"objects\": [{\"model\": \"models/cube.obj\", \"material\": \"lamp\"}],\n"
                                                       "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    Expected<Scene> glowing = loadScene(e.string());
    ASSERT_TRUE(glowing.ok()) << glowing.error().message;
    const Material* lamp = findMaterial(*glowing, "lamp");
    const Material* dud = findMaterial(*glowing, "dud");
    ASSERT_TRUE(lamp && dud);
    ASSERT_GE(lamp->emissionTexture, 0);
    EXPECT_EQ(glowing->textures[static_cast<size_t>(lamp->emissionTexture)].image.at(1, 0), glm::vec3(0.5f));
    EXPECT_EQ(dud->emissionTexture, -1);
    EXPECT_TRUE(contains(log.text(), "none.png")) << log.text();
}

TEST(JsonScene, LeakRegions) {
    writeFile("leak/models/cube.obj", kCubeObj);
    const std::string head = "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                             "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n  \"leakRegions\": ";
    const auto load = [&](const std::string& name, const std::string& regions) {
        return loadScene(writeFile("leak/" + name, head + regions + "\n}\n").string());
    };
    Expected<Scene> none = load("none.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n"
                                             "   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}");
    ASSERT_TRUE(none.ok()) << none.error().message;
    ASSERT_TRUE(none->leakRegions.has_value());
    EXPECT_EQ(none->leakRegions->darkMin, glm::vec3(0.0f));
    EXPECT_EQ(none->leakRegions->darkMax, glm::vec3(1.0f));
    EXPECT_EQ(none->leakRegions->litMin, glm::vec3(-1.0f));
    EXPECT_EQ(none->leakRegions->litMax, glm::vec3(0.0f, 1.0f, 1.0f));  // touching at x = 0: open boxes share no point
    Expected<Scene> without = loadScene(writeFile("leak/without.json", head + "null\n}\n").string());
    ASSERT_FALSE(without.ok());  // null is not an object
    EXPECT_TRUE(contains(without.error().message, "without.json:4:")) << without.error().message;

    struct Bad {
        const char* name;
        std::string regions;
        std::vector<std::string> says;  // the message names the file and line, the key and the problem
    };
    const std::vector<Bad> bad = {
        {"missing-lit.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]}}", {"missing-lit.json:4:", "\"lit\""}},
        {"unknown.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]},\n   \"grey\": {}}",
         {"unknown.json:6:", "\"grey\"", "dark, lit"}},
        {"box-key.json", "{\"dark\": {\"min\": [0, 0, 0], \"maximum\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"box-key.json:4:", "\"maximum\"", "leak region 'dark'", "max, min"}},
        {"empty.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1],\n           \"max\": [0, 1, -1]}}",
         {"empty.json:6:", "leakRegions/lit/max", "not above min -1 on z"}},
        {"short.json", "{\"dark\": {\"min\": [0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"short.json:4:", "leakRegions/dark/min", "3 numbers"}},
        {"text.json", "{\"dark\": {\"min\": [0, 0, \"0\"], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"text.json:4:", "leakRegions/dark/min/2", "the string \"0\""}},
        {"infinite.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1e999, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"infinite.json:4:", "not finite"}},  // the JSON parser refuses the overflow at its line
        {"overlap.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0.5, 1, 1]}}",
         {"overlap.json:5:", "overlap"}},
    };
    for (const Bad& b : bad) {
        Expected<Scene> scene = load(b.name, b.regions);
        ASSERT_FALSE(scene.ok()) << b.name;
        for (const std::string& part : b.says) EXPECT_TRUE(contains(scene.error().message, part)) << b.name << ": " << scene.error().message;
        EXPECT_EQ(scene.error().message.find('\n'), std::string::npos) << b.name;
    }
}

TEST(JsonScene, AreaLightTexturesAndTwoSided) {
    writeFile("arealight/models/cube.obj", kCubeObj);
    // A PNG is decoded from sRGB: full red and green stay 1 and 0 exactly, 8-bit 128 is 0.2158 (sRGB EOTF).
    Image still(2, 1);
    still.at(0, 0) = glm::vec3(1.0f, 0.0f, 0.0f);
    still.at(1, 0) = glm::vec3(0.0f, 1.0f, 0.0f);
    ASSERT_TRUE(writeImage(tempDir() / "arealight/still.png", still, ToneMap{0.0f, ToneCurve::Clamp}).ok());
    ASSERT_TRUE(writeImage(tempDir() / "arealight/f0.exr", Image(4, 2, glm::vec3(0.25f))).ok());
    ASSERT_TRUE(writeImage(tempDir() / "arealight/f1.exr", Image(4, 2, glm::vec3(3.0f))).ok());
    const fs::path p = writeFile("arealight/scene.json", R"({
  "objects": [{"model": "models/cube.obj"}],
  "camera": {"position": [0, 0, 5], "target": [0, 0, 0]},
  "lights": [
    {"name": "still", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1],
     "radiance": 2, "twoSided": true, "texture": "still.png"},
    {"name": "video", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1],
     "radiance": 2, "texture": {"frames": ["f0.exr", "f1.exr"], "frameRate": 12}},
    {"name": "square", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1],
     "radiance": 2, "texture": {"pattern": "bouncing-square", "resolution": 32, "size": 0.5,
                                "velocity": [0.1, -0.2], "start": [0.5, 0.25]}},
    {"name": "plain", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1], "radiance": 2}
  ]
})");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.size(), 4u);
    const Light& still0 = scene->lights[0];
    EXPECT_TRUE(still0.twoSided);
    ASSERT_EQ(still0.texture.kind, AreaTexture::Kind::Images);
    ASSERT_EQ(still0.texture.frames.size(), 1u);
    const Image& png = scene->textures[still0.texture.frames[0]].image;
    ASSERT_EQ(png.width(), 2);
    EXPECT_EQ(png.at(0, 0), glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(png.at(1, 0), glm::vec3(0.0f, 1.0f, 0.0f));

    const Light& video = scene->lights[1];
    EXPECT_FALSE(video.twoSided);
    ASSERT_EQ(video.texture.frames.size(), 2u);
    EXPECT_FLOAT_EQ(video.texture.frameRate, 12.0f);
    EXPECT_EQ(scene->textures[video.texture.frames[0]].image.at(3, 1), glm::vec3(0.25f));  // EXR is linear as stored
    EXPECT_EQ(scene->textures[video.texture.frames[1]].image.at(0, 0), glm::vec3(3.0f));

    const AreaTexture& sq = scene->lights[2].texture;
    EXPECT_EQ(sq.kind, AreaTexture::Kind::BouncingSquare);
    EXPECT_EQ(sq.resolution, 32);
    EXPECT_FLOAT_EQ(sq.squareSize, 0.5f);
    EXPECT_EQ(sq.squareVelocity, glm::vec2(0.1f, -0.2f));
    EXPECT_EQ(sq.squareStart, glm::vec2(0.5f, 0.25f));

    EXPECT_FALSE(scene->lights[3].texture.textured());
    EXPECT_FALSE(scene->lights[3].twoSided);
}

TEST(JsonScene, AreaLightTextureBadInput) {
    writeFile("areabad/models/cube.obj", kCubeObj);
    ASSERT_TRUE(writeImage(tempDir() / "areabad/small.exr", Image(2, 2, glm::vec3(1.0f))).ok());
    ASSERT_TRUE(writeImage(tempDir() / "areabad/large.exr", Image(4, 2, glm::vec3(1.0f))).ok());
    Image negative(2, 2, glm::vec3(1.0f));
    negative.at(1, 1) = glm::vec3(-1.0f);
    ASSERT_TRUE(writeImage(tempDir() / "areabad/negative.exr", negative).ok());
    writeFile("areabad/garbage.png", "this is not a PNG file");
    int n = 0;
    // The light's extra keys are on line 5 of the file: every error names the file, that line and `expect`.
    const auto check = [&](const std::string& type, const std::string& extra, const std::string& expect) {
        SCOPED_TRACE(extra);
        const std::string name = "case" + std::to_string(n++) + ".json";
        const fs::path p = writeFile("areabad/" + name,
                                     "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                                     "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
                                     "  \"lights\": [{\"name\": \"screen\", \"type\": \"" + type + "\",\n" +
                                         "    " + extra + ",\n"
                                         "    \"position\": [0, 2, 0], \"edgeU\": [1, 0, 0], \"edgeV\": [0, 0, 1], "
                                         "\"radiance\": 1, \"intensity\": 1}]\n}\n");
        Expected<Scene> scene = loadScene(p.string());
        ASSERT_FALSE(scene.ok());
        const std::string& msg = scene.error().message;
        EXPECT_TRUE(contains(msg, name + ":5:")) << msg;
        EXPECT_TRUE(contains(msg, expect)) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    };
    // `check` gives a non-area light area keys too: "texture" and "twoSided" must be reported before the
    // unknown-key check would name the others. `area` cases are well-formed area lights but for `extra`.
    const auto area = [&](const std::string& extra, const std::string& expect) {
        SCOPED_TRACE(extra);
        const std::string name = "case" + std::to_string(n++) + ".json";
        const fs::path p = writeFile("areabad/" + name,
                                     "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                                     "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
                                     "  \"lights\": [{\"name\": \"screen\", \"type\": \"area\",\n" +
                                         ("    " + extra + ",\n") +
                                         "    \"position\": [0, 2, 0], \"edgeU\": [1, 0, 0], \"edgeV\": [0, 0, 1], "
                                         "\"radiance\": 1}]\n}\n");
        Expected<Scene> scene = loadScene(p.string());
        ASSERT_FALSE(scene.ok());
        const std::string& msg = scene.error().message;
        EXPECT_TRUE(contains(msg, name + ":5:")) << msg;
        EXPECT_TRUE(contains(msg, expect)) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    };
    area(R"("texture": "absent.png")", "absent.png: file not found");
    area(R"("texture": "garbage.png")", "garbage.png");
    area(R"("texture": "negative.exr")", "negative texel");
    area(R"("texture": 3)", "must be an image path");
    area(R"("texture": {"frames": ["small.exr", "large.exr"]})", "frame 1 is 4x2, frame 0 is 2x2");
    area(R"("texture": {"frames": []})", "non-empty array");
    area(R"("texture": {"frames": ["small.exr", "absent.exr"]})", "absent.exr: file not found");
    area(R"("texture": {"frames": ["small.exr"], "frameRate": 0})", "frame rate must be positive");
    area(R"("texture": {"frames": ["small.exr"], "frameRate": -24})", "outside");
    area(R"("texture": {"frames": ["small.exr"], "fps": 24})", "unknown key \"fps\"");
    area(R"("texture": {"frames": ["small.exr"], "pattern": "bouncing-square"})", "exactly one of");
    area(R"("texture": {"pattern": "checkerboard"})", "unknown texture pattern \"checkerboard\"");
    area(R"("texture": {"pattern": "bouncing-square", "resolution": 0})", "resolution must be an integer");
    area(R"("texture": {"pattern": "bouncing-square", "resolution": 2.5})", "resolution must be an integer");
    area(R"("texture": {"pattern": "bouncing-square", "resolution": 100000})", "resolution must be an integer");
    area(R"("texture": {"pattern": "bouncing-square", "size": 0})", "size must be in (0, 1]");
    area(R"("texture": {"pattern": "bouncing-square", "size": 1.5})", "outside [0, 1]");
    area(R"("texture": {"pattern": "bouncing-square", "velocity": [1]})", "array of 2 numbers");
    area(R"("texture": {"pattern": "bouncing-square", "start": [0.5, 2]})", "outside [0, 1]");
    area(R"("texture": {"pattern": "bouncing-square", "speed": 1})", "unknown key \"speed\"");
    area(R"("twoSided": "yes")", "expected true or false");
    check("point", R"("texture": "small.exr")", "applies to area lights only");
    check("spot", R"("twoSided": true)", "applies to area lights only");
}

TEST(JsonLocator, FindsLinesOfKeysAndElements) {
    const std::string text = "{\n  \"a\": 1,\n  \"b\": [\n    {\"c\": \"x\"},\n    {\"d\": 2}\n  ],\n  \"e/f\": {}\n}\n";
    const JsonLocator locator(text);
    EXPECT_EQ(locator.line(""), 1);
    EXPECT_EQ(locator.line("/a"), 2);
    EXPECT_EQ(locator.line("/b"), 3);
    EXPECT_EQ(locator.line("/b/0/c"), 4);
    EXPECT_EQ(locator.line("/b/1"), 5);
    EXPECT_EQ(locator.line("/b/1/d"), 5);
    EXPECT_EQ(locator.line("/e~1f"), 7);
    EXPECT_EQ(locator.line("/b/1/zzz"), 5);  // nearest ancestor
    EXPECT_EQ(JsonLocator::lineColumn(text, 0), std::make_pair(1, 1));
    EXPECT_EQ(JsonLocator::lineColumn(text, 4), std::make_pair(2, 3));
}
