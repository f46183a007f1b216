#include "scene/JsonSceneLoader.h"

#include "core/FileIo.h"

#include "core/ImageIo.h"
#include "core/Log.h"
#include "scene/AreaTexture.h"
#include "scene/JsonLocator.h"
#include "scene/ModelLoader.h"
#include "scene/SceneLoader.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace bounce {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// glTF 2.0's default alphaCutoff (material.alphaCutoff), used for "mask" without one and for "blend".
constexpr float kDefaultAlphaCutoff = 0.5f;
// A normal map's xy scale beyond this would tilt every normal to the horizon: a typo, not a material.
constexpr float kMaxNormalScale = 10.0f;
// Upper bound of an area light's texture frame rate (frames per second): far above any video rate,
// it only catches typos such as a period given in milliseconds.
constexpr float kMaxTextureFrameRate = 1e4f;

std::string joinKeys(const std::set<std::string>& keys) {
    std::string out;
    for (const std::string& k : keys) out += (out.empty() ? "" : ", ") + k;
    return out;
}

// Reads one scene file, turning each JSON value into scene data with "file:line: what" errors.
class JsonSceneReader {
public:
    JsonSceneReader(const fs::path& path, const std::string& text) : m_path(path), m_locator(text) {}

    Expected<Scene> read(const json& root) {
        Scene& s = m_scene;
        s.source = m_path.string();
        s.name = m_path.stem().string();
        BOUNCE_TRY_VOID(expectObject(root, "", "the scene file"));
        BOUNCE_TRY_VOID(checkKeys(root, "", "scene", {"name", "frameRate", "settings", "camera", "materials", "objects", "lights", "leakRegions"}));
        if (root.contains("name")) {
            BOUNCE_TRY(s.name, text(root["name"], "/name"));
        }
        if (root.contains("frameRate")) {
            BOUNCE_TRY(s.frameRate, number(root["frameRate"], "/frameRate", 1e-3f, 1e4f));
        }
        if (root.contains("settings")) BOUNCE_TRY_VOID(settings(root["settings"], "/settings"));
        if (root.contains("materials")) BOUNCE_TRY_VOID(materials(root["materials"], "/materials"));
        if (!root.contains("objects")) return err("", "no \"objects\": a scene needs at least one object");
        BOUNCE_TRY_VOID(objects(root["objects"], "/objects"));
        if (root.contains("lights")) BOUNCE_TRY_VOID(lights(root["lights"], "/lights"));
        if (root.contains("leakRegions")) BOUNCE_TRY_VOID(leakRegions(root["leakRegions"], "/leakRegions"));
        if (root.contains("camera")) {
            BOUNCE_TRY_VOID(camera(root["camera"], "/camera"));
        } else if (!m_cameraFromModel) {
            return err("", "no \"camera\" (and no model supplied one)");
        }
        return std::move(m_scene);
    }

private:
    template <class... Args>
    Error err(const std::string& pointer, fmt::format_string<Args...> format, Args&&... args) const {
        const int line = m_locator.line(pointer);
        const std::string where = line > 0 ? fmt::format("{}:{}", m_path.string(), line) : m_path.string();
        return Error{where + ": " + fmt::format(format, std::forward<Args>(args)...)};
    }

    // A value-level error: names the key by its path in the file ("materials/white/baseColor"), so a
    // message is readable without the line, and says what was found.
    template <class... Args>
    Error valueErr(const std::string& pointer, fmt::format_string<Args...> format, Args&&... args) const {
        const std::string key = pointer.empty() ? std::string("(root)") : pointer.substr(1);
        return err(pointer, "{}: {}", key, fmt::format(format, std::forward<Args>(args)...));
    }

    static std::string found(const json& j) {
        if (j.is_string()) {
            std::string v = j.get<std::string>();
            if (v.size() > 24) v = v.substr(0, 21) + "...";
            return fmt::format("the string \"{}\"", v);
        }
        if (j.is_number()) return fmt::format("the number {}", j.dump());
        if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
        if (j.is_null()) return "null";
        if (j.is_array()) return fmt::format("an array of {}", j.size());
        return "an object";
    }

    std::string origin(const std::string& pointer) const {
        const int line = m_locator.line(pointer);
        return line > 0 ? fmt::format("{}:{}", m_path.string(), line) : m_path.string();
    }

    Expected<void> expectObject(const json& j, const std::string& p, const std::string& what) const {
        if (!j.is_object()) return err(p, "{} must be a JSON object", what);
        return {};
    }

    Expected<void> checkKeys(const json& j, const std::string& p, const std::string& what,
                             const std::set<std::string>& known) const {
        for (const auto& [key, value] : j.items())
            if (!known.count(key))
                return err(p + "/" + key, "{}: unknown key \"{}\" (known: {})", what, key, joinKeys(known));
        return {};
    }

    Expected<std::string> text(const json& j, const std::string& p) const {
        if (!j.is_string()) return valueErr(p, "expected a string, got {}", found(j));
        return j.get<std::string>();
    }

    Expected<bool> boolean(const json& j, const std::string& p) const {
        if (!j.is_boolean()) return valueErr(p, "expected true or false, got {}", found(j));
        return j.get<bool>();
    }

    Expected<float> number(const json& j, const std::string& p, float lo = -kInf, float hi = kInf) const {
        if (!j.is_number()) return valueErr(p, "expected a number, got {}", found(j));
        const double v = j.get<double>();
        if (!std::isfinite(v)) return valueErr(p, "value is not finite");
        if (v < lo || v > hi) return valueErr(p, "value {} is outside [{}, {}]", v, lo, hi);
        return static_cast<float>(v);
    }

    Expected<glm::vec3> vec3(const json& j, const std::string& p) const {
        if (!j.is_array() || j.size() != 3) return valueErr(p, "expected an array of 3 numbers, got {}", found(j));
        glm::vec3 v(0.0f);
        for (int i = 0; i < 3; ++i) {
            BOUNCE_TRY(v[i], number(j[static_cast<size_t>(i)], p + "/" + std::to_string(i)));
        }
        return v;
    }

    Expected<glm::vec2> vec2(const json& j, const std::string& p, float lo, float hi) const {
        if (!j.is_array() || j.size() != 2) return valueErr(p, "expected an array of 2 numbers, got {}", found(j));
        glm::vec2 v(0.0f);
        for (int i = 0; i < 2; ++i) {
            BOUNCE_TRY(v[i], number(j[static_cast<size_t>(i)], p + "/" + std::to_string(i), lo, hi));
        }
        return v;
    }

    // A colour or radiometric triple: a number (grey) or [r, g, b], each in [lo, hi].
    Expected<glm::vec3> rgb(const json& j, const std::string& p, float lo, float hi) const {
        if (j.is_number()) {
            BOUNCE_TRY(const float v, number(j, p, lo, hi));
            return glm::vec3(v);
        }
        if (!j.is_array() || j.size() != 3) return valueErr(p, "expected a number or an array [r, g, b], got {}", found(j));
        glm::vec3 v(0.0f);
        for (int i = 0; i < 3; ++i) {
            BOUNCE_TRY(v[i], number(j[static_cast<size_t>(i)], p + "/" + std::to_string(i), lo, hi));
        }
        return v;
    }

    Expected<glm::quat> rotation(const json& j, const std::string& p) const {
        BOUNCE_TRY_VOID(expectObject(j, p, "rotation"));
        BOUNCE_TRY_VOID(checkKeys(j, p, "rotation", {"axis", "degrees"}));
        if (!j.contains("axis") || !j.contains("degrees")) return err(p, "rotation needs \"axis\" and \"degrees\"");
        BOUNCE_TRY(const glm::vec3 axis, vec3(j["axis"], p + "/axis"));
        if (!(glm::length(axis) > 0.0f)) return err(p + "/axis", "rotation axis is zero");
        BOUNCE_TRY(const float degrees, number(j["degrees"], p + "/degrees"));
        return glm::angleAxis(glm::radians(degrees), glm::normalize(axis));
    }

    // A uniform scale (number) or per-axis [x, y, z].
    Expected<glm::vec3> scale(const json& j, const std::string& p) const {
        glm::vec3 s(0.0f);
        if (j.is_number()) {
            BOUNCE_TRY(const float v, number(j, p));
            s = glm::vec3(v);
        } else {
            BOUNCE_TRY(s, vec3(j, p));
        }
        if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) return err(p, "scale has a zero component");
        return s;
    }

    // Translation, rotation and scale of a transform or a keyframe (fields absent: identity).
    Expected<void> trs(const json& j, const std::string& p, TransformKey& key) const {
        if (j.contains("translation")) {
            BOUNCE_TRY(key.translation, vec3(j["translation"], p + "/translation"));
        }
        if (j.contains("rotation")) {
            BOUNCE_TRY(key.rotation, rotation(j["rotation"], p + "/rotation"));
        }
        if (j.contains("scale")) {
            BOUNCE_TRY(key.scale, scale(j["scale"], p + "/scale"));
        }
        return {};
    }

    Expected<glm::mat4> transform(const json& j, const std::string& p) const {
        BOUNCE_TRY_VOID(expectObject(j, p, "transform"));
        BOUNCE_TRY_VOID(checkKeys(j, p, "transform", {"translation", "rotation", "scale"}));
        TransformKey key;
        BOUNCE_TRY_VOID(trs(j, p, key));
        return glm::translate(glm::mat4(1.0f), key.translation) * glm::toMat4(key.rotation) *
               glm::scale(glm::mat4(1.0f), key.scale);
    }

    Expected<TransformTrack> animation(const json& j, const std::string& p) const {
        BOUNCE_TRY_VOID(expectObject(j, p, "animation"));
        BOUNCE_TRY_VOID(checkKeys(j, p, "animation", {"interpolation", "loop", "keys"}));
        TransformTrack track;
        if (j.contains("interpolation")) {
            BOUNCE_TRY(const std::string mode, text(j["interpolation"], p + "/interpolation"));
            if (mode == "linear") track.interpolation = Interpolation::Linear;
            else if (mode == "catmull-rom") track.interpolation = Interpolation::CatmullRom;
            else return err(p + "/interpolation", "unknown interpolation \"{}\" (known: linear, catmull-rom)", mode);
        }
        if (j.contains("loop")) {
            BOUNCE_TRY(track.loop, boolean(j["loop"], p + "/loop"));
        }
        if (!j.contains("keys") || !j["keys"].is_array() || j["keys"].empty())
            return err(p, "animation needs a non-empty \"keys\" array");
        const json& keys = j["keys"];
        for (size_t i = 0; i < keys.size(); ++i) {
            const std::string kp = p + "/keys/" + std::to_string(i);
            BOUNCE_TRY_VOID(expectObject(keys[i], kp, "animation key"));
            BOUNCE_TRY_VOID(checkKeys(keys[i], kp, "animation key", {"time", "translation", "rotation", "scale"}));
            if (!keys[i].contains("time")) return err(kp, "animation key needs \"time\" (seconds)");
            TransformKey key;
            BOUNCE_TRY(key.time, number(keys[i]["time"], kp + "/time"));
            if (!track.keys.empty() && key.time <= track.keys.back().time)
                return err(kp + "/time", "key times must increase ({} s after {} s)", key.time, track.keys.back().time);
            BOUNCE_TRY_VOID(trs(keys[i], kp, key));
            track.keys.push_back(key);
        }
        return track;
    }

    Expected<void> settings(const json& j, const std::string& p) {
        BOUNCE_TRY_VOID(expectObject(j, p, "settings"));
        for (const auto& [key, value] : j.items()) {
            const std::string vp = p + "/" + key;
            if (key.find('.') == std::string::npos) return err(vp, "setting \"{}\" is not of the form technique.setting", key);
            if (value.is_string()) m_scene.settings[key] = value.get<std::string>();
            else if (value.is_number() || value.is_boolean()) m_scene.settings[key] = value.dump();
            else return err(vp, "setting \"{}\" must be a string, number or boolean", key);
            if (const SceneSettingCheck& check = sceneSettingCheck()) {
                if (auto ok = check(key, m_scene.settings[key]); !ok.ok())
                    return err(vp, "setting \"{}\": {}", key, ok.error().message);
            }
        }
        return {};
    }

    Expected<void> materials(const json& j, const std::string& p) {
        BOUNCE_TRY_VOID(expectObject(j, p, "materials (name -> material)"));
        for (const auto& [name, value] : j.items()) {
            BOUNCE_TRY(Material m, material(value, p + "/" + name, name));
            m_materialIndex[name] = static_cast<uint32_t>(m_scene.materials.size());
            m_scene.materials.push_back(std::move(m));
        }
        return {};
    }

    Expected<Material> material(const json& j, const std::string& p, const std::string& name) {
        const std::string what = fmt::format("material '{}'", name);
        BOUNCE_TRY_VOID(expectObject(j, p, what));
        BOUNCE_TRY_VOID(checkKeys(j, p, what,
                                  {"baseColor", "baseColorTexture", "emission", "emissionTexture", "roughness", "metallic",
                                   "specularF0", "twoSided", "alphaMode", "alphaCutoff", "alpha", "alphaTexture",
                                   "normalTexture", "normalScale", "metallicRoughnessTexture"}));
        Material m;
        m.name = name;
        // Two-sided unless the file says otherwise, like the OBJ and PLY materials a JSON material
        // usually replaces (docs/scene.md "JSON scene files"): a surface wound the other way stays visible.
        m.twoSided = true;
        if (j.contains("baseColor")) {
            BOUNCE_TRY(m.baseColor, rgb(j["baseColor"], p + "/baseColor", 0.0f, 1.0f));
        }
        if (j.contains("emission")) {
            BOUNCE_TRY(m.emission, rgb(j["emission"], p + "/emission", 0.0f, kInf));
        }
        if (j.contains("roughness")) {
            BOUNCE_TRY(m.roughness, number(j["roughness"], p + "/roughness", 0.0f, 1.0f));
        }
        if (j.contains("metallic")) {
            BOUNCE_TRY(m.metallic, number(j["metallic"], p + "/metallic", 0.0f, 1.0f));
        }
        if (j.contains("specularF0")) {
            BOUNCE_TRY(m.specularF0, number(j["specularF0"], p + "/specularF0", 0.0f, 1.0f));
        }
        if (j.contains("twoSided")) {
            BOUNCE_TRY(m.twoSided, boolean(j["twoSided"], p + "/twoSided"));
        }
        if (j.contains("baseColorTexture")) {
            BOUNCE_TRY(m.baseColorTexture, materialTexture(j["baseColorTexture"], p + "/baseColorTexture", what, "base colour"));
        }
        if (j.contains("emissionTexture")) {
            BOUNCE_TRY(m.emissionTexture, materialTexture(j["emissionTexture"], p + "/emissionTexture", what, "emission"));
        }
        BOUNCE_TRY_VOID(alphaAndMaps(j, p, what, m));
        return m;
    }

    // Alpha masking, normal and metallic-roughness maps (docs/scene.md "JSON scene files"), read as
    // glTF defines them: MASK keeps texels whose coverage reaches alphaCutoff, BLEND is masked at 0.5.
    Expected<void> alphaAndMaps(const json& j, const std::string& p, const std::string& what, Material& m) {
        std::string mode = "opaque";
        if (j.contains("alphaMode")) {
            BOUNCE_TRY(mode, text(j["alphaMode"], p + "/alphaMode"));
            if (mode != "opaque" && mode != "mask" && mode != "blend")
                return err(p + "/alphaMode", "alphaMode \"{}\": expected \"opaque\", \"mask\" or \"blend\"", mode);
        }
        for (const char* key : {"alphaCutoff", "alpha", "alphaTexture"})
            if (j.contains(key) && mode == "opaque")
                return err(p + "/" + key, "{} needs \"alphaMode\": \"mask\" (or \"blend\")", key);
        if (mode != "opaque") {
            m.alphaCutoff = kDefaultAlphaCutoff;
            if (j.contains("alphaCutoff")) {
                BOUNCE_TRY(m.alphaCutoff, number(j["alphaCutoff"], p + "/alphaCutoff", 0.0f, 1.0f));
            }
            if (mode == "blend") {
                if (j.contains("alphaCutoff")) return err(p + "/alphaCutoff", "alphaCutoff applies to \"mask\" only");
                spdlog::warn("{}: {}: alphaMode blend is rendered as mask with alphaCutoff {} (no blending)", origin(p),
                             what, kDefaultAlphaCutoff);
            }
            if (j.contains("alpha")) {
                BOUNCE_TRY(m.alpha, number(j["alpha"], p + "/alpha", 0.0f, 1.0f));
            }
            if (j.contains("alphaTexture")) {
                BOUNCE_TRY(m.alphaTexture, materialTexture(j["alphaTexture"], p + "/alphaTexture", what, "alpha factor",
                                                           TextureUse::Coverage));
            } else if (j.contains("baseColorTexture")) {
                BOUNCE_TRY(m.alphaTexture, materialTexture(j["baseColorTexture"], p + "/baseColorTexture", what,
                                                           "alpha factor", TextureUse::Alpha));
            }
        }
        if (j.contains("normalTexture")) {
            BOUNCE_TRY(m.normalTexture, materialTexture(j["normalTexture"], p + "/normalTexture", what,
                                                        "interpolated normal", TextureUse::Linear));
        }
        if (j.contains("normalScale")) {
            BOUNCE_TRY(m.normalScale, number(j["normalScale"], p + "/normalScale", -kMaxNormalScale, kMaxNormalScale));
        }
        if (j.contains("metallicRoughnessTexture")) {
            BOUNCE_TRY(m.metallicRoughnessTexture,
                       materialTexture(j["metallicRoughnessTexture"], p + "/metallicRoughnessTexture", what,
                                       "roughness and metallic", TextureUse::Linear));
        }
        return {};
    }

    // A material's texture file: its index in Scene::textures, or -1 with a warning when it is missing
    // or unreadable (the material then keeps its `fallback` value alone).
    Expected<int> materialTexture(const json& j, const std::string& p, const std::string& what, const char* fallback,
                                  TextureUse use = TextureUse::SrgbColour) {
        BOUNCE_TRY(const std::string rel, text(j, p));
        const fs::path file = m_path.parent_path() / rel;
        Expected<Image> image = use == TextureUse::SrgbColour
                                    ? (fs::exists(file) ? readImage(file)
                                                        : Expected<Image>(makeError("{}: file not found", file.string())))
                                    : readTextureFile(file, use);
        if (!image.ok()) {
            spdlog::warn("{}: {}: texture unusable, using the {}: {}", origin(p), what, fallback, image.error().message);
            return -1;
        }
        m_scene.textures.push_back({file.string(), std::move(image.value())});
        return static_cast<int>(m_scene.textures.size() - 1);
    }

    Expected<void> objects(const json& j, const std::string& p) {
        if (!j.is_array() || j.empty()) return err(p, "\"objects\" must be a non-empty array");
        for (size_t i = 0; i < j.size(); ++i) BOUNCE_TRY_VOID(object(j[i], p + "/" + std::to_string(i), i));
        return {};
    }

    Expected<void> object(const json& j, const std::string& p, size_t index) {
        BOUNCE_TRY_VOID(expectObject(j, p, "an object"));
        std::string name = fmt::format("object-{}", index);
        if (j.contains("name")) {
            BOUNCE_TRY(name, text(j["name"], p + "/name"));
        }
        const std::string what = fmt::format("object '{}'", name);
        BOUNCE_TRY_VOID(checkKeys(j, p, what, {"name", "model", "transform", "material", "animation", "lights", "camera"}));
        if (!j.contains("model")) return err(p, "{}: needs \"model\" (a .gltf .glb .obj .ply path)", what);
        BOUNCE_TRY(const std::string rel, text(j["model"], p + "/model"));
        ModelPlacement placement;
        placement.name = name;
        placement.origin = origin(p + "/model") + ": " + what;
        if (j.contains("transform")) {
            BOUNCE_TRY(placement.transform, transform(j["transform"], p + "/transform"));
        }
        if (j.contains("material")) {
            const std::string mp = p + "/material";
            if (j["material"].is_string()) {
                const std::string ref = j["material"].get<std::string>();
                const auto it = m_materialIndex.find(ref);
                if (it == m_materialIndex.end()) {
                    std::set<std::string> known;
                    for (const auto& [k, v] : m_materialIndex) known.insert(k);
                    return err(mp, "{}: unknown material \"{}\" (known: {})", what, ref,
                               known.empty() ? "none" : joinKeys(known));
                }
                placement.materialOverride = static_cast<int>(it->second);
            } else {
                BOUNCE_TRY(Material m, material(j["material"], mp, name));
                placement.materialOverride = static_cast<int>(m_scene.materials.size());
                m_scene.materials.push_back(std::move(m));
            }
        }
        placement.importLights = false;
        placement.importCamera = false;
        if (j.contains("lights")) {
            BOUNCE_TRY(placement.importLights, boolean(j["lights"], p + "/lights"));
        }
        if (j.contains("camera")) {
            BOUNCE_TRY(placement.importCamera, boolean(j["camera"], p + "/camera"));
        }
        TransformTrack track;
        if (j.contains("animation")) {
            BOUNCE_TRY(track, animation(j["animation"], p + "/animation"));
        }
        const size_t first = m_scene.objects.size();
        BOUNCE_TRY(const ModelImportResult result, appendModel(m_scene, m_path.parent_path() / rel, placement));
        m_cameraFromModel = m_cameraFromModel || result.camera;
        // worldFromObject(t) = animation(t) * transform: the track moves the placed model as a whole.
        for (size_t o = first; o < m_scene.objects.size(); ++o) m_scene.objects[o].animation = track;
        return {};
    }

    Expected<void> lights(const json& j, const std::string& p) {
        if (!j.is_array()) return err(p, "\"lights\" must be an array");
        for (size_t i = 0; i < j.size(); ++i) BOUNCE_TRY_VOID(light(j[i], p + "/" + std::to_string(i), i));
        return {};
    }

    Expected<void> light(const json& j, const std::string& p, size_t index) {
        BOUNCE_TRY_VOID(expectObject(j, p, "a light"));
        Light l;
        l.name = fmt::format("light-{}", index);
        if (j.contains("name")) {
            BOUNCE_TRY(l.name, text(j["name"], p + "/name"));
        }
        const std::string what = fmt::format("light '{}'", l.name);
        if (!j.contains("type")) return err(p, "{}: needs \"type\" (point, spot, directional, area)", what);
        BOUNCE_TRY(const std::string type, text(j["type"], p + "/type"));
        std::set<std::string> keys = {"name", "type", "animation"};
        if (type == "point") {
            l.type = LightType::Point;
            keys.insert({"position", "intensity"});
        } else if (type == "spot") {
            l.type = LightType::Spot;
            keys.insert({"position", "direction", "target", "intensity", "cutoffDegrees", "falloffExponent"});
        } else if (type == "directional") {
            l.type = LightType::Directional;
            keys.insert({"direction", "irradiance"});
        } else if (type == "area") {
            l.type = LightType::Area;
            keys.insert({"position", "edgeU", "edgeV", "radiance", "texture", "twoSided"});
        } else {
            return err(p + "/type", "{}: unknown type \"{}\" (known: point, spot, directional, area)", what, type);
        }
        for (const char* areaOnly : {"texture", "twoSided"})
            if (l.type != LightType::Area && j.contains(areaOnly))
                return err(p + "/" + areaOnly, "{}: \"{}\" applies to area lights only, not to a {} light", what,
                           areaOnly, type);
        BOUNCE_TRY_VOID(checkKeys(j, p, what + " (" + type + ")", keys));
        const auto need = [&](const char* key) -> Expected<void> {
            if (!j.contains(key)) return err(p, "{}: a {} light needs \"{}\"", what, type, key);
            return {};
        };
        if (keys.count("position")) {
            BOUNCE_TRY_VOID(need("position"));
            BOUNCE_TRY(l.position, vec3(j["position"], p + "/position"));
        }
        if (keys.count("intensity")) {
            BOUNCE_TRY_VOID(need("intensity"));
            BOUNCE_TRY(l.intensity, rgb(j["intensity"], p + "/intensity", 0.0f, kInf));
        }
        if (l.type == LightType::Spot) {
            if (j.contains("direction") == j.contains("target"))
                return err(p, "{}: a spot light needs exactly one of \"direction\" and \"target\"", what);
            if (j.contains("direction")) {
                BOUNCE_TRY(l.direction, vec3(j["direction"], p + "/direction"));
            } else {
                BOUNCE_TRY(const glm::vec3 target, vec3(j["target"], p + "/target"));
                l.direction = target - l.position;
            }
            BOUNCE_TRY_VOID(need("cutoffDegrees"));
            BOUNCE_TRY(const float cutoff, number(j["cutoffDegrees"], p + "/cutoffDegrees"));
            // (0, 180] as docs/scene.md says: a zero cone lights nothing.
            if (!(cutoff > 0.0f) || cutoff > 180.0f)
                return valueErr(p + "/cutoffDegrees", "{}: value {} is outside (0, 180]", what, cutoff);
            l.cutoffAngle = glm::radians(cutoff);
            if (j.contains("falloffExponent")) {
                BOUNCE_TRY(l.falloffExponent, number(j["falloffExponent"], p + "/falloffExponent", 0.0f, kInf));
            }
        }
        if (l.type == LightType::Directional) {
            BOUNCE_TRY_VOID(need("direction"));
            BOUNCE_TRY(l.direction, vec3(j["direction"], p + "/direction"));
            BOUNCE_TRY_VOID(need("irradiance"));
            BOUNCE_TRY(l.irradiance, rgb(j["irradiance"], p + "/irradiance", 0.0f, kInf));
        }
        if (l.type == LightType::Spot || l.type == LightType::Directional) {
            if (!(glm::length(l.direction) > 0.0f)) return err(p, "{}: zero direction", what);
            l.direction = glm::normalize(l.direction);
        }
        if (l.type == LightType::Area) {
            BOUNCE_TRY_VOID(need("edgeU"));
            BOUNCE_TRY_VOID(need("edgeV"));
            BOUNCE_TRY_VOID(need("radiance"));
            BOUNCE_TRY(l.edgeU, vec3(j["edgeU"], p + "/edgeU"));
            BOUNCE_TRY(l.edgeV, vec3(j["edgeV"], p + "/edgeV"));
            BOUNCE_TRY(l.radiance, rgb(j["radiance"], p + "/radiance", 0.0f, kInf));
            if (!(l.area() > 0.0f)) return err(p, "{}: area light edges span zero area", what);
            if (j.contains("twoSided")) {
                BOUNCE_TRY(l.twoSided, boolean(j["twoSided"], p + "/twoSided"));
            }
            if (j.contains("texture")) {
                BOUNCE_TRY(l.texture, areaTexture(j["texture"], p + "/texture", what));
            }
        }
        if (j.contains("animation")) {
            BOUNCE_TRY(l.animation, animation(j["animation"], p + "/animation"));
        }
        m_scene.lights.push_back(std::move(l));
        return {};
    }

    // One emission image of an area light: a file relative to the scene, PNG/JPEG decoded from sRGB to
    // linear, EXR as stored; its texels are multipliers of the radiance, so they must be finite and
    // non-negative. Returns its index in Scene::textures.
    Expected<uint32_t> areaTextureImage(const json& j, const std::string& p, const std::string& what) {
        BOUNCE_TRY(const std::string rel, text(j, p));
        const fs::path file = m_path.parent_path() / rel;
        if (!fs::exists(file)) return err(p, "{}: texture {}: file not found", what, file.string());
        Expected<Image> image = readImage(file);
        if (!image.ok()) return err(p, "{}: texture unusable: {}", what, image.error().message);
        if (image->empty()) return err(p, "{}: texture {} is empty", what, file.string());
        if (Expected<void> finite = checkFinite(*image, file.string()); !finite.ok())
            return err(p, "{}: texture {}", what, finite.error().message);
        for (const glm::vec3& texel : image->pixels())
            if (texel.r < 0.0f || texel.g < 0.0f || texel.b < 0.0f)
                return err(p, "{}: texture {} has a negative texel (texels multiply the radiance)", what, file.string());
        const auto index = static_cast<uint32_t>(m_scene.textures.size());
        m_scene.textures.push_back({file.string(), std::move(image.value())});
        return index;
    }

    // An area light's "texture": an image path, {"frames": [paths], "frameRate": fps}, or
    // {"pattern": "bouncing-square", ...} (docs/scene.md "Lights").
    Expected<AreaTexture> areaTexture(const json& j, const std::string& p, const std::string& what) {
        AreaTexture t;
        if (j.is_string()) {
            t.kind = AreaTexture::Kind::Images;
            BOUNCE_TRY(const uint32_t index, areaTextureImage(j, p, what));
            t.frames = {index};
            return t;
        }
        if (!j.is_object())
            return err(p, "{}: \"texture\" must be an image path, {{\"frames\": [...]}} or {{\"pattern\": ...}}", what);
        if (j.contains("frames") == j.contains("pattern"))
            return err(p, "{}: a texture object needs exactly one of \"frames\" (an image sequence) and \"pattern\"", what);
        if (j.contains("frames")) {
            BOUNCE_TRY_VOID(checkKeys(j, p, what + " texture", {"frames", "frameRate"}));
            t.kind = AreaTexture::Kind::Images;
            const json& frames = j["frames"];
            if (!frames.is_array() || frames.empty())
                return err(p + "/frames", "{}: \"frames\" must be a non-empty array of image paths", what);
            for (size_t i = 0; i < frames.size(); ++i) {
                const std::string fp = p + "/frames/" + std::to_string(i);
                BOUNCE_TRY(const uint32_t index, areaTextureImage(frames[i], fp, what));
                const Image& first = m_scene.textures[t.frames.empty() ? index : t.frames.front()].image;
                const Image& image = m_scene.textures[index].image;
                if (image.width() != first.width() || image.height() != first.height())
                    return err(fp, "{}: frame {} is {}x{}, frame 0 is {}x{}: all frames must be the same size", what, i,
                               image.width(), image.height(), first.width(), first.height());
                t.frames.push_back(index);
            }
            if (j.contains("frameRate")) {
                BOUNCE_TRY(t.frameRate, number(j["frameRate"], p + "/frameRate", 0.0f, kMaxTextureFrameRate));
                if (!(t.frameRate > 0.0f)) return err(p + "/frameRate", "{}: texture frame rate must be positive", what);
            }
            return t;
        }
        BOUNCE_TRY_VOID(checkKeys(j, p, what + " texture pattern", {"pattern", "resolution", "size", "velocity", "start"}));
        BOUNCE_TRY(const std::string pattern, text(j["pattern"], p + "/pattern"));
        if (pattern != "bouncing-square")
            return err(p + "/pattern", "{}: unknown texture pattern \"{}\" (known: bouncing-square)", what, pattern);
        t.kind = AreaTexture::Kind::BouncingSquare;
        if (j.contains("resolution")) {
            const json& r = j["resolution"];
            if (!r.is_number_integer() || r.get<int64_t>() < 1 || r.get<int64_t>() > kMaxAreaTextureResolution)
                return err(p + "/resolution", "{}: resolution must be an integer in [1, {}] (texels per side)", what,
                           kMaxAreaTextureResolution);
            t.resolution = static_cast<int>(r.get<int64_t>());
        }
        if (j.contains("size")) {
            BOUNCE_TRY(t.squareSize, number(j["size"], p + "/size", 0.0f, 1.0f));
            if (!(t.squareSize > 0.0f)) return err(p + "/size", "{}: square size must be in (0, 1]", what);
        }
        if (j.contains("velocity")) {
            BOUNCE_TRY(t.squareVelocity, vec2(j["velocity"], p + "/velocity", -kInf, kInf));
        }
        if (j.contains("start")) {
            BOUNCE_TRY(t.squareStart, vec2(j["start"], p + "/start", 0.0f, 1.0f));
        }
        return t;
    }

    // One open box {"min": [x, y, z], "max": [x, y, z]} (metres) of "leakRegions".
    Expected<void> leakBox(const json& j, const std::string& p, const char* room, glm::vec3& lo, glm::vec3& hi) const {
        const std::string what = fmt::format("leak region '{}'", room);
        BOUNCE_TRY_VOID(expectObject(j, p, what + " ({\"min\": [x, y, z], \"max\": [x, y, z]})"));
        BOUNCE_TRY_VOID(checkKeys(j, p, what, {"min", "max"}));
        if (!j.contains("min") || !j.contains("max")) return err(p, "{}: needs \"min\" and \"max\" (corners, metres)", what);
        BOUNCE_TRY(lo, vec3(j["min"], p + "/min"));
        BOUNCE_TRY(hi, vec3(j["max"], p + "/max"));
        // The box is open (metrics/LightLeak.h boxMask: strictly inside), so min = max on an axis holds no point.
        for (int a = 0; a < 3; ++a)
            if (!(lo[a] < hi[a]))
                return valueErr(p + "/max", "{}: max {} is not above min {} on {} (an empty box)", what, hi[a], lo[a], "xyz"[a]);
        return {};
    }

    // "leakRegions": {"dark": box, "lit": box}: where no light must arrive and what normalises the
    // score (scene/Scene.h LeakRegions), for `bounce sweep` and `bounce compare --leak-scene`.
    Expected<void> leakRegions(const json& j, const std::string& p) {
        BOUNCE_TRY_VOID(expectObject(j, p, "leakRegions ({\"dark\": box, \"lit\": box})"));
        BOUNCE_TRY_VOID(checkKeys(j, p, "leakRegions", {"dark", "lit"}));
        if (!j.contains("dark") || !j.contains("lit"))
            return err(p, "leakRegions needs \"dark\" (where no light arrives) and \"lit\" (the lit reference region)");
        LeakRegions r;
        BOUNCE_TRY_VOID(leakBox(j["dark"], p + "/dark", "dark", r.darkMin, r.darkMax));
        BOUNCE_TRY_VOID(leakBox(j["lit"], p + "/lit", "lit", r.litMin, r.litMax));
        // Open boxes share a point exactly when their ranges overlap with positive length on every axis;
        // a pixel in both would count as leak and as the light that normalises it.
        bool overlap = true;
        for (int a = 0; a < 3; ++a) overlap = overlap && std::max(r.darkMin[a], r.litMin[a]) < std::min(r.darkMax[a], r.litMax[a]);
        if (overlap) return err(p + "/lit", "leakRegions: the dark and the lit boxes overlap (a surface point would be in both)");
        m_scene.leakRegions = r;
        return {};
    }

    Expected<void> camera(const json& j, const std::string& p) {
        BOUNCE_TRY_VOID(expectObject(j, p, "camera"));
        BOUNCE_TRY_VOID(checkKeys(j, p, "camera",
                                  {"position", "target", "up", "fovDegrees", "projection", "orthoHeight", "near", "far", "animation"}));
        Camera& c = m_scene.camera;
        if (!j.contains("position") || !j.contains("target")) return err(p, "camera needs \"position\" and \"target\"");
        BOUNCE_TRY(c.position, vec3(j["position"], p + "/position"));
        BOUNCE_TRY(c.target, vec3(j["target"], p + "/target"));
        if (c.position == c.target) return err(p + "/target", "camera target equals its position");
        if (j.contains("up")) {
            BOUNCE_TRY(c.up, vec3(j["up"], p + "/up"));
        }
        if (j.contains("projection")) {
            BOUNCE_TRY(const std::string proj, text(j["projection"], p + "/projection"));
            if (proj == "perspective") c.projection = Projection::Perspective;
            else if (proj == "orthographic") c.projection = Projection::Orthographic;
            else return err(p + "/projection", "unknown projection \"{}\" (known: perspective, orthographic)", proj);
        }
        if (j.contains("fovDegrees")) {
            BOUNCE_TRY(const float fov, number(j["fovDegrees"], p + "/fovDegrees", 0.0f, 180.0f));
            if (!(fov > 0.0f && fov < 180.0f)) return err(p + "/fovDegrees", "field of view must be in (0, 180) degrees");
            c.verticalFov = glm::radians(fov);
        }
        if (j.contains("orthoHeight")) {
            BOUNCE_TRY(c.orthoHeight, number(j["orthoHeight"], p + "/orthoHeight", 1e-6f, kInf));
        }
        if (j.contains("near")) {
            BOUNCE_TRY(c.nearPlane, number(j["near"], p + "/near", 1e-6f, kInf));
        }
        if (j.contains("far")) {
            BOUNCE_TRY(c.farPlane, number(j["far"], p + "/far", 1e-6f, kInf));
        }
        if (j.contains("animation")) {
            BOUNCE_TRY(c.animation, animation(j["animation"], p + "/animation"));
        }
        return {};
    }

    fs::path m_path;
    JsonLocator m_locator;
    Scene m_scene;
    std::map<std::string, uint32_t> m_materialIndex;
    bool m_cameraFromModel = false;
};

}  // namespace

Expected<Scene> loadJsonScene(const fs::path& path) {
    BOUNCE_TRY(const std::string text, readTextFile(path));
    BOUNCE_TRY(const json root, parseJsonDocument(text, path.string()));
    JsonSceneReader reader(path, text);
    return reader.read(root);
}

}  // namespace bounce
