#pragma once
// The scene model shared by every renderer in bounce: the GPU techniques and the CPU reference read
// the same Scene, so lights, materials and units mean the same thing on both sides.
//
// Units (see docs/scene.md):
//   length            metres
//   time              seconds (animation keyframes)
//   Light::intensity  radiant intensity, W/sr per RGB channel (point; spot on its axis)
//   Light::irradiance irradiance on a surface facing the light, W/m^2 (directional)
//   Light::radiance   emitted radiance, W/(m^2 sr) (rectangular area light, one-sided, Lambertian)
//   Material::emission emitted radiance, W/(m^2 sr)
// The BRDF is fixed by docs/scene.md "Materials": Lambert (baseColor/pi, scaled by 1-metallic) plus
// GGX/Smith/Schlick specular with F0 = mix(specularF0, baseColor, metallic) and alpha = roughness^2.
#include "core/Image.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bounce {

// Indexed triangle mesh in object space. normals and uvs are empty or one per position.
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    // Tangent frames for normal maps: xyz the unit tangent along +u, w = +-1 such that the bitangent
    // w * cross(normal, tangent) points along -v (up the image, the +y of a glTF normal map). Empty
    // or one per position; finalizeScene fills them from the uvs for meshes a normal-mapped material
    // uses (computeTangents).
    std::vector<glm::vec4> tangents;
    std::vector<uint32_t> indices;  // 3 per triangle

    size_t triangleCount() const { return indices.size() / 3; }
};

// A texture decoded to linear RGB (sRGB-encoded base-colour files are decoded on load).
struct TextureImage {
    std::string name;  // file path or generated name, for messages
    Image image;
};

struct Material {
    std::string name;
    glm::vec3 baseColor{0.8f};       // albedo of the diffuse lobe (linear RGB, in [0,1])
    int baseColorTexture = -1;       // index into Scene::textures, multiplied with baseColor
    glm::vec3 emission{0.0f};        // emitted radiance, W/(m^2 sr)
    int emissionTexture = -1;        // index into Scene::textures, multiplied with emission (linear RGB)
    float roughness = 1.0f;          // perceptual roughness; GGX alpha = roughness^2
    float metallic = 0.0f;
    float specularF0 = 0.0f;         // dielectric reflectance at normal incidence (0 = pure Lambert)
    bool twoSided = false;           // shade back faces with the flipped normal
    // Alpha masking (glTF alphaMode MASK): the surface exists only where coverage >= alphaCutoff,
    // coverage = alpha * alphaTexture (its red channel, linear; glTF: the base-colour texture's alpha).
    // alphaCutoff 0 is opaque (no texel is below it); glTF BLEND is loaded as MASK at 0.5.
    float alpha = 1.0f;              // coverage factor in [0, 1] (glTF baseColorFactor.a)
    int alphaTexture = -1;           // index into Scene::textures: coverage in every channel
    float alphaCutoff = 0.0f;        // in [0, 1]; 0: opaque
    int normalTexture = -1;          // tangent-space normal map, linear RGB = (n + 1) / 2 (glTF normalTexture)
    float normalScale = 1.0f;        // scales the map's x and y (glTF normalTexture.scale)
    int metallicRoughnessTexture = -1;  // linear: G multiplies roughness, B metallic (glTF)

    bool masked() const { return alphaCutoff > 0.0f && (alpha < 1.0f || alphaTexture >= 0); }
};

// Coverage at a texel value `sample` (the alpha texture's red channel, 1 without one); a masked
// material's surface is absent where this is false. Shared by every renderer.
inline bool coveredAt(const Material& m, float sample) { return m.alpha * sample >= m.alphaCutoff; }

// Keyframed rigid transform. Translation is interpolated linearly or with Catmull-Rom splines,
// rotation by slerp, scale linearly. Times are seconds; outside the key range the ends are held,
// or the track wraps when `loop` is set.
struct TransformKey {
    float time = 0.0f;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
};

enum class Interpolation { Linear, CatmullRom };

struct TransformTrack {
    std::vector<TransformKey> keys;  // sorted by time
    Interpolation interpolation = Interpolation::Linear;
    bool loop = true;

    bool empty() const { return keys.empty(); }
    float duration() const { return keys.empty() ? 0.0f : keys.back().time - keys.front().time; }
    // The transform at time t; identity when empty.
    glm::mat4 evaluate(float t) const;
};

// A placed mesh. worldFromObject(t) = animation(t) * transform.
struct Object {
    std::string name;
    uint32_t mesh = 0;
    uint32_t material = 0;
    glm::mat4 transform{1.0f};
    TransformTrack animation;

    bool isDynamic() const { return !animation.empty(); }
    glm::mat4 worldFromObject(float t) const { return animation.empty() ? transform : animation.evaluate(t) * transform; }
};

enum class LightType { Point, Spot, Directional, Area };

// Emission texture of a rectangular area light (Nichols 2010 ch. 5: video screens as lights). The
// light emits radiance * texture(u, v) at position + (u - 1/2) edgeU + (v - 1/2) edgeV, u, v in [0, 1].
// Image column 0 is u = 0 and image row 0 is v = 1, so seen from the emitting side (edgeU to the right,
// edgeV up) the picture is upright and not mirrored. Texel values are linear multipliers (a PNG is
// decoded from sRGB). See scene/AreaTexture.h for evaluating it at a time.
struct AreaTexture {
    enum class Kind { None, Images, BouncingSquare };
    Kind kind = Kind::None;
    // Images: indices into Scene::textures, all the same size; one is a still picture, several are a
    // sequence shown at frameRate frames per second, looping.
    std::vector<uint32_t> frames;
    float frameRate = 24.0f;
    // BouncingSquare: the thesis's pathological test video (section 5.4.7, Fig. 5.15), a white square of
    // side squareSize (fraction of the light's sides) on black, moving at squareVelocity (light sides
    // per second) and reflecting off the edges, starting at squareStart (its centre, in u, v);
    // rasterised with exact coverage at resolution x resolution texels.
    int resolution = 64;
    float squareSize = 0.25f;
    glm::vec2 squareVelocity{0.35f, 0.22f};
    glm::vec2 squareStart{0.3f, 0.6f};

    bool textured() const { return kind != Kind::None; }
    bool animated() const { return kind == Kind::BouncingSquare || (kind == Kind::Images && frames.size() > 1); }
};

// Spot: I(alpha) = intensity * cos(alpha)^falloffExponent for alpha < cutoffAngle, else 0,
// alpha measured from `direction` (the cosine-power spot the papers use; exponent 1 and cutoff 90 deg
// is Laine et al.'s "180 degree cosine spot", whose flux is pi * intensity).
// Area: rectangle centred at `position` with full edge vectors `edgeU`, `edgeV`; it emits `radiance`
// (times its texture, if any) from the side of normalize(cross(edgeU, edgeV)), or from both sides.
struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // spot axis, directional propagation direction
    glm::vec3 intensity{0.0f};               // W/sr (point, spot)
    glm::vec3 irradiance{0.0f};              // W/m^2 (directional)
    glm::vec3 radiance{0.0f};                // W/(m^2 sr) (area)
    float cutoffAngle = 1.5707964f;          // radians, spot half-angle
    float falloffExponent = 1.0f;            // spot cosine power
    glm::vec3 edgeU{1.0f, 0.0f, 0.0f};       // area light edges (metres)
    glm::vec3 edgeV{0.0f, 0.0f, 1.0f};
    AreaTexture texture;                     // area: emission multiplier over the rectangle
    bool twoSided = false;                   // area: emits from both faces (the back is mirrored in u)
    TransformTrack animation;                // moves position, direction and edges

    bool isDynamic() const { return !animation.empty(); }
    // The light with its animation applied at time t.
    Light at(float t) const;
    glm::vec3 areaNormal() const;
    float area() const;
    // Total emitted flux in W (per channel): point 4*pi*I, spot integral of I over its cone,
    // area pi*L*A per emitting side (an area light's texture multiplies this by its mean,
    // areaTextureMean in scene/AreaTexture.h), directional has none (infinite) and returns 0.
    glm::vec3 flux() const;
};

enum class Projection { Perspective, Orthographic };

struct Camera {
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    Projection projection = Projection::Perspective;
    float verticalFov = 0.6981317f;  // radians (40 degrees), perspective
    float orthoHeight = 2.0f;        // metres, orthographic view height
    float nearPlane = 0.01f;         // metres
    float farPlane = 100.0f;         // metres
    TransformTrack animation;        // moves position and target

    Camera at(float t) const;
    glm::mat4 viewFromWorld() const;
    glm::mat4 clipFromView(float aspect) const;  // OpenGL clip space, depth -1..1
};

// World-space boxes (open: points strictly inside) for the light-leak score (metrics/LightLeak.h):
// in truth no light reaches the surfaces in the dark box; the lit box's mean luminance normalises.
// Declared by scenes built to measure leaks (two-rooms); `bounce sweep` scores every technique on them.
struct LeakRegions {
    glm::vec3 darkMin{0.0f}, darkMax{0.0f}, litMin{0.0f}, litMax{0.0f};  // metres
};

struct Scene {
    std::string name;
    std::string source;  // file path, or "builtin:NAME"
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<TextureImage> textures;
    std::vector<Object> objects;
    std::vector<Light> lights;
    Camera camera;
    float frameRate = 30.0f;  // frames per second of `bounce render --frames`
    // Default technique settings from the scene file, "technique.setting" -> value text.
    std::map<std::string, std::string> settings;
    std::optional<LeakRegions> leakRegions;

    size_t triangleCount() const;
    bool hasEmissiveMaterials() const;
    // Some light has non-zero power (its intensity, irradiance or radiance; a textured area light
    // counts even if its texture is black at some frame) or some material emits. `bounce render` and
    // `bounce reference` both refuse a scene without (docs/scene.md "Validation").
    bool emitsLight() const;
    float timeOfFrame(uint32_t frame) const { return static_cast<float>(frame) / frameRate; }
    // Axis-aligned bounds of all objects at time t.
    void bounds(float t, glm::vec3& lo, glm::vec3& hi) const;
};

}  // namespace bounce
