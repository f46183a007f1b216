// furnace: a closed, inward-facing 2 m cube whose every surface has albedo rho and emits radiance Le,
// with no lights. The exact radiance everywhere is Le / (1 - rho) (docs/scene.md, analytic-tests.md).
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>

namespace bounce {

namespace {
constexpr float kHalfSize = 1.0f;      // metres: the room is [-1, 1]^3
constexpr int kWallSubdivisions = 4;   // 4 x 4 cells per wall: vertices for per-vertex techniques
constexpr double kDefaultAlbedo = 0.5;
constexpr double kDefaultEmission = 1.0;  // W/(m^2 sr)
constexpr double kMaxEmission = 1e6;      // W/(m^2 sr), a sanity bound only
}  // namespace

Expected<Scene> buildFurnace(const SceneParams& params) {
    BOUNCE_TRY(const double albedo, numberParam(params, "furnace", "albedo", kDefaultAlbedo, 0.0, 1.0));
    BOUNCE_TRY(const double emission, numberParam(params, "furnace", "emission", kDefaultEmission, 0.0, kMaxEmission));

    Scene s;
    s.name = "furnace";
    s.source = "builtin:furnace";
    Material m;
    m.name = "furnace";
    m.baseColor = glm::vec3(static_cast<float>(albedo));
    m.emission = glm::vec3(static_cast<float>(emission));
    m.roughness = 1.0f;
    m.specularF0 = 0.0f;
    s.materials.push_back(m);

    MeshBuilder mb("room");
    mb.axisBox(glm::vec3(-kHalfSize), glm::vec3(kHalfSize), /*outward=*/false, kWallSubdivisions);
    Object o;
    o.name = "room";
    o.mesh = 0;
    o.material = 0;
    s.meshes.push_back(mb.take());
    s.objects.push_back(o);

    // Inside, off-centre so the view holds a wall, the floor and a corner (any view reads Le/(1-rho)).
    s.camera.position = glm::vec3(0.3f, 0.2f, 0.6f);  // metres
    s.camera.target = glm::vec3(-0.2f, -0.3f, -1.0f);
    s.camera.verticalFov = glm::radians(60.0f);
    s.camera.nearPlane = 0.01f;  // metres
    s.camera.farPlane = 10.0f;   // metres, beyond the room's 3.5 m diagonal
    // Hemicube radiosity: the walls are uniform, so 0.25 m elements (3 x 3 per 0.5 m cell) resolve the
    // exact solution; the default 0.05 m would give 11,616 elements, a minute per gather frame.
    for (const char* t : {"radiosity-gather", "radiosity-pr", "radiosity-incremental", "radiosity-cross"})
        s.settings[std::string(t) + ".elementSize"] = "0.25";
    return s;
}

}  // namespace bounce
