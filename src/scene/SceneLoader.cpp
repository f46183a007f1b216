#include "scene/SceneLoader.h"

#include "scene/BuiltinScenes.h"
#include "scene/JsonSceneLoader.h"
#include "scene/ModelLoader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace bounce {

namespace {

using Builder = Expected<Scene> (*)(const SceneParams&);

struct BuiltinEntry {
    BuiltinSceneInfo info;
    Builder build;
};

const std::vector<BuiltinEntry>& registry() {
    static const std::vector<BuiltinEntry> entries = {
        {{"cornell-box",
          "Cornell box (measured geometry and albedos), spot light under the ceiling pointing down",
          {}},
         buildCornellBox},
        {{"cornell-box-area", "Cornell box lit by its rectangular ceiling area light", {}}, buildCornellBoxArea},
        {{"cornell-box-dynamic",
          "Cornell box with the spot light orbiting (Catmull-Rom loop) and the tall block turning; 4 s loop",
          {}},
         buildCornellBoxDynamic},
        {{"cornell-box-rotating",
          "Cornell box (area light, no blocks) with one white box turning in its centre, 8 s per turn; van de "
          "Hoef 2013's radiosity scene",
          {{"light", "large: ceiling light, large (the data's rectangle doubled per side) or small (the data's "
                     "rectangle); both emit the same flux"}}},
         buildCornellBoxRotating},
        {{"furnace",
          "Closed 2 m cube, every surface of albedo rho emitting Le, no lights: radiance is Le/(1-rho) everywhere",
          {{"albedo", "0.5: albedo rho of every surface, in [0, 1]"},
           {"emission", "1.0: emitted radiance Le of every surface, W/(m^2 sr)"}}},
         buildFurnace},
        {{"two-rooms",
          "Two open-topped rooms sharing a thin wall, a point light in the lit room (x < 0) only; the dark room "
          "(x > 0) has zero radiance, so any light there is leakage",
          {{"wallThickness", "0.02: thickness of the shared wall, metres, in (0, 0.5]"}}},
         buildTwoRooms},
        {{"atrium",
          "Procedural courtyard with two storeys of arcades, drapes and a fountain, open sky and sun; the "
          "Sponza-class stand-in",
          {{"triangles", "100000: triangle budget; the tessellation lands within 10 %"}}},
         buildAtrium},
        {{"courtyard",
          "The atrium with alpha-masked foliage (bushes in planters, hanging ivy; a procedural leaf mask) at "
          "Sponza-class size, lit by the sun or a sky-sized area light over the open roof",
          {{"triangles", "150000: triangle budget (foliage included); the tessellation lands within 10 %"},
           {"light", "sun: the atrium's sun; sky: a 12 m x 20 m area light over the open roof instead"}}},
         buildCourtyard},
        {{"indirect-light",
          "Closed 4 m x 2.6 m x 4 m room, albedo 0.9 everywhere, lit only by a daylight window (area light) on "
          "the right that the camera does not see; a 0.5 m box turning on the floor, 8 s per turn; van de Hoef "
          "2013's radiosity scene",
          {}},
         buildIndirectLight},
        {{"area-screen",
          "A 1.6 m x 0.9 m textured, animated screen (the only light, one-sided) facing a stage of diffuse and "
          "glossy boxes and spheres; Nichols 2010 ch. 5's set-up",
          {{"pattern", "bars: the screen's video, bars (a colour-bar test card of 4 frames at 2 fps) or square (a "
                       "white square bouncing on black); both emit the same mean flux"},
           {"squareSize", "0.25: pattern=square's side as a fraction of the screen's, in [1/256, 1] (same mean flux at "
                          "any size; the texture gets finer below 1/32 so that the square spans two texels)"}}},
         buildAreaScreen},
        {{"furnished-room",
          "Closed 4 m x 2.6 m x 4 m living room lit by a spot pointing at the ceiling, with an open bookshelf and "
          "a table casting large indirect shadows (the floor under the table, the shelf's compartments)",
          {{"furniture", "all: the shelf and the table; none: the empty room (same walls, light and camera)"}}},
         buildFurnishedRoom},
    };
    return entries;
}

SceneSettingCheck& settingCheck() {
    static SceneSettingCheck check;
    return check;
}

std::string knownBuiltins() {
    std::string names;
    for (const BuiltinEntry& e : registry()) names += (names.empty() ? "" : ", ") + e.info.name;
    return names;
}

}  // namespace

void setSceneSettingCheck(SceneSettingCheck check) { settingCheck() = std::move(check); }
const SceneSettingCheck& sceneSettingCheck() { return settingCheck(); }

const std::vector<BuiltinSceneInfo>& builtinScenes() {
    static const std::vector<BuiltinSceneInfo> infos = [] {
        std::vector<BuiltinSceneInfo> out;
        for (const BuiltinEntry& e : registry()) out.push_back(e.info);
        return out;
    }();
    return infos;
}

Expected<Scene> loadScene(std::string_view nameOrPath, const SceneParams& params) {
    const std::string name(nameOrPath);
    const auto& entries = registry();
    const auto it = std::find_if(entries.begin(), entries.end(), [&](const BuiltinEntry& e) { return e.info.name == name; });
    if (it != entries.end()) {
        for (const auto& [key, value] : params) {
            if (it->info.params.count(key)) continue;
            std::string known;
            for (const auto& [k, doc] : it->info.params) known += (known.empty() ? "" : ", ") + k;
            return makeError("scene '{}': unknown parameter '{}' (known: {})", name, key,
                             known.empty() ? "none" : known);
        }
        BOUNCE_TRY(Scene scene, it->build(params));
        BOUNCE_TRY_VOID(finalizeScene(scene));
        return scene;
    }

    std::string ext = std::filesystem::path(name).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool isFile = ext == ".json" || ext == ".gltf" || ext == ".glb" || ext == ".obj" || ext == ".ply";
    if (!isFile)
        return makeError("unknown scene '{}' (built-ins: {}; or a scene file .json .gltf .glb .obj .ply)", name,
                         knownBuiltins());
    if (!params.empty())
        return makeError("{}: scene parameters ({}) apply to built-in scenes only", name, params.begin()->first);
    const std::filesystem::path path(name);
    if (!std::filesystem::exists(path)) return makeError("{}: scene file not found", name);
    Expected<Scene> scene = ext == ".json" ? loadJsonScene(path) : loadModelScene(path);
    if (!scene.ok()) return scene.error();
    BOUNCE_TRY_VOID(finalizeScene(*scene));
    return scene;
}

}  // namespace bounce
