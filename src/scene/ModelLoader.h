#pragma once
// Model files read through assimp 5.2: glTF 2.0 (.gltf, .glb, with KHR_lights_punctual and cameras),
// OBJ/MTL and PLY. Unit conventions and what assimp reports are in docs/scene.md "Model files".
#include "core/Error.h"
#include "scene/Scene.h"

#include <glm/mat4x4.hpp>

#include <filesystem>
#include <string>

namespace bounce {

struct ModelPlacement {
    std::string name;               // object names: `name` (one mesh) or `name/node` (several); empty: node names
    glm::mat4 transform{1.0f};      // world from model
    int materialOverride = -1;      // a scene material index applied to every mesh instead of the file's
    bool importLights = true;
    bool importCamera = true;       // the file's first camera replaces scene.camera
    // For error messages: where the placement came from ("scene.json:12"), or empty.
    std::string origin;
};

struct ModelImportResult {
    size_t objects = 0;
    size_t lights = 0;
    bool camera = false;
};

// Appends the model's meshes, materials, textures and objects (and lights/camera if asked) to `scene`.
// A texture that cannot be read is a warning: the material falls back to its base colour.
Expected<ModelImportResult> appendModel(Scene& scene, const std::filesystem::path& path, const ModelPlacement& placement);

// A model file as a whole scene: the file's lights and first camera, or a default camera framing the
// model and a default sun when the file has neither lights nor emissive materials. Not finalized.
Expected<Scene> loadModelScene(const std::filesystem::path& path);

// How a material reads a texture file's channels (glTF 2.0 section 3.9: base colour and emission are
// sRGB; normal, metallic-roughness and the base colour's alpha are linear). Alpha: the alpha channel
// in RGB (1 without one, glTF's rule); Coverage: the alpha channel, or the first channel of an image
// without alpha (JSON's alphaTexture, a grey mask).
enum class TextureUse { SrgbColour, Alpha, Coverage, Linear };

// A texture file's pixels for `use` (PNG/JPEG through stb_image; EXR as stored, no alpha).
Expected<Image> readTextureFile(const std::filesystem::path& file, TextureUse use);

}  // namespace bounce
