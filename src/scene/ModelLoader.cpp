#include "scene/ModelLoader.h"

#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/ToneMap.h"
#include "scene/ObjNormals.h"
#include "scene/PlyCheck.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <string_view>
#include <optional>
#include <cstdint>
#include <utility>

namespace bounce {

namespace fs = std::filesystem;

namespace {

// KHR_lights_punctual gives candela (point, spot) and lux (directional). bounce's lights are radiometric;
// 683 lm/W is the luminous efficacy that defines the candela (555 nm), so 1 cd = 1/683 W/sr and
// 1 lx = 1/683 W/m^2 (docs/scene.md "Model files").
constexpr float kLumensPerWatt = 683.0f;
// glTF's dielectric reflectance at normal incidence (glTF 2.0 metallic-roughness model).
constexpr float kGltfDielectricF0 = 0.04f;
// glTF 2.0 material.alphaCutoff's default (section 5.19); also the cutoff bounce uses for BLEND.
constexpr float kGltfDefaultAlphaCutoff = 0.5f;
// Default sun for model files without lights: irradiance on a surface facing it, about 1 W/(m^2 sr) of
// radiance off an 0.8 albedo surface facing it (0.8 * 4 / pi), well exposed with ACES at 0 EV.
constexpr glm::vec3 kDefaultSunIrradiance{4.0f};  // W/m^2
const glm::vec3 kDefaultSunDirection = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));

enum class Format { Gltf, Obj, Ply };

// assimp's name for the mesh and node of OBJ faces outside any `o`/`g` statement (ObjFileParser's
// DEFAULT_OBJNAME). Nobody wrote it: messages and object names use the file's name instead.
constexpr std::string_view kAssimpDefaultObject = "defaultobject";

// The name a user recognises for an assimp mesh or node name: the file's when assimp made it up.
std::string userName(const aiString& name, const fs::path& path, bool stem) {
    if (name.length == 0 || std::string_view(name.C_Str()) == kAssimpDefaultObject)
        return stem ? path.stem().string() : path.filename().string();
    return name.C_Str();
}

std::string lowerExtension(const fs::path& p) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
    // assimp matrices are row-major (a1..a4 is the first row); glm is column-major.
    return glm::transpose(glm::make_mat4(&m.a1));
}

glm::vec3 toGlm(const aiVector3D& v) { return {v.x, v.y, v.z}; }
glm::vec3 toGlm(const aiColor3D& c) { return {c.r, c.g, c.b}; }

glm::mat4 globalTransform(const aiNode* node) {
    glm::mat4 m(1.0f);
    for (; node; node = node->mParent) m = toGlm(node->mTransformation) * m;
    return m;
}

// Decodes an 8-bit sRGB-encoded image (base colour) to linear RGB.
Image decodeSrgb8(const unsigned char* pixels, int width, int height, int channels) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = pixels + (static_cast<size_t>(y) * width + x) * channels;
            const auto c = [&](int k) { return srgbDecode(p[std::min(k, channels - 1)] / 255.0f); };
            image.at(x, y) = channels >= 3 ? glm::vec3(c(0), c(1), c(2)) : glm::vec3(c(0));
        }
    return image;
}

// Decodes 8-bit pixels of `channels` channels for `use`: sRGB colour (existing decodeSrgb8), the alpha
// channel replicated to RGB, or linear RGB. Alpha of an image without one is 1 (glTF: opaque).
Image decodeFor(TextureUse use, const unsigned char* pixels, int width, int height, int channels) {
    if (use == TextureUse::SrgbColour) return decodeSrgb8(pixels, width, height, channels);
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = pixels + (static_cast<size_t>(y) * width + x) * channels;
            const auto c = [&](int k) { return p[std::min(k, channels - 1)] / 255.0f; };
            const bool hasAlpha = channels == 2 || channels == 4;
            if (use == TextureUse::Alpha)
                image.at(x, y) = glm::vec3(hasAlpha ? p[channels - 1] / 255.0f : 1.0f);
            else if (use == TextureUse::Coverage)
                image.at(x, y) = glm::vec3(hasAlpha ? p[channels - 1] / 255.0f : c(0));
            else
                image.at(x, y) = channels >= 3 ? glm::vec3(c(0), c(1), c(2)) : glm::vec3(c(0));
        }
    return image;
}

// glTF 2.0 (section 3.7.2.1, "Meshes: Overview"): "When normals are not specified, client
// implementations MUST calculate flat normals". Each triangle's corners get its geometric normal
// (counter-clockwise = front, as glTF defines); a vertex is shared only by triangles of the same normal.
// assimp 5.2's aiProcess_GenNormals cannot do this on glTF's indexed meshes: it writes each face's
// normal into shared vertices, the last face winning (checked against assimp 5.2.5 on an indexed cube).
void makeFlatNormals(Mesh& m) {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec3> normals;
    std::vector<uint32_t> indices;
    indices.reserve(m.indices.size());
    std::map<std::pair<uint32_t, std::array<float, 3>>, uint32_t> shared;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        // A degenerate triangle gets a zero normal; finalizeScene drops it.
        const glm::vec3 n = glm::length(cr) > 0.0f ? glm::normalize(cr) : glm::vec3(0.0f);
        for (int k = 0; k < 3; ++k) {
            const uint32_t source = m.indices[t + k];
            const auto [it, added] = shared.try_emplace({source, {n.x, n.y, n.z}}, static_cast<uint32_t>(positions.size()));
            if (added) {
                positions.push_back(m.positions[source]);
                if (!m.uvs.empty()) uvs.push_back(m.uvs[source]);
                normals.push_back(n);
            }
            indices.push_back(it->second);
        }
    }
    m.positions = std::move(positions);
    m.uvs = std::move(uvs);
    m.normals = std::move(normals);
    m.indices = std::move(indices);
}

// Serves `text` in place of the file `path` and everything else (MTL files, textures) from disk: how
// an OBJ rewritten by addMissingObjNormals reaches assimp with its relative references intact.
class OverlayIoSystem : public Assimp::DefaultIOSystem {
public:
    OverlayIoSystem(std::string path, std::string text) : m_path(std::move(path)), m_text(std::move(text)) {}

    Assimp::IOStream* Open(const char* file, const char* mode) override {
        if (m_path == file || ComparePaths(m_path.c_str(), file))
            return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(m_text.data()), m_text.size());
        return DefaultIOSystem::Open(file, mode);
    }

private:
    std::string m_path, m_text;
};

Expected<Image> decodeEmbedded(const aiTexture* tex, const std::string& what, TextureUse use) {
    if (tex->mHeight == 0) {  // compressed file bytes (PNG, JPEG) of length mWidth
        int w = 0, h = 0, n = 0;
        const auto* bytes = reinterpret_cast<const stbi_uc*>(tex->pcData);
        if (stbi_info_from_memory(bytes, static_cast<int>(tex->mWidth), &w, &h, &n) &&
            (w > kMaxImageSide || h > kMaxImageSide))
            return makeError("{}: embedded image is {}x{}; images may be at most {} pixels per side", what, w, h,
                             kMaxImageSide);
        unsigned char* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(tex->pcData),
                                                    static_cast<int>(tex->mWidth), &w, &h, &n, 0);
        if (!data) return makeError("{}: cannot decode embedded image ({})", what, stbi_failure_reason());
        Image image = decodeFor(use, data, w, h, n);
        stbi_image_free(data);
        return image;
    }
    if (tex->mWidth > static_cast<unsigned>(kMaxImageSide) || tex->mHeight > static_cast<unsigned>(kMaxImageSide))
        return makeError("{}: embedded image is {}x{}; images may be at most {} pixels per side", what, tex->mWidth,
                         tex->mHeight, kMaxImageSide);
    std::vector<unsigned char> rgba(static_cast<size_t>(tex->mWidth) * tex->mHeight * 4);
    for (size_t i = 0; i < static_cast<size_t>(tex->mWidth) * tex->mHeight; ++i) {
        rgba[4 * i] = tex->pcData[i].r;
        rgba[4 * i + 1] = tex->pcData[i].g;
        rgba[4 * i + 2] = tex->pcData[i].b;
        rgba[4 * i + 3] = tex->pcData[i].a;
    }
    return decodeFor(use, rgba.data(), static_cast<int>(tex->mWidth), static_cast<int>(tex->mHeight), 4);
}

// A texture file's pixels for `use`. EXR (and anything stb cannot read as 8 bits) goes through
// readImage: linear values, no alpha channel.
Expected<Image> readTextureFileImpl(const fs::path& file, TextureUse use) {
    if (!fs::exists(file)) return makeError("{}: file not found", file.string());
    if (use == TextureUse::SrgbColour || lowerExtension(file) == ".exr") {
        BOUNCE_TRY(Image image, readImage(file));
        if (use == TextureUse::Alpha) image = Image(image.width(), image.height(), glm::vec3(1.0f));
        // Coverage of an EXR: its first channel, as for grey masks.
        if (use == TextureUse::Coverage)
            for (glm::vec3& px : image.pixels()) px = glm::vec3(px.r);
        return image;
    }
    int w = 0, h = 0, n = 0;
    if (stbi_info(file.c_str(), &w, &h, &n) && (w > kMaxImageSide || h > kMaxImageSide))
        return makeError("{}: image is {}x{}; images may be at most {} pixels per side", file.string(), w, h,
                         kMaxImageSide);
    unsigned char* data = stbi_load(file.c_str(), &w, &h, &n, 0);
    if (!data) return makeError("{}: cannot decode image ({})", file.string(), stbi_failure_reason());
    Image image = decodeFor(use, data, w, h, n);
    stbi_image_free(data);
    return image;
}

// glTF extensions bounce reads (docs/scene.md "glTF 2.0"); any other one the file lists in
// extensionsUsed gets one warning line: assimp 5.2 drops most of them silently.
constexpr std::array<std::string_view, 2> kSupportedGltfExtensions = {"KHR_lights_punctual",
                                                                       "KHR_materials_emissive_strength"};

void warnUnsupportedGltfExtensions(const fs::path& path, const std::string& where) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string json = bytes;
    constexpr size_t kGlbHeader = 12, kChunkHeader = 8;  // glTF 2.0 section 4.4 (GLB file format)
    if (bytes.size() >= kGlbHeader + kChunkHeader && bytes.compare(0, 4, "glTF") == 0) {
        uint32_t length = 0;
        std::memcpy(&length, bytes.data() + kGlbHeader, sizeof(length));
        json = bytes.substr(kGlbHeader + kChunkHeader, std::min<size_t>(length, bytes.size() - kGlbHeader - kChunkHeader));
    }
    const nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
    if (!doc.is_object() || !doc.contains("extensionsUsed") || !doc["extensionsUsed"].is_array()) return;
    for (const nlohmann::json& e : doc["extensionsUsed"]) {
        if (!e.is_string()) continue;
        const std::string name = e.get<std::string>();
        if (std::find(kSupportedGltfExtensions.begin(), kSupportedGltfExtensions.end(), name) ==
            kSupportedGltfExtensions.end())
            spdlog::warn("{}: glTF extension {} is not supported; the model is rendered without it", where, name);
    }
}

class Importer {
public:
    Importer(Scene& scene, const fs::path& path, const ModelPlacement& placement, Format format)
        : m_scene(scene), m_path(path), m_placement(placement), m_format(format) {}

    Expected<ModelImportResult> run(const aiScene* ai) {
        m_ai = ai;
        m_meshBase = static_cast<uint32_t>(m_scene.meshes.size());
        m_materialBase = static_cast<uint32_t>(m_scene.materials.size());
        for (unsigned i = 0; i < ai->mNumMaterials; ++i) m_scene.materials.push_back(material(ai->mMaterials[i], i));
        m_meshUsable.assign(ai->mNumMeshes, false);
        for (unsigned i = 0; i < ai->mNumMeshes; ++i) m_scene.meshes.push_back(mesh(ai->mMeshes[i], i));
        countInstances(ai->mRootNode);
        const size_t firstObject = m_scene.objects.size();
        visit(ai->mRootNode, m_placement.transform);
        m_result.objects = m_scene.objects.size() - firstObject;
        if (m_result.objects == 0) return makeError("{}: the model has no triangle meshes", where());
        if (m_placement.importLights)
            for (unsigned i = 0; i < ai->mNumLights; ++i) BOUNCE_TRY_VOID(light(ai->mLights[i]));
        if (m_placement.importCamera && ai->mNumCameras > 0) BOUNCE_TRY_VOID(camera(ai->mCameras[0]));
        return m_result;
    }

private:
    std::string where() const { return m_placement.origin.empty() ? m_path.string() : m_placement.origin; }

    Material material(const aiMaterial* am, unsigned index) {
        Material m;
        aiString name;
        m.name = am->Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0 ? name.C_Str()
                                                                                : fmt::format("material-{}", index);
        m.name = m_path.filename().string() + ":" + m.name;
        aiColor4D colour;
        if (am->Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS || am->Get(AI_MATKEY_COLOR_DIFFUSE, colour) == AI_SUCCESS) {
            m.baseColor = {colour.r, colour.g, colour.b};
            if (m_format == Format::Gltf) m.alpha = std::clamp(colour.a, 0.0f, 1.0f);
        }
        aiColor3D emissive;
        if (am->Get(AI_MATKEY_COLOR_EMISSIVE, emissive) == AI_SUCCESS) {
            m.emission = toGlm(emissive);
            float strength = 1.0f;  // KHR_materials_emissive_strength
            if (am->Get(AI_MATKEY_EMISSIVE_INTENSITY, strength) == AI_SUCCESS) m.emission *= strength;
        }
        if (m_format == Format::Gltf) {
            float f = 0.0f;
            if (am->Get(AI_MATKEY_ROUGHNESS_FACTOR, f) == AI_SUCCESS) m.roughness = f;
            if (am->Get(AI_MATKEY_METALLIC_FACTOR, f) == AI_SUCCESS) m.metallic = f;
            m.specularF0 = kGltfDielectricF0;
            int twoSided = 0;
            m.twoSided = am->Get(AI_MATKEY_TWOSIDED, twoSided) == AI_SUCCESS && twoSided != 0;
        } else {
            // OBJ and PLY: Lambert only; neither format defines face culling, so shade both sides.
            m.roughness = 1.0f;
            m.metallic = 0.0f;
            m.specularF0 = 0.0f;
            m.twoSided = true;
        }
        aiString texPath;
        if (am->GetTexture(aiTextureType_BASE_COLOR, 0, &texPath) == AI_SUCCESS ||
            am->GetTexture(aiTextureType_DIFFUSE, 0, &texPath) == AI_SUCCESS)
            m.baseColorTexture = texture(texPath.C_Str(), m.name, "base colour");
        // glTF's emissiveTexture (sRGB, multiplied by emissiveFactor) and MTL's map_Ke.
        if (am->GetTexture(aiTextureType_EMISSIVE, 0, &texPath) == AI_SUCCESS)
            m.emissionTexture = texture(texPath.C_Str(), m.name, "emission factor");
        if (m_format == Format::Gltf) gltfMaterial(am, m);
        return m;
    }

    // glTF's alpha mode, normal and metallic-roughness textures (docs/scene.md "glTF 2.0").
    void gltfMaterial(const aiMaterial* am, Material& m) {
        aiString mode;
        if (am->Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS && std::string_view(mode.C_Str()) != "OPAQUE") {
            m.alphaCutoff = kGltfDefaultAlphaCutoff;
            float cutoff = 0.0f;
            if (std::string_view(mode.C_Str()) == "MASK") {
                if (am->Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff) == AI_SUCCESS) m.alphaCutoff = std::clamp(cutoff, 0.0f, 1.0f);
            } else {
                spdlog::warn("{}: material '{}': alphaMode {} is rendered as MASK with alphaCutoff {} (no blending)",
                             where(), m.name, mode.C_Str(), kGltfDefaultAlphaCutoff);
            }
            aiString texPath;
            if (am->GetTexture(aiTextureType_BASE_COLOR, 0, &texPath) == AI_SUCCESS ||
                am->GetTexture(aiTextureType_DIFFUSE, 0, &texPath) == AI_SUCCESS)
                m.alphaTexture = texture(texPath.C_Str(), m.name, "alpha factor (no mask)", TextureUse::Alpha);
        }
        aiString texPath;
        if (am->GetTexture(aiTextureType_NORMALS, 0, &texPath) == AI_SUCCESS) {
            m.normalTexture = texture(texPath.C_Str(), m.name, "interpolated normal", TextureUse::Linear);
            float scale = 1.0f;
            if (am->Get(AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), scale) == AI_SUCCESS && std::isfinite(scale))
                m.normalScale = scale;
        }
        if (am->GetTexture(AI_MATKEY_GLTF_PBRMETALLICROUGHNESS_METALLICROUGHNESS_TEXTURE, &texPath) == AI_SUCCESS ||
            am->GetTexture(aiTextureType_METALNESS, 0, &texPath) == AI_SUCCESS)
            m.metallicRoughnessTexture = texture(texPath.C_Str(), m.name, "roughness and metallic factors", TextureUse::Linear);
    }

    // Index of the texture in the scene, or -1 (with a warning) when it cannot be read.
    int texture(const std::string& ref, const std::string& materialName, const char* fallback,
                TextureUse use = TextureUse::SrgbColour) {
        const std::string key = ref + "#" + std::to_string(static_cast<int>(use));
        const auto cached = m_textures.find(key);
        if (cached != m_textures.end()) return cached->second;
        Expected<Image> image = Error{};
        std::string name;
        if (const aiTexture* embedded = m_ai->GetEmbeddedTexture(ref.c_str())) {
            name = fmt::format("{}:{}", m_path.string(), ref);
            image = decodeEmbedded(embedded, name, use);
        } else {
            std::string rel = ref;
            std::replace(rel.begin(), rel.end(), '\\', '/');  // MTL files written on Windows
            const fs::path file = m_path.parent_path() / rel;
            name = file.string();
            image = readTextureFileImpl(file, use);
        }
        int index = -1;
        if (image.ok()) {
            index = static_cast<int>(m_scene.textures.size());
            m_scene.textures.push_back({name, std::move(image.value())});
        } else {
            spdlog::warn("{}: material '{}': texture unusable, using the {}: {}", where(), materialName, fallback,
                         image.error().message);
        }
        m_textures[key] = index;
        return index;
    }

    Mesh mesh(const aiMesh* am, unsigned index) {
        Mesh m;
        m.name = std::string_view(am->mName.C_Str()) == kAssimpDefaultObject ? m_path.filename().string()
                 : am->mName.length > 0                                       ? am->mName.C_Str()
                                                                              : fmt::format("mesh-{}", index);
        if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return m;  // points and lines: skipped
        m.positions.reserve(am->mNumVertices);
        for (unsigned v = 0; v < am->mNumVertices; ++v) m.positions.push_back(toGlm(am->mVertices[v]));
        if (am->HasNormals())
            for (unsigned v = 0; v < am->mNumVertices; ++v) m.normals.push_back(toGlm(am->mNormals[v]));
        if (am->HasTextureCoords(0))
            for (unsigned v = 0; v < am->mNumVertices; ++v)
                m.uvs.push_back({am->mTextureCoords[0][v].x, am->mTextureCoords[0][v].y});
        for (unsigned f = 0; f < am->mNumFaces; ++f) {
            const aiFace& face = am->mFaces[f];
            if (face.mNumIndices != 3) continue;
            m.indices.insert(m.indices.end(), face.mIndices, face.mIndices + 3);
        }
        // OBJ faces without normals got theirs from addMissingObjNormals; PLY keeps finalizeScene's
        // smooth normals (docs/scene.md "Model files").
        if (m_format == Format::Gltf && m.normals.empty()) makeFlatNormals(m);
        m_meshUsable[index] = !m.indices.empty();
        return m;
    }

    void countInstances(const aiNode* node) {
        for (unsigned i = 0; i < node->mNumMeshes; ++i)
            if (m_meshUsable[node->mMeshes[i]]) ++m_instances;
        for (unsigned c = 0; c < node->mNumChildren; ++c) countInstances(node->mChildren[c]);
    }

    void visit(const aiNode* node, const glm::mat4& parent) {
        const glm::mat4 world = parent * toGlm(node->mTransformation);
        for (unsigned i = 0; i < node->mNumMeshes; ++i) {
            const unsigned meshIndex = node->mMeshes[i];
            if (!m_meshUsable[meshIndex]) continue;
            const aiMesh* am = m_ai->mMeshes[meshIndex];
            Object o;
            std::string part = node->mName.length == 0 ? m_scene.meshes[m_meshBase + meshIndex].name
                                                        : userName(node->mName, m_path, /*stem=*/true);
            if (node->mNumMeshes > 1) part += fmt::format("#{}", i);
            if (m_placement.name.empty()) o.name = part;
            else o.name = m_instances == 1 ? m_placement.name : m_placement.name + "/" + part;
            o.mesh = m_meshBase + meshIndex;
            o.material = m_placement.materialOverride >= 0 ? static_cast<uint32_t>(m_placement.materialOverride)
                                                           : m_materialBase + am->mMaterialIndex;
            o.transform = world;
            m_scene.objects.push_back(std::move(o));
        }
        for (unsigned c = 0; c < node->mNumChildren; ++c) visit(node->mChildren[c], world);
    }

    Expected<void> light(const aiLight* al) {
        // assimp names a glTF light after the node that carries it.
        const aiNode* node = m_ai->mRootNode->FindNode(al->mName);
        const glm::mat4 m = m_placement.transform * (node ? globalTransform(node) : glm::mat4(1.0f));
        Light l;
        l.name = m_placement.name.empty() ? al->mName.C_Str() : m_placement.name + "/" + al->mName.C_Str();
        // assimp 5.2 reports the glTF colour already multiplied by the intensity.
        const glm::vec3 value = toGlm(al->mColorDiffuse) / kLumensPerWatt;
        l.position = glm::vec3(m * glm::vec4(toGlm(al->mPosition), 1.0f));
        const glm::vec3 localDirection = glm::length(toGlm(al->mDirection)) > 0.0f ? toGlm(al->mDirection)
                                                                                    : glm::vec3(0, 0, -1);
        l.direction = glm::normalize(glm::mat3(m) * localDirection);
        switch (al->mType) {
            case aiLightSource_POINT:
                l.type = LightType::Point;
                l.intensity = value;
                break;
            case aiLightSource_SPOT: {
                l.type = LightType::Spot;
                l.intensity = value;
                // assimp passes glTF's half-angles through. glTF fades smoothly from the inner to the outer
                // cone (t = (cos a - cos outer)/(cos inner - cos outer), intensity t^2); bounce's cos^n spot
                // keeps the outer cone as cutoff and matches glTF's half-intensity angle, t = 1/sqrt(2).
                const float outer = std::clamp(al->mAngleOuterCone, 1e-4f, glm::half_pi<float>());
                const float inner = std::clamp(al->mAngleInnerCone, 0.0f, outer);
                const float cosHalf = std::cos(outer) + (std::cos(inner) - std::cos(outer)) / std::sqrt(2.0f);
                l.cutoffAngle = outer;
                l.falloffExponent = cosHalf < 1.0f ? std::log(0.5f) / std::log(cosHalf) : 0.0f;
                break;
            }
            case aiLightSource_DIRECTIONAL:
                l.type = LightType::Directional;
                l.irradiance = value;
                break;
            default:
                spdlog::warn("{}: light '{}' of unsupported type {} skipped", where(), l.name, static_cast<int>(al->mType));
                return {};
        }
        m_scene.lights.push_back(std::move(l));
        ++m_result.lights;
        return {};
    }

    Expected<void> camera(const aiCamera* ac) {
        const aiNode* node = m_ai->mRootNode->FindNode(ac->mName);
        const glm::mat4 m = m_placement.transform * (node ? globalTransform(node) : glm::mat4(1.0f));
        Camera& c = m_scene.camera;
        // assimp 5.2's glTF importer also copies the node's translation into mPosition, so the node
        // transform alone places the camera (for glTF the camera sits at its node's origin).
        const glm::vec3 local = node && m_format == Format::Gltf ? glm::vec3(0.0f) : toGlm(ac->mPosition);
        c.position = glm::vec3(m * glm::vec4(local, 1.0f));
        c.target = c.position + glm::normalize(glm::mat3(m) * toGlm(ac->mLookAt));
        c.up = glm::normalize(glm::mat3(m) * toGlm(ac->mUp));
        c.projection = Projection::Perspective;
        // assimp 5.2 stores glTF's yfov * aspectRatio as mHorizontalFOV (or yfov when the aspect is absent).
        c.verticalFov = ac->mAspect > 0.0f ? ac->mHorizontalFOV / ac->mAspect : ac->mHorizontalFOV;
        if (ac->mClipPlaneNear > 0.0f) c.nearPlane = ac->mClipPlaneNear;
        if (ac->mClipPlaneFar > c.nearPlane) c.farPlane = ac->mClipPlaneFar;
        m_result.camera = true;
        return {};
    }

    Scene& m_scene;
    fs::path m_path;
    const ModelPlacement& m_placement;
    Format m_format;
    const aiScene* m_ai = nullptr;
    uint32_t m_meshBase = 0, m_materialBase = 0;
    std::vector<bool> m_meshUsable;
    size_t m_instances = 0;
    std::map<std::string, int> m_textures;  // (reference, use) -> Scene::textures index or -1
    ModelImportResult m_result;
};

}  // namespace

namespace {
// Some line of `text` is a vertex statement: "v" then a space or tab (not "vt", "vn", "vp") at the
// start of the line, where assimp's reader looks for it.
bool objHasVertex(std::string_view text) {
    size_t at = 0;
    while (at < text.size()) {
        size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(at, end - at);
        if (line.size() > 1 && line[0] == 'v' && (line[1] == ' ' || line[1] == '\t')) return true;
        at = end + 1;
    }
    return false;
}

// The binary glTF container (glTF 2.0 spec, "GLB File Format Specification"): a 12-byte header (magic,
// version, total length) and chunks of an 8-byte header (length, type) and their data. assimp 5.2
// allocates what a chunk header claims before reading it: a 397-byte file asked for 3.4 GB (found by
// fuzz_model). Every length must fit in the file; the first chunk must be the JSON one.
Expected<void> checkGlbChunks(const fs::path& path, const std::string& where) {
    std::error_code ec;
    const uint64_t size = fs::file_size(path, ec);
    if (ec) return makeError("{}: cannot read: {}", where, ec.message());
    std::ifstream in(path, std::ios::binary);
    const auto u32 = [&in](uint64_t at) -> std::optional<uint32_t> {
        unsigned char b[4];
        in.seekg(static_cast<std::streamoff>(at));
        if (!in.read(reinterpret_cast<char*>(b), 4)) return std::nullopt;
        return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
    };
    constexpr uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;
    const auto version = u32(4), length = u32(8);
    if (!version || !length) return makeError("{}: GLB header is truncated", where);
    if (*version != 2) return makeError("{}: GLB version {} (bounce reads glTF 2.0)", where, *version);
    if (*length > size) return makeError("{}: GLB header claims {} bytes, the file has {}", where, *length, size);
    uint64_t at = 12;
    for (int chunk = 0; at < *length; ++chunk) {
        const auto chunkLength = u32(at), chunkType = u32(at + 4);
        if (!chunkLength || !chunkType || at + 8 > *length) return makeError("{}: GLB chunk {} header is truncated", where, chunk);
        if (chunk == 0 && *chunkType != kJsonChunk) return makeError("{}: GLB's first chunk is not JSON", where);
        if (at + 8 + *chunkLength > *length)
            return makeError("{}: GLB chunk {} claims {} bytes, {} remain", where, chunk, *chunkLength, *length - at - 8);
        // Later chunks: BIN (kBinChunk) or a type readers skip (the spec); their lengths fit, as checked.
        (void)kBinChunk;
        at += 8 + uint64_t(*chunkLength);
    }
    if (at == 12) return makeError("{}: GLB has no JSON chunk", where);
    return {};
}

}  // namespace

Expected<ModelImportResult> appendModel(Scene& scene, const fs::path& path, const ModelPlacement& placement) {
    const std::string ext = lowerExtension(path);
    Format format;
    if (ext == ".gltf" || ext == ".glb") format = Format::Gltf;
    else if (ext == ".obj") format = Format::Obj;
    else if (ext == ".ply") format = Format::Ply;
    else return makeError("{}: unsupported model extension '{}' (use .gltf .glb .obj .ply)", path.string(), ext);
    const std::string where = placement.origin.empty() ? path.string() : placement.origin;
    if (!fs::exists(path)) return makeError("{}: model file '{}' not found", where, path.string());
    if (fs::is_directory(path)) return makeError("{}: model file '{}' is a directory", where, path.string());
    if (std::ifstream probe(path, std::ios::binary); !probe)
        return makeError("{}: cannot open model file '{}': {}", where, path.string(), std::strerror(errno));

    Assimp::Importer importer;
    if (format == Format::Gltf) {
        // assimp hands a file its glTF reader does not recognise to whichever reader claims the content
        // (an OBJ reader for "f 1 2 3 ...", found by fuzz_model), with that reader's bugs (below). A .glb
        // must start with the binary container's magic, a .gltf with a JSON object.
        std::ifstream in(path, std::ios::binary);
        char head[4] = {};
        in.read(head, sizeof head);
        const std::string_view got(head, static_cast<size_t>(in.gcount()));
        if (ext == ".glb" && got != "glTF")
            return makeError("{}: model '{}': not a binary glTF file (it does not start with \"glTF\")", where, path.string());
        if (ext == ".glb")
            BOUNCE_TRY_VOID(checkGlbChunks(path, fmt::format("{}: model '{}'", where, path.string())));
        if (ext == ".gltf") {
            in.clear();
            in.seekg(0);
            char c = 0;
            while (in.get(c) && (c == ' ' || c == '\t' || c == '\r' || c == '\n')) {
            }
            if (!in || c != '{')
                return makeError("{}: model '{}': not a glTF file (its JSON does not start with '{{')", where, path.string());
        }
        warnUnsupportedGltfExtensions(path, fmt::format("{}: model '{}'", where, path.string()));
    }
    if (format == Format::Ply) {
        // assimp 5.2 hangs or crashes on some malformed PLY files: bounce checks the structure first.
        std::ifstream in(path, std::ios::binary);
        if (!in) return makeError("{}: cannot read model '{}'", where, path.string());
        const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        BOUNCE_TRY_VOID(checkPlyFile(bytes, where == path.string() ? where : fmt::format("{}: model '{}'", where, path.string())));
    }
    if (format == Format::Obj) {
        // assimp 5.2 ignores OBJ smoothing groups: faces without normals get them from bounce first.
        std::ifstream in(path, std::ios::binary);
        if (!in) return makeError("{}: cannot read model '{}'", where, path.string());
        const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        // assimp 5.2.5 reads past its line buffer when a file's only line is a long face, line or point
        // statement (found by fuzz_model under ASan). A file without a vertex holds no geometry, so it is
        // refused here, before assimp sees it.
        if (!objHasVertex(text))
            return makeError("{}: model '{}': OBJ file has no vertex ('v' statement)", where, path.string());
        if (std::optional<ObjNormalsRewrite> rewrite = addMissingObjNormals(text)) {
            spdlog::debug("{}: normals added to {} flat and {} smoothing-group face(s)", where, rewrite->flatFaces,
                          rewrite->smoothFaces);
            importer.SetIOHandler(new OverlayIoSystem(path.string(), std::move(rewrite->text)));
        }
    }
    const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
    const aiScene* ai = importer.ReadFile(path.string(), flags);
    if (!ai || (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !ai->mRootNode)
        return makeError("{}: cannot read model '{}': {}", where, path.string(), importer.GetErrorString());
    // Non-finite values are refused before JoinIdenticalVertices: assimp 5.2 joins a NaN vertex with
    // another one (its spatial sort compares NaN distances), which hides the NaN behind a degenerate
    // triangle or, worse, a valid but wrong one.
    for (unsigned i = 0; i < ai->mNumMeshes; ++i) {
        const aiMesh* am = ai->mMeshes[i];
        const auto bad = [](const aiVector3D& v) { return !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z); };
        for (unsigned v = 0; v < am->mNumVertices; ++v) {
            const char* what = bad(am->mVertices[v])                               ? "position"
                               : am->HasNormals() && bad(am->mNormals[v])         ? "normal"
                               : am->HasTextureCoords(0) && bad(am->mTextureCoords[0][v]) ? "texture coordinate"
                                                                                  : nullptr;
            if (what)
                return makeError("{}: mesh '{}': vertex {} has a non-finite {}", where, userName(am->mName, path, false), v, what);
        }
    }
    // FlipUVs: bounce's uv origin is the image's top-left corner (Image row 0), see docs/scene.md.
    ai = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices | aiProcess_FlipUVs);
    if (!ai) return makeError("{}: cannot read model '{}': {}", where, path.string(), importer.GetErrorString());
    Importer run(scene, path, placement, format);
    return run.run(ai);
}

Expected<Image> readTextureFile(const fs::path& file, TextureUse use) { return readTextureFileImpl(file, use); }

Expected<Scene> loadModelScene(const fs::path& path) {
    Scene scene;
    scene.name = path.stem().string();
    scene.source = path.string();
    BOUNCE_TRY(const ModelImportResult result, appendModel(scene, path, ModelPlacement{}));
    if (!result.camera) {
        // Frame the model's bounding sphere from the front (+z), slightly above.
        glm::vec3 lo, hi;
        scene.bounds(0.0f, lo, hi);
        const glm::vec3 centre = 0.5f * (lo + hi);
        const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
        const float fov = scene.camera.verticalFov;
        const float distance = radius / std::sin(0.5f * fov);
        scene.camera.target = centre;
        scene.camera.position = centre + distance * glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));
        scene.camera.nearPlane = std::max(1e-3f, 0.01f * radius);  // metres
        scene.camera.farPlane = distance + 4.0f * radius;
    }
    if (scene.lights.empty() && !scene.hasEmissiveMaterials()) {
        Light sun;
        sun.name = "default-sun";
        sun.type = LightType::Directional;
        sun.direction = kDefaultSunDirection;
        sun.irradiance = kDefaultSunIrradiance;
        scene.lights.push_back(sun);
    }
    return scene;
}

}  // namespace bounce
