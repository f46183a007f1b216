// furnished-room: a closed living room lit by a spot pointing at the ceiling (an uplight), with an open
// bookshelf against the back wall and a table: furniture that casts large indirect shadows. The spot's
// cone reaches the ceiling and the tops of the walls only, so the floor, the furniture and most of the
// walls are lit by one bounce off the ceiling, and the floor under the table and the shelf's
// compartments see that ceiling only partly: the test scene of the RSM-family gathers' optional VPL
// visibility (docs/techniques/rsm.md, "VPL visibility"), which without visibility put several times the
// one-bounce light there. Parameter `furniture=none` empties the room (same walls, light and camera):
// the case where visibility must change nothing. Details: docs/scene.md "furnished-room".
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>

namespace bounce {

namespace {

// The room: x in [-2, 2], floor y = 0, z in [-2, 2] (the back wall at z = -2 faces the camera); a
// living-room size, bounce's choice.
constexpr float kRoomHalfWidth = 2.0f;  // metres
constexpr float kRoomHeight = 2.6f;     // metres, a common ceiling height
constexpr float kRoomHalfDepth = 2.0f;  // metres
// Cells per wall edge: vertices for per-vertex techniques and smaller elements for the ones that
// split geometry; 8 keeps the room at 768 triangles.
constexpr int kWallCells = 8;

// Albedos (linear RGB), Lambertian: white paint, a light oak floor, a darker wood for the furniture.
// Bounce's choices (typical paint and wood reflectances), not measured data.
constexpr glm::vec3 kPaintAlbedo{0.8f};
constexpr glm::vec3 kFloorAlbedo{0.55f, 0.42f, 0.3f};
constexpr glm::vec3 kWoodAlbedo{0.45f, 0.32f, 0.2f};

// The table: a 1.2 m x 0.8 m top, 4 cm thick, 0.76 m high (a common dining-table height), on four 5 cm
// legs set 5 cm in from the corners; front-left of the room, its long side along x.
constexpr glm::vec3 kTableCentre{-0.6f, 0.0f, -0.2f};  // metres, centre of its footprint
constexpr float kTableHalfLength = 0.6f, kTableHalfWidth = 0.4f;  // metres
constexpr float kTableHeight = 0.76f, kTableTopThickness = 0.04f;  // metres
constexpr float kLegSide = 0.05f, kLegInset = 0.05f;              // metres

// The bookshelf: 1.2 m wide, 1.8 m high, 0.4 m deep, against the back wall right of centre, open
// toward the room; 2 cm side panels and five 2 cm boards (bottom, three shelves, top) make four
// compartments 0.43 m high. The back wall closes it (no back panel).
constexpr float kShelfCentreX = 0.9f;         // metres
constexpr float kShelfHalfWidth = 0.6f;       // metres
constexpr float kShelfHeight = 1.8f;          // metres
constexpr float kShelfDepth = 0.4f;           // metres
constexpr float kPanelThickness = 0.02f;      // metres
constexpr int kShelfBoards = 5;               // bottom, three shelves, top

// The uplight: a spot 1.3 m above the floor, right of the room's centre, pointing straight up with a
// 55 degree cutoff (at most 60 degrees: one perspective RSM, the thesis's case) and a cos^1 falloff. Its
// cone meets the ceiling in a disc of radius 1.3 m x tan 55 = 1.86 m and the right, front and back walls
// above 2.3-2.4 m; nothing below the spot's height is lit directly. 10 W/sr puts the ceiling above it at
// E = 10 / 1.3^2 = 5.9 W/m^2 (radiance 1.5 W/(m^2 sr)) and the indirectly lit floor near 0.3 W/(m^2 sr).
constexpr glm::vec3 kLightPosition{-0.5f, 1.4f, -0.3f};  // metres
constexpr float kLightCutoffDegrees = 35.0f;
constexpr float kLightFalloff = 1.0f;
constexpr glm::vec3 kLightIntensity{40.0f};  // W/sr

// The camera: eye height 1.1 m near the front wall, looking toward the back left, 60 degree vertical
// field of view: the floor under the table (visible between its top and the floor from this height), the
// shelf's compartments, the back and left walls and part of the ceiling are in view.
constexpr glm::vec3 kCameraPosition{0.7f, 1.1f, 1.85f};  // metres
constexpr glm::vec3 kCameraTarget{-0.2f, 0.7f, -1.6f};   // metres
constexpr float kCameraFovDegrees = 60.0f;

}  // namespace

Expected<Scene> buildFurnishedRoom(const SceneParams& params) {
    BOUNCE_TRY(const std::string furniture, choiceParam(params, "furnished-room", "furniture", "all", {"all", "none"}));
    Scene s;
    s.name = "furnished-room";
    s.source = "builtin:furnished-room";
    const auto material = [&](const char* name, glm::vec3 albedo) {
        Material m;
        m.name = name;
        m.baseColor = albedo;
        m.roughness = 1.0f;
        m.metallic = 0.0f;
        m.specularF0 = 0.0f;
        s.materials.push_back(m);
        return static_cast<uint32_t>(s.materials.size() - 1);
    };
    const uint32_t paint = material("paint", kPaintAlbedo);
    const uint32_t floorWood = material("floor", kFloorAlbedo);
    const uint32_t wood = material("wood", kWoodAlbedo);
    const auto object = [&](Mesh mesh, uint32_t mat) {
        Object o;
        o.name = mesh.name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        o.material = mat;
        s.meshes.push_back(std::move(mesh));
        s.objects.push_back(std::move(o));
    };

    const float x0 = -kRoomHalfWidth, x1 = kRoomHalfWidth, z0 = -kRoomHalfDepth, z1 = kRoomHalfDepth;
    const float y1 = kRoomHeight;
    const auto wall = [&](const char* name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 front,
                          uint32_t mat) {
        MeshBuilder mb(name);
        mb.quad(a, b, c, d, front, kWallCells, kWallCells);
        object(mb.take(), mat);
    };
    wall("floor", {x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}, {0, 1, 0}, floorWood);
    wall("ceiling", {x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, {0, -1, 0}, paint);
    wall("left", {x0, 0, z0}, {x0, 0, z1}, {x0, y1, z1}, {x0, y1, z0}, {1, 0, 0}, paint);
    wall("right", {x1, 0, z0}, {x1, 0, z1}, {x1, y1, z1}, {x1, y1, z0}, {-1, 0, 0}, paint);
    wall("back", {x0, 0, z0}, {x1, 0, z0}, {x1, y1, z0}, {x0, y1, z0}, {0, 0, 1}, paint);
    wall("front", {x0, 0, z1}, {x1, 0, z1}, {x1, y1, z1}, {x0, y1, z1}, {0, 0, -1}, paint);

    if (furniture == "all") {
        MeshBuilder table("table");
        const glm::vec3 c = kTableCentre;
        table.axisBox(c + glm::vec3(-kTableHalfLength, kTableHeight - kTableTopThickness, -kTableHalfWidth),
                      c + glm::vec3(kTableHalfLength, kTableHeight, kTableHalfWidth));
        for (int i = 0; i < 4; ++i) {
            const float sx = (i & 1) ? 1.0f : -1.0f, sz = (i & 2) ? 1.0f : -1.0f;
            const glm::vec3 corner = c + glm::vec3(sx * (kTableHalfLength - kLegInset), 0.0f, sz * (kTableHalfWidth - kLegInset));
            const glm::vec3 inward(-sx * kLegSide, 0.0f, -sz * kLegSide);
            const glm::vec3 lo = glm::min(corner, corner + inward), hi = glm::max(corner, corner + inward);
            table.axisBox(lo, glm::vec3(hi.x, kTableHeight - kTableTopThickness, hi.z));
        }
        object(table.take(), wood);

        MeshBuilder shelf("bookshelf");
        const float sx0 = kShelfCentreX - kShelfHalfWidth, sx1 = kShelfCentreX + kShelfHalfWidth;
        const float front = z0 + kShelfDepth;
        shelf.axisBox({sx0, 0.0f, z0}, {sx0 + kPanelThickness, kShelfHeight, front});
        shelf.axisBox({sx1 - kPanelThickness, 0.0f, z0}, {sx1, kShelfHeight, front});
        for (int k = 0; k < kShelfBoards; ++k) {
            const float pitch = (kShelfHeight - kPanelThickness) / static_cast<float>(kShelfBoards - 1);
            const float y = pitch * static_cast<float>(k);
            shelf.axisBox({sx0 + kPanelThickness, y, z0}, {sx1 - kPanelThickness, y + kPanelThickness, front});
        }
        object(shelf.take(), wood);
    }

    Light light;
    light.name = "uplight";
    light.type = LightType::Spot;
    light.position = kLightPosition;
    light.direction = glm::vec3(0.0f, 1.0f, 0.0f);
    light.cutoffAngle = glm::radians(kLightCutoffDegrees);
    light.falloffExponent = kLightFalloff;
    light.intensity = kLightIntensity;
    s.lights.push_back(light);

    s.camera.position = kCameraPosition;
    s.camera.target = kCameraTarget;
    s.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    s.camera.verticalFov = glm::radians(kCameraFovDegrees);
    s.camera.nearPlane = 0.01f;  // metres; the front wall is 0.15 m behind the camera
    s.camera.farPlane = 10.0f;   // metres; beyond the room's 6.2 m diagonal
    return s;
}

}  // namespace bounce
