// indirect-light: van de Hoef 2013's "Indirect light" test scene for radiosity, a closed room painted
// bright white and lit only by daylight entering through a window on the right, with one rotating box as
// the dynamic object. The window is a rectangular area light set in an opening of the right wall (as
// cornell-box-area's light sits in an opening of its ceiling); the camera does not see it, so most of
// what the image shows is lit indirectly. Every surface is a planar quad (radiosity works on quads).
// Details: docs/scene.md "indirect-light".
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>

namespace bounce {

namespace {

// The room: x in [-2, 2] (the right wall at +2, seen from the camera), floor y = 0, z in [-2, 2]; a
// living-room size chosen here, not taken from the thesis.
constexpr float kRoomWidth = 4.0f;   // metres along x
constexpr float kRoomHeight = 2.6f;  // metres, a common ceiling height
constexpr float kRoomDepth = 4.0f;   // metres along z

// "Bright white paint" of albedo 0.9 on every surface (van de Hoef 2013 sec. 5.1), grey (no tint).
constexpr glm::vec3 kPaintAlbedo{0.9f};

// The window on the right wall (x = +2): 1.4 m wide (along z) by 1.2 m tall with its sill at 0.9 m (a
// common residential window), centred at z = +1.0 m, in the room's front half: behind the camera's right
// frustum plane (see the camera below), so daylight falls into the view from the right without the window
// being in it.
constexpr float kWindowWidth = 1.4f;    // metres along z
constexpr float kWindowHeight = 1.2f;   // metres along y
constexpr float kWindowSill = 0.9f;     // metres above the floor
constexpr float kWindowCentreZ = 1.0f;  // metres

// Daylight radiance, white. The room is nearly closed and every surface reflects 0.9, so interreflection
// dominates: as in an integrating sphere, the mean irradiance is about Phi / (A (1 - rho (1 - f))) with
// flux Phi = pi L A_w = 5.28 L W (A_w = 1.68 m^2), room area A = 73.6 m^2 and the window's share
// f = A_w / A = 0.023 (light reaching the window leaves the room): 0.60 L W/m^2, a mean radiance of
// rho E / pi = 0.17 L. Only an eighth of it is direct (Phi / A = 0.072 L W/m^2, radiance 0.021 L).
// 3 W/(m^2 sr) puts the walls at about 0.5 W/(m^2 sr): well exposed with ACES at 0 EV (measured with
// `bounce reference`: 0.48 over the default view, docs/scene.md "indirect-light"). Techniques that stop
// after one bounce see only about a fifth of that (measured 0.093 with `--bounces 1`).
constexpr glm::vec3 kWindowRadiance{3.0f};  // W/(m^2 sr)
// Radiosity's element pitch on a GPU, metres, as setting text (the scene's defaults are text).
constexpr const char* kGpuElementSize = "0.1";

// The rotating box: a 0.5 m cube on the left half of the floor, turning once every 8 s about its vertical
// axis. Its half-diagonal (0.35 m) keeps it 0.85 m from the left wall and 1.25 m from the back wall.
constexpr float kBoxSide = 0.5f;                           // metres
constexpr glm::vec3 kBoxBaseCentre{-0.8f, 0.0f, -0.4f};    // metres, centre of its footprint
constexpr float kBoxPeriod = 8.0f;                         // seconds per turn

// Camera: eye height 1.4 m, 0.1 m in front of the front wall (z = +2), looking down toward the far left
// corner with a 55 degree vertical field of view: the box, the left and back walls and the floor are in
// view. The window's corners lie beyond the right frustum plane for any aspect up to
// 3.4:1 (IndirectLight.* in tests/unit/SceneTest.cpp checks up to 2:1), so the window is never seen.
constexpr glm::vec3 kCameraPosition{0.3f, 1.4f, 1.9f};    // metres
constexpr glm::vec3 kCameraTarget{-0.8f, 0.5f, -2.0f};    // metres
constexpr float kCameraFovDegrees = 55.0f;

}  // namespace

Expected<Scene> buildIndirectLight(const SceneParams&) {
    Scene s;
    s.name = "indirect-light";
    s.source = "builtin:indirect-light";
    Material paint;
    paint.name = "white-paint";
    paint.baseColor = kPaintAlbedo;
    paint.roughness = 1.0f;
    paint.metallic = 0.0f;
    paint.specularF0 = 0.0f;
    s.materials.push_back(paint);

    const auto object = [&](Mesh mesh) {
        Object o;
        o.name = mesh.name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        o.material = 0;
        s.meshes.push_back(std::move(mesh));
        s.objects.push_back(std::move(o));
        return &s.objects.back();
    };

    const float x0 = -0.5f * kRoomWidth, x1 = 0.5f * kRoomWidth;
    const float z0 = -0.5f * kRoomDepth, z1 = 0.5f * kRoomDepth;
    const float y0 = 0.0f, y1 = kRoomHeight;
    // One wall quad facing `front` (into the room).
    const auto wall = [&](const char* name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 front) {
        MeshBuilder mb(name);
        mb.quad(a, b, c, d, front);
        object(mb.take());
    };
    wall("floor", {x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, {0, 1, 0});
    wall("ceiling", {x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, {0, -1, 0});
    wall("left", {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}, {1, 0, 0});
    wall("back", {x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, {0, 0, 1});
    wall("front", {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, {0, 0, -1});

    // The right wall with the window cut out: four quads around the opening.
    const float wz0 = kWindowCentreZ - 0.5f * kWindowWidth, wz1 = kWindowCentreZ + 0.5f * kWindowWidth;
    const float wy0 = kWindowSill, wy1 = kWindowSill + kWindowHeight;
    {
        MeshBuilder mb("right");
        const glm::vec3 inward(-1.0f, 0.0f, 0.0f);
        const auto rect = [&](float za, float ya, float zb, float yb) {
            mb.quad({x1, ya, za}, {x1, ya, zb}, {x1, yb, zb}, {x1, yb, za}, inward);
        };
        rect(z0, y0, z1, wy0);    // below the window, full width
        rect(z0, wy1, z1, y1);    // above the window, full width
        rect(z0, wy0, wz0, wy1);  // beside the window, toward the back
        rect(wz1, wy0, z1, wy1);  // beside the window, toward the front
        object(mb.take());
    }

    {
        MeshBuilder mb("rotating-box");
        const float h = 0.5f * kBoxSide;
        mb.axisBox(glm::vec3(-h, 0.0f, -h), glm::vec3(h, kBoxSide, h), /*outward=*/true);
        Object* box = object(mb.take());
        box->animation = turntable(kBoxBaseCentre, kBoxPeriod);
    }

    Light window;
    window.name = "window";
    window.type = LightType::Area;
    window.position = glm::vec3(x1, 0.5f * (wy0 + wy1), kWindowCentreZ);
    // cross(+z, +y) = -x: the window emits into the room.
    window.edgeU = glm::vec3(0.0f, 0.0f, kWindowWidth);
    window.edgeV = glm::vec3(0.0f, kWindowHeight, 0.0f);
    window.radiance = kWindowRadiance;
    s.lights.push_back(window);

    s.camera.position = kCameraPosition;
    s.camera.target = kCameraTarget;
    s.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    s.camera.verticalFov = glm::radians(kCameraFovDegrees);
    s.camera.nearPlane = 0.01f;  // metres; the front wall is 0.1 m behind the camera
    s.camera.farPlane = 10.0f;   // metres; beyond the room's 6.2 m diagonal
    // Hemicube radiosity's element pitch per device profile (issue 29 #20): on llvmpipe 0.25 m (~1,300
    // elements, as before the automatic size, which gives 0.27 m here); on a GPU kGpuElementSize (~7,500
    // elements), of the order of the thesis's ~10,000 static elements (sec. 5.1's Cornell boxes). Albedo 0.9 needs 20+ bounces
    // (thesis sec. 5.1); 16 Gauss-Seidel sweeps leave the gather method a little dark, as the thesis's
    // capped gather was.
    for (const char* t : {"radiosity-gather", "radiosity-pr", "radiosity-incremental", "radiosity-cross"}) {
        s.settings[std::string(t) + ".elementSize@llvmpipe"] = "0.25";
        s.settings[std::string(t) + ".elementSize@gpu"] = kGpuElementSize;
    }
    s.settings["radiosity-gather.bounces"] = "16";
    return s;
}

}  // namespace bounce
