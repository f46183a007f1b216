// The Cornell box from the published Cornell University measurements (Program of Computer Graphics,
// "Cornell Box Data", https://www.graphics.cornell.edu/online/box/data.html), converted from
// millimetres to metres. The data's frame is right-handed with +y up and the camera looking along +z,
// so it is used as is. See docs/scene.md "cornell-box" for the albedos' source and the lights.
// cornell-box-rotating is the area-lit room without the blocks, with one white box turning in its centre
// (van de Hoef 2013's radiosity test scene: one rotating box as the dynamic object).
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace bounce {

namespace {

constexpr float kMillimetre = 0.001f;  // the data is in mm

// Room interior point used to orient the walls inward (mm; roughly the box centre).
constexpr glm::vec3 kRoomCentreMm{278.0f, 274.4f, 279.6f};
constexpr float kCeilingHeight = 548.8f * kMillimetre;

// Linear-RGB approximations of the measured Lambertian reflectance spectra (white, red, green),
// as used by Bitterli's "Rendering Resources" Cornell box; derivation in docs/scene.md.
constexpr glm::vec3 kWhiteAlbedo{0.725f, 0.71f, 0.68f};
constexpr glm::vec3 kRedAlbedo{0.63f, 0.065f, 0.05f};
constexpr glm::vec3 kGreenAlbedo{0.14f, 0.45f, 0.091f};

// Camera: position 278 273 -800 mm, direction +z, focal length 35 mm on a 25 mm x 25 mm film, so the
// vertical field of view is 2 atan(12.5/35) = 39.3 degrees.
constexpr glm::vec3 kCameraPositionMm{278.0f, 273.0f, -800.0f};
const float kCameraFov = 2.0f * std::atan(12.5f / 35.0f);

// A rectangle in the ceiling plane (mm): an area light and the ceiling's opening for it.
struct CeilingRect {
    float x0, x1, z0, z1;
    float areaMm2() const { return (x1 - x0) * (z1 - z0); }
    // The same centre with both sides scaled by `factor`.
    CeilingRect scaled(float factor) const {
        const float cx = 0.5f * (x0 + x1), cz = 0.5f * (z0 + z1);
        const float hx = 0.5f * factor * (x1 - x0), hz = 0.5f * factor * (z1 - z0);
        return {cx - hx, cx + hx, cz - hz, cz + hz};
    }
};

// The data's light rectangle (mm): x 213..343, z 227..332, in the ceiling plane.
constexpr CeilingRect kDataLight{213.0f, 343.0f, 227.0f, 332.0f};

// Spot light: 1 cm under the ceiling centre, pointing down. A 60 degree cutoff with cos^8 falloff gives a
// soft-edged pool (intensity at 30 degrees is cos^8 = 0.32 of the axis value, at 45 degrees 0.06, so the
// hard cutoff at 60 degrees, where it is 0.004, is invisible). 1 W/sr puts the floor under it at about
// 0.8 W/(m^2 sr) of direct radiance (I/d^2 * albedo/pi, d = 0.539 m), bright but unclipped with ACES at 0 EV.
constexpr float kSpotDrop = 0.01f;                      // metres below the ceiling
const float kSpotCutoff = glm::radians(60.0f);
constexpr float kSpotFalloff = 8.0f;
constexpr glm::vec3 kSpotIntensity{1.0f};               // W/sr

// Area light radiance: floor irradiance under the 0.0137 m^2 light at 0.549 m is about
// L * A / h^2 = 0.045 L, so 40 W/(m^2 sr) gives ~0.4 W/(m^2 sr) direct radiance on the white floor
// before interreflection roughly doubles it: well exposed with ACES at 0 EV.
constexpr glm::vec3 kAreaRadiance{40.0f};               // W/(m^2 sr)

// cornell-box-dynamic: spot orbit and tall-block turn, both looping every 4 s.
constexpr float kLoopSeconds = 4.0f;
constexpr float kSpotOrbitRadius = 0.12f;  // metres, keeps the pool on the floor
constexpr int kSpotOrbitKeys = 8;

// cornell-box-rotating (van de Hoef 2013's Cornell scene: a "relatively large ceiling light" and one
// rotating box). The size is chosen here, not taken from the thesis: light=large doubles the data's
// rectangle per side (260 mm x 210 mm, 4x the area: clearly larger, yet 148 mm of ceiling remain beside
// it); light=small is the data's rectangle. Either way the radiance is kAreaRadiance * (data area / light
// area), so the flux pi L A is cornell-box-area's 1.7 W and the exposure matches it: large
// 10 W/(m^2 sr), small 40 W/(m^2 sr).
constexpr float kLargeLightScale = 2.0f;                 // per side, relative to the data's rectangle
// The box: 0.2 m x 0.2 m footprint, 0.28 m tall, centred on the floor (the room's x, z centre), white.
// Its half-diagonal (0.141 m) keeps it 0.13 m clear of every wall while it turns.
constexpr float kRotatingBoxSide = 0.2f;                 // metres
constexpr float kRotatingBoxHeight = 0.28f;              // metres
constexpr float kRotatingBoxPeriod = 8.0f;               // seconds per turn (45 degrees per second)

glm::vec3 mm(float x, float y, float z) { return glm::vec3(x, y, z) * kMillimetre; }

enum class Lighting { Spot, Area };

struct Block {
    glm::vec2 footprint[4];  // x, z in mm, in order around the block
    float height;            // mm
};

// Short block: top at 165 mm; tall block: top at 330 mm (corners from the data's top faces).
constexpr Block kShortBlock{{{130.0f, 65.0f}, {82.0f, 225.0f}, {240.0f, 272.0f}, {290.0f, 114.0f}}, 165.0f};
constexpr Block kTallBlock{{{423.0f, 247.0f}, {265.0f, 296.0f}, {314.0f, 456.0f}, {472.0f, 406.0f}}, 330.0f};

glm::vec3 blockCentre(const Block& b) {
    glm::vec2 c(0.0f);
    for (const glm::vec2& p : b.footprint) c += p;
    c *= 0.25f;
    return mm(c.x, 0.0f, c.y);
}

// The block's mesh in object space, centred on its footprint so it can turn about its vertical axis.
Mesh blockMesh(const std::string& name, const Block& b) {
    const glm::vec3 c = blockCentre(b);
    glm::vec3 bottom[4], top[4];
    for (int i = 0; i < 4; ++i) {
        bottom[i] = mm(b.footprint[i].x, 0.0f, b.footprint[i].y) - c;
        top[i] = mm(b.footprint[i].x, b.height, b.footprint[i].y) - c;
    }
    MeshBuilder mb(name);
    mb.box(bottom, top, true);
    return mb.take();
}

// A wall quad of the data (mm), facing the room's interior.
Mesh wallMesh(const std::string& name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    MeshBuilder mb(name);
    const glm::vec3 mid = 0.25f * (a + b + c + d);
    mb.quad(a * kMillimetre, b * kMillimetre, c * kMillimetre, d * kMillimetre, kRoomCentreMm - mid);
    return mb.take();
}

// The ceiling with the light's rectangle cut out, for the area-lit variant (the real box's light sits
// in an opening in the ceiling; leaving the ceiling whole would make the emitter coplanar with it).
Mesh ceilingWithOpening(const CeilingRect& light) {
    MeshBuilder mb("ceiling");
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    const float y = 548.8f;
    const float x0 = 0.0f, x1 = 556.0f, z0 = 0.0f, z1 = 559.2f;
    const auto rect = [&](float ax, float az, float bx, float bz) {
        mb.quad(mm(ax, y, az), mm(bx, y, az), mm(bx, y, bz), mm(ax, y, bz), down);
    };
    rect(x0, z0, x1, light.z0);                  // front strip
    rect(x0, light.z1, x1, z1);                  // back strip
    rect(x0, light.z0, light.x0, light.z1);      // beside the light, low x
    rect(light.x1, light.z0, x1, light.z1);      // beside the light, high x
    return mb.take();
}

struct CornellOptions {
    Lighting lighting = Lighting::Spot;
    CeilingRect areaLight = kDataLight;          // Area: the light's rectangle and the ceiling's opening
    glm::vec3 areaRadiance = kAreaRadiance;      // Area: W/(m^2 sr)
    bool blocks = true;                          // the data's short and tall blocks
};

Scene cornellBox(const std::string& name, const CornellOptions& options) {
    const Lighting lighting = options.lighting;
    Scene s;
    s.name = name;
    s.source = "builtin:" + name;

    const auto material = [&](const char* materialName, glm::vec3 albedo) {
        Material m;
        m.name = materialName;
        m.baseColor = albedo;
        m.roughness = 1.0f;
        m.metallic = 0.0f;
        m.specularF0 = 0.0f;
        s.materials.push_back(m);
        return static_cast<uint32_t>(s.materials.size() - 1);
    };
    const uint32_t white = material("white", kWhiteAlbedo);
    const uint32_t red = material("red", kRedAlbedo);
    const uint32_t green = material("green", kGreenAlbedo);

    const auto object = [&](Mesh mesh, uint32_t mat, glm::vec3 translation = glm::vec3(0.0f)) {
        Object o;
        o.name = mesh.name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        o.material = mat;
        o.transform = glm::translate(glm::mat4(1.0f), translation);
        s.meshes.push_back(std::move(mesh));
        s.objects.push_back(std::move(o));
    };

    object(wallMesh("floor", {552.8f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 559.2f}, {549.6f, 0.0f, 559.2f}),
           white);
    if (lighting == Lighting::Area) {
        object(ceilingWithOpening(options.areaLight), white);
    } else {
        object(wallMesh("ceiling", {556.0f, 548.8f, 0.0f}, {556.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 559.2f},
                        {0.0f, 548.8f, 0.0f}),
               white);
    }
    object(wallMesh("back", {549.6f, 0.0f, 559.2f}, {0.0f, 0.0f, 559.2f}, {0.0f, 548.8f, 559.2f},
                    {556.0f, 548.8f, 559.2f}),
           white);
    // The data's "left wall" is red and its "right wall" green, as seen by the camera.
    object(wallMesh("left", {552.8f, 0.0f, 0.0f}, {549.6f, 0.0f, 559.2f}, {556.0f, 548.8f, 559.2f},
                    {556.0f, 548.8f, 0.0f}),
           red);
    object(wallMesh("right", {0.0f, 0.0f, 559.2f}, {0.0f, 0.0f, 0.0f}, {0.0f, 548.8f, 0.0f}, {0.0f, 548.8f, 559.2f}),
           green);
    if (options.blocks) {
        object(blockMesh("short-block", kShortBlock), white, blockCentre(kShortBlock));
        object(blockMesh("tall-block", kTallBlock), white, blockCentre(kTallBlock));
    }

    Light light;
    if (lighting == Lighting::Area) {
        light.name = "ceiling-light";
        light.type = LightType::Area;
        const CeilingRect& r = options.areaLight;
        light.position = mm(0.5f * (r.x0 + r.x1), 548.8f, 0.5f * (r.z0 + r.z1));
        // cross(+x, +z) = -y: the light emits downward.
        light.edgeU = mm(r.x1 - r.x0, 0.0f, 0.0f);
        light.edgeV = mm(0.0f, 0.0f, r.z1 - r.z0);
        light.radiance = options.areaRadiance;
    } else {
        light.name = "spot";
        light.type = LightType::Spot;
        light.position = glm::vec3(0.278f, kCeilingHeight - kSpotDrop, 0.2796f);
        light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        light.intensity = kSpotIntensity;
        light.cutoffAngle = kSpotCutoff;
        light.falloffExponent = kSpotFalloff;
    }
    s.lights.push_back(light);

    s.camera.position = kCameraPositionMm * kMillimetre;
    s.camera.target = s.camera.position + glm::vec3(0.0f, 0.0f, 1.0f);
    s.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    s.camera.verticalFov = kCameraFov;
    s.camera.nearPlane = 0.01f;  // metres; the box starts 0.8 m away
    s.camera.farPlane = 10.0f;   // metres; the far corner is ~1.4 m away
    return s;
}

}  // namespace

Expected<Scene> buildCornellBox(const SceneParams&) { return cornellBox("cornell-box", {}); }

Expected<Scene> buildCornellBoxArea(const SceneParams&) {
    CornellOptions options;
    options.lighting = Lighting::Area;
    return cornellBox("cornell-box-area", options);
}

Expected<Scene> buildCornellBoxRotating(const SceneParams& params) {
    const char* name = "cornell-box-rotating";
    BOUNCE_TRY(const std::string size, choiceParam(params, name, "light", "large", {"large", "small"}));
    CornellOptions options;
    options.lighting = Lighting::Area;
    options.blocks = false;
    options.areaLight = size == "large" ? kDataLight.scaled(kLargeLightScale) : kDataLight;
    options.areaRadiance = kAreaRadiance * (kDataLight.areaMm2() / options.areaLight.areaMm2());
    Scene s = cornellBox(name, options);

    // The box's mesh is centred on its vertical axis; its track places it on the floor's centre and turns it.
    MeshBuilder mb("rotating-box");
    const float h = 0.5f * kRotatingBoxSide;
    mb.axisBox(glm::vec3(-h, 0.0f, -h), glm::vec3(h, kRotatingBoxHeight, h), /*outward=*/true);
    Object box;
    box.name = "rotating-box";
    box.mesh = static_cast<uint32_t>(s.meshes.size());
    for (uint32_t m = 0; m < s.materials.size(); ++m)
        if (s.materials[m].name == "white") box.material = m;
    box.animation = turntable(mm(kRoomCentreMm.x, 0.0f, kRoomCentreMm.z), kRotatingBoxPeriod);
    s.meshes.push_back(mb.take());
    s.objects.push_back(std::move(box));
    return s;
}

Expected<Scene> buildCornellBoxDynamic(const SceneParams&) {
    Scene s = cornellBox("cornell-box-dynamic", {});

    // The spot's track offsets its position around a horizontal circle; Catmull-Rom through evenly spaced
    // keys on the circle gives a smooth closed orbit (the last key repeats the first to close the loop).
    Light& spot = s.lights[0];
    spot.animation.interpolation = Interpolation::CatmullRom;
    spot.animation.loop = true;
    for (int k = 0; k <= kSpotOrbitKeys; ++k) {
        const float phase = glm::two_pi<float>() * static_cast<float>(k % kSpotOrbitKeys) / kSpotOrbitKeys;
        TransformKey key;
        key.time = kLoopSeconds * static_cast<float>(k) / kSpotOrbitKeys;
        key.translation = kSpotOrbitRadius * glm::vec3(std::cos(phase), 0.0f, std::sin(phase));
        spot.animation.keys.push_back(key);
    }

    // The tall block turns once about its vertical axis per loop, in quarter-turn keys.
    for (Object& o : s.objects) {
        if (o.name != "tall-block") continue;
        const glm::vec3 centre = glm::vec3(o.transform[3]);
        o.transform = glm::mat4(1.0f);
        o.animation = turntable(centre, kLoopSeconds);
    }
    return s;
}

}  // namespace bounce
