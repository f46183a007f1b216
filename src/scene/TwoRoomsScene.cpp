// two-rooms: two rooms side by side sharing one thin wall, a point light in one (the "lit" room, x < 0)
// and none in the other (the "dark" room, x > 0). It measures light leaking through thin geometry:
// the true radiance of every dark-room surface is zero.
//
// Both rooms are open at the top so a camera above sees into both, with no reliance on back-face
// culling. Nothing is above the walls, so an open top is the same as a perfectly black ceiling: a ray
// from inside either room (or from the light, below the wall tops) that crosses the shared wall's plane
// does so below the wall tops and hits the wall, and a ray that leaves upward never returns. Hence the
// dark room receives no light at all, by any number of bounces. Details: docs/scene.md "two-rooms".
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>

namespace bounce {

namespace {
constexpr float kRoomWidth = 2.0f;    // metres along x, per room
constexpr float kRoomDepth = 2.0f;    // metres along z, z in [-1, 1]
constexpr float kRoomHeight = 1.0f;   // metres, wall tops
constexpr int kSubdivisions = 4;      // cells per wall edge: vertices for per-vertex techniques
constexpr double kDefaultWallThickness = 0.02;  // metres
constexpr double kMaxWallThickness = 0.5;       // metres, keeps the rooms' proportions
constexpr glm::vec3 kWhiteAlbedo{0.75f};
// Point light in the middle of the lit room at 0.6 m: the floor below gets E = I / 0.36 m^2, radiance
// 0.75 * E / pi = 1 W/(m^2 sr) for I = 1.5 W/sr, well exposed with ACES at 0 EV.
constexpr float kLightHeight = 0.6f;             // metres
constexpr glm::vec3 kLightIntensity{1.5f};       // W/sr
}  // namespace

Expected<Scene> buildTwoRooms(const SceneParams& params) {
    BOUNCE_TRY(const double thicknessParam,
               numberParam(params, "two-rooms", "wallThickness", kDefaultWallThickness, 0.0, kMaxWallThickness));
    if (!(thicknessParam > 0.0)) return makeError("scene 'two-rooms': wallThickness must be positive");
    const float t = static_cast<float>(thicknessParam);
    const float h = 0.5f * t;  // the shared wall is x in [-h, h]
    const float d = 0.5f * kRoomDepth;

    Scene s;
    s.name = "two-rooms";
    s.source = "builtin:two-rooms";
    Material white;
    white.name = "white";
    white.baseColor = kWhiteAlbedo;
    s.materials.push_back(white);

    const auto object = [&](Mesh mesh) {
        Object o;
        o.name = mesh.name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        o.material = 0;
        s.meshes.push_back(std::move(mesh));
        s.objects.push_back(std::move(o));
    };
    const glm::vec3 up(0, 1, 0);
    // One room: floor and three outer walls facing inward; `sign` is -1 for the lit room (x < 0).
    const auto room = [&](const std::string& prefix, float sign) {
        const float inner = sign * h, outer = sign * (h + kRoomWidth);
        const float x0 = std::min(inner, outer), x1 = std::max(inner, outer);
        MeshBuilder floor(prefix + "-floor");
        floor.quad({x0, 0, -d}, {x1, 0, -d}, {x1, 0, d}, {x0, 0, d}, up, kSubdivisions, kSubdivisions);
        object(floor.take());
        MeshBuilder walls(prefix + "-walls");
        const float H = kRoomHeight;
        walls.quad({outer, 0, -d}, {outer, 0, d}, {outer, H, d}, {outer, H, -d}, {-sign, 0, 0}, kSubdivisions,
                   kSubdivisions);
        walls.quad({x0, 0, -d}, {x1, 0, -d}, {x1, H, -d}, {x0, H, -d}, {0, 0, 1}, kSubdivisions, kSubdivisions);
        walls.quad({x0, 0, d}, {x1, 0, d}, {x1, H, d}, {x0, H, d}, {0, 0, -1}, kSubdivisions, kSubdivisions);
        object(walls.take());
    };
    room("lit", -1.0f);
    room("dark", 1.0f);
    MeshBuilder wall("shared-wall");
    wall.axisBox({-h, 0.0f, -d}, {h, kRoomHeight, d}, /*outward=*/true, kSubdivisions);
    object(wall.take());

    Light light;
    light.name = "lit-light";
    light.type = LightType::Point;
    light.position = glm::vec3(-(h + 0.5f * kRoomWidth), kLightHeight, 0.0f);
    light.intensity = kLightIntensity;
    s.lights.push_back(light);

    // The rooms as metrics/LightLeak.h's twoRoomsMasks splits them: x beyond the shared wall's faces.
    constexpr float kBeyond = 1e3f;  // metres: "everything on that side"
    s.leakRegions = LeakRegions{{h, -kBeyond, -kBeyond}, {kBeyond, kBeyond, kBeyond},
                                {-kBeyond, -kBeyond, -kBeyond}, {-h, kBeyond, kBeyond}};

    // Looking down from above, slightly over the dark room so the dark face of the shared wall is in view.
    // The camera stays inside the rooms' footprint, so every outer wall is seen from its front side.
    s.camera.position = glm::vec3(0.3f, 5.0f, 0.4f);  // metres
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    s.camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
    s.camera.verticalFov = glm::radians(50.0f);
    s.camera.nearPlane = 0.05f;  // metres
    s.camera.farPlane = 20.0f;   // metres
    return s;
}

}  // namespace bounce
