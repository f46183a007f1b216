// glTF materials as artists ship them (issue 30): alpha masks (MASK, BLEND as MASK at 0.5), normal
// maps with tangents, metallic-roughness textures, unsupported-extension warnings; the same keys in
// JSON scene materials; and the reference path tracer's intersection filter (a masked-out surface is
// absent for every ray, an opaque one is not).
#include "core/ImageIo.h"
#include "reference/PathTracer.h"
#include "scene/MeshBuilder.h"
#include "scene/SceneLoader.h"
#include "SceneFileTestSupport.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>
#include <stb/stb_image_write.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace bounce;
using namespace bounce::scenefiletest;

namespace {

void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
}

// An 8-bit PNG of `channels` channels from bytes, row 0 first.
std::string png(int w, int h, int channels, const std::vector<unsigned char>& bytes) {
    std::string out;
    EXPECT_TRUE(stbi_write_png_to_func(appendBytes, &out, w, h, channels, bytes.data(), w * channels));
    return out;
}

// One quad (two triangles) in the xz plane facing +y with uvs, and three materials' worth of options:
// `material` is the glTF material object's text.
std::string quadGltf(const std::string& material, const std::string& extra = "") {
    // 2x2 RGBA texture: alpha 255 on the left column, 0 on the right; RGB (200, 100, 50).
    const std::string rgba = png(2, 2, 4, {200, 100, 50, 255, 200, 100, 50, 0, 200, 100, 50, 255, 200, 100, 50, 0});
    // 1x1 normal map tilted toward +x (linear 0.75, 0.5, 0.93) and a metallic-roughness texel (G 0.5, B 0.25).
    const std::string normal = png(1, 1, 3, {191, 128, 237});
    const std::string mr = png(1, 1, 3, {0, 128, 64});
    std::string buffer;
    const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 0, -1, 0, 0, -1};
    const float normals[12] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
    const float uvs[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    buffer.append(reinterpret_cast<const char*>(positions), sizeof positions);
    buffer.append(reinterpret_cast<const char*>(normals), sizeof normals);
    buffer.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
    buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
    return R"({
  "asset": {"version": "2.0"},)" + extra + R"(
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"name": "quad", "mesh": 0}],
  "meshes": [{"name": "quadMesh", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "materials": [)" + material + R"(],
  "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
  "images": [{"uri": "data:image/png;base64,)" + base64(rgba) + R"("}, {"uri": "data:image/png;base64,)" +
           base64(normal) + R"("}, {"uri": "data:image/png;base64,)" + base64(mr) + R"("}],
  "buffers": [{"byteLength": )" + std::to_string(buffer.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
           base64(buffer) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, -1], "max": [1, 0, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
})";
}

}  // namespace

TEST(MaterialMaps, GltfMaskNormalAndMetallicRoughnessTextures) {
    const fs::path path = writeFile("mask.gltf", quadGltf(R"({"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.3,
        "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.8], "baseColorTexture": {"index": 0},
                                 "metallicFactor": 1, "roughnessFactor": 1, "metallicRoughnessTexture": {"index": 2}},
        "normalTexture": {"index": 1, "scale": 0.5}})"));
    Expected<Scene> scene = loadScene(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& m = scene->materials[scene->objects[0].material];
    EXPECT_NEAR(m.alphaCutoff, 0.3f, 1e-6f);
    EXPECT_NEAR(m.alpha, 0.8f, 1e-6f);
    EXPECT_TRUE(m.masked());
    ASSERT_GE(m.alphaTexture, 0);
    const Image& alpha = scene->textures[static_cast<size_t>(m.alphaTexture)].image;
    EXPECT_FLOAT_EQ(alpha.at(0, 0).r, 1.0f);  // linear alpha, left column opaque
    EXPECT_FLOAT_EQ(alpha.at(1, 0).r, 0.0f);
    ASSERT_GE(m.baseColorTexture, 0);         // the colour itself stays sRGB-decoded
    EXPECT_NEAR(scene->textures[static_cast<size_t>(m.baseColorTexture)].image.at(0, 0).r, 0.578f, 0.002f);
    ASSERT_GE(m.normalTexture, 0);
    EXPECT_NEAR(scene->textures[static_cast<size_t>(m.normalTexture)].image.at(0, 0).r, 191.0f / 255.0f, 1e-6f);  // linear
    EXPECT_NEAR(m.normalScale, 0.5f, 1e-6f);
    ASSERT_GE(m.metallicRoughnessTexture, 0);
    EXPECT_NEAR(scene->textures[static_cast<size_t>(m.metallicRoughnessTexture)].image.at(0, 0).g, 128.0f / 255.0f, 1e-6f);
    // Tangents from the uvs: u runs +x, v runs +z (uv (0, 0) at z = -1), so the bitangent (up the image,
    // -v) is -z: w cross(+y, +x) = w (-z), w = +1.
    const Mesh& mesh = scene->meshes[scene->objects[0].mesh];
    ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
    for (const glm::vec4& t : mesh.tangents) {
        EXPECT_NEAR(t.x, 1.0f, 1e-5f);
        EXPECT_NEAR(t.w, 1.0f, 0.0f);
    }
}

TEST(MaterialMaps, GltfBlendIsMaskedAtHalfWithAWarningAndUnknownExtensionsWarn) {
    LogCapture log;
    const fs::path path = writeFile("blend.gltf", quadGltf(R"({"name": "glass", "alphaMode": "BLEND",
        "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})",
                                                           R"( "extensionsUsed": ["KHR_materials_transmission", "KHR_lights_punctual"],)"));
    Expected<Scene> scene = loadScene(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& m = scene->materials[scene->objects[0].material];
    EXPECT_NEAR(m.alphaCutoff, 0.5f, 0.0f);
    EXPECT_TRUE(m.masked());
    const std::string text = log.text();
    EXPECT_NE(text.find("alphaMode BLEND is rendered as MASK with alphaCutoff 0.5"), std::string::npos) << text;
    EXPECT_NE(text.find("glTF extension KHR_materials_transmission is not supported"), std::string::npos) << text;
    EXPECT_EQ(text.find("KHR_lights_punctual is not supported"), std::string::npos) << text;
}

TEST(MaterialMaps, GltfOpaqueIgnoresTheTexturesAlpha) {
    const fs::path path = writeFile("opaque.gltf", quadGltf(R"({"name": "wall", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})"));
    Expected<Scene> scene = loadScene(path.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_FALSE(scene->materials[scene->objects[0].material].masked());
}

TEST(MaterialMaps, JsonMaterialsTakeTheSameKeys) {
    std::vector<unsigned char> grey = {0, 255, 255, 0};  // a 2x2 grey mask without alpha: its first channel
    std::ofstream(tempDir() / "mask.png", std::ios::binary) << png(2, 2, 1, grey);
    std::ofstream(tempDir() / "flat.png", std::ios::binary) << png(1, 1, 3, {128, 128, 255});
    writeFile("plane.obj", "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
    const auto scene = [&](const std::string& material) {
        return writeFile("m.json", R"({"materials": {"m": )" + material + R"(},
  "objects": [{"model": "plane.obj", "material": "m"}],
  "lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": 1}],
  "camera": {"position": [0, 1, 1], "target": [0, 0, 0]}})");
    };
    Expected<Scene> s = loadScene(scene(R"({"alphaMode": "mask", "alphaCutoff": 0.25, "alphaTexture": "mask.png",
        "normalTexture": "flat.png", "normalScale": 2, "metallicRoughnessTexture": "flat.png"})").string());
    ASSERT_TRUE(s.ok()) << s.error().message;
    const Material& m = s->materials[s->objects[0].material];
    EXPECT_NEAR(m.alphaCutoff, 0.25f, 0.0f);
    ASSERT_GE(m.alphaTexture, 0);
    EXPECT_FLOAT_EQ(s->textures[static_cast<size_t>(m.alphaTexture)].image.at(1, 0).r, 1.0f);
    EXPECT_FLOAT_EQ(s->textures[static_cast<size_t>(m.alphaTexture)].image.at(0, 0).r, 0.0f);
    EXPECT_GE(m.normalTexture, 0);
    EXPECT_NEAR(m.normalScale, 2.0f, 0.0f);
    EXPECT_GE(m.metallicRoughnessTexture, 0);
    EXPECT_FALSE(s->meshes[s->objects[0].mesh].tangents.empty());

    Expected<Scene> bad = loadScene(scene(R"({"alphaMode": "cutout"})").string());
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("alphaMode \"cutout\": expected"), std::string::npos) << bad.error().message;
    bad = loadScene(scene(R"({"alphaCutoff": 0.5})").string());
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("alphaCutoff needs \"alphaMode\""), std::string::npos) << bad.error().message;
    bad = loadScene(scene(R"({"alphaMode": "mask", "alphaCutoff": 1.5})").string());
    EXPECT_FALSE(bad.ok());
}

namespace {

enum class Card { Absent, MaskedOut, Opaque };

// cornell-box with a horizontal card between the spot and the floor (as MaterialMasksGpuTest).
Scene cornellWithCard(Card card) {
    auto loaded = loadScene("cornell-box");
    EXPECT_TRUE(loaded.ok());
    Scene s = std::move(*loaded);
    if (card == Card::Absent) return s;
    MeshBuilder b("card");
    b.quad({0.06f, 0.40f, 0.06f}, {0.50f, 0.40f, 0.06f}, {0.50f, 0.40f, 0.50f}, {0.06f, 0.40f, 0.50f}, {0, -1, 0});
    Material m;
    m.name = "card";
    m.baseColor = glm::vec3(0.7f);
    m.twoSided = true;
    m.alphaTexture = static_cast<int>(s.textures.size());
    s.textures.push_back({"zero-coverage", Image(4, 4, glm::vec3(0.0f))});
    m.alphaCutoff = card == Card::MaskedOut ? 0.5f : 0.0f;
    s.objects.push_back({});
    s.objects.back().name = "card";
    s.objects.back().mesh = static_cast<uint32_t>(s.meshes.size());
    s.objects.back().material = static_cast<uint32_t>(s.materials.size());
    s.meshes.push_back(b.take());
    s.materials.push_back(m);
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

double meanOf(const Image& img) {
    double sum = 0.0;
    for (const glm::vec3& p : img.pixels()) sum += (p.r + p.g + p.b) / 3.0;
    return sum / static_cast<double>(img.pixelCount());
}

}  // namespace

TEST(MaterialMaps, PathTracerRaysPassMaskedOutTexels) {
    // Same seed and samples: with the filter rejecting every hit on the card, each path is the same as
    // without the card, so the images are equal (not merely within noise); the opaque card darkens.
    PathTracerSettings pts;
    pts.width = pts.height = 32;
    pts.samplesPerPixel = 16;
    pts.bounces = 2;
    double means[3];
    for (int k = 0; k < 3; ++k) {
        auto tracer = PathTracer::create(cornellWithCard(static_cast<Card>(k)), pts);
        ASSERT_TRUE(tracer.ok()) << tracer.error().message;
        means[k] = meanOf(tracer->render().radiance);
    }
    EXPECT_NEAR(means[1] / means[0], 1.0, 1e-6);
    EXPECT_LT(means[2] / means[0], 0.7);  // the opaque card shades most of the floor and walls
}
