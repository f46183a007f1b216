#include "scene/SceneLoader.h"

#include "scene/BuiltinScenes.h"

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
    };
    return entries;
}

std::string knownBuiltins() {
    std::string names;
    for (const BuiltinEntry& e : registry()) names += (names.empty() ? "" : ", ") + e.info.name;
    return names;
}

}  // namespace

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
    return makeError("{}: loading scene files is not available in this build", name);
}

}  // namespace bounce
