// atrium: a procedural courtyard standing in for Sponza-class scenes. A paved floor, four surrounding
// walls, two storeys of arcades (tessellated cylindrical columns carrying semicircular arch bays) along
// the long sides with gallery floors and roofs, red/blue/green drapes hanging in the upper galleries,
// a fountain in the middle, open sky and a directional sun. The tessellation is sized so the triangle
// count lands within 10 % of the `triangles` parameter (docs/scene.md "atrium").
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <deque>

namespace bounce {

namespace {

// Layout (metres; a design, loosely Sponza-sized, not measured data). The courtyard is x in [-kHalfWidth, kHalfWidth], z in [-kHalfLength, kHalfLength].
constexpr float kHalfWidth = 6.0f;
constexpr float kHalfLength = 10.0f;
constexpr float kWallHeight = 9.0f;
constexpr float kArcadeX = 3.5f;         // column axis, |x|
constexpr float kStoreyHeight = 4.0f;    // floor-to-floor
constexpr float kColumnRadius = 0.25f;
constexpr float kColumnSpacing = 2.0f;   // along z, centre to centre
constexpr int kColumnsPerRow = 10;       // z = -9, -7, ..., 9
constexpr float kSlabThickness = 0.25f;
constexpr float kBayHalfSpan = 0.5f * kColumnSpacing;
constexpr float kBayInnerRadius = kBayHalfSpan - kColumnRadius;  // the arch springs from the column faces
constexpr float kBayDepth = 2.0f * kColumnRadius;
// Drapes: hung behind the upper arcade, folds as a sine across their width that deepens downward.
constexpr float kDrapeSetBack = 0.6f;      // behind the column axis
constexpr float kDrapeTopBelowRoof = 0.3f;
constexpr float kDrapeLength = 2.6f;
constexpr float kDrapeHalfWidth = 0.7f;
constexpr float kDrapeFoldDepth = 0.08f;
constexpr float kDrapeFolds = 3.0f;        // sine periods across the width
// Fountain in the middle of the courtyard.
constexpr float kBasinRadius = 1.5f;
constexpr float kBasinHeight = 0.6f;
constexpr float kSpoutRadius = 0.2f;
constexpr float kSpoutHeight = 1.8f;

// Budget limits for the `triangles` parameter.
constexpr double kDefaultTriangles = 100000.0;
constexpr double kMaxTriangles = 2.0e7;  // ~1 GB of vertex data: beyond any GI lab's GPU budget

// Sun: propagation direction (from above the west (-x) and south (+z) walls, ~28 degrees from vertical;
// it lights the east arcade and the far north wall the camera looks at) and irradiance on a
// surface facing it. Paving of albedo 0.5 facing up then shows 0.5 * 6 * cos / pi = 0.85 W/(m^2 sr).
constexpr glm::vec3 kSunDirection{0.35f, -0.9f, -0.2f};
constexpr glm::vec3 kSunIrradiance{6.0f, 5.7f, 5.0f};  // W/m^2, slightly warm

struct Tessellation {
    int columnSegments, columnRings, baySegments, floorCellsX, floorCellsZ, wallCells, slabCells;
    int drapeCellsU, drapeCellsV, fountainSegments;
};

Tessellation tessellationFor(double density) {
    const auto level = [&](double perUnit, int minimum) {
        return std::max(minimum, static_cast<int>(std::lround(perUnit * density)));
    };
    Tessellation t;
    t.columnSegments = level(6.0, 6);
    t.columnRings = level(3.0, 1);
    t.baySegments = 4 * level(2.0, 1);
    t.floorCellsX = level(6.0, 1);
    t.floorCellsZ = level(10.0, 1);
    t.wallCells = level(4.0, 1);
    t.slabCells = level(2.0, 1);
    t.drapeCellsU = level(6.0, 2);
    t.drapeCellsV = level(8.0, 2);
    t.fountainSegments = level(12.0, 12);
    return t;
}

enum MaterialId : uint32_t { kPaving, kStone, kPlaster, kRedDrape, kBlueDrape, kGreenDrape, kWater, kMaterialCount };

struct Part {
    MaterialId material;
    MeshBuilder builder;
};

// Builds (or, with counting builders, only counts) every part of the atrium.
void generate(const Tessellation& t, bool countOnly, std::deque<Part>& parts) {
    const auto part = [&](const std::string& name, MaterialId material) -> MeshBuilder& {
        parts.push_back({material, countOnly ? MeshBuilder::counter() : MeshBuilder(name)});
        return parts.back().builder;
    };
    const glm::vec3 up(0, 1, 0);
    const float W = kHalfWidth, L = kHalfLength, H = kWallHeight;

    MeshBuilder& floor = part("floor", kPaving);
    floor.quad({-W, 0, -L}, {W, 0, -L}, {W, 0, L}, {-W, 0, L}, up, t.floorCellsX, t.floorCellsZ);

    MeshBuilder& walls = part("walls", kPlaster);
    const int longCells = t.wallCells * 2, shortCells = t.wallCells;
    walls.quad({-W, 0, -L}, {-W, 0, L}, {-W, H, L}, {-W, H, -L}, {1, 0, 0}, longCells, shortCells);
    walls.quad({W, 0, -L}, {W, 0, L}, {W, H, L}, {W, H, -L}, {-1, 0, 0}, longCells, shortCells);
    walls.quad({-W, 0, -L}, {W, 0, -L}, {W, H, -L}, {-W, H, -L}, {0, 0, 1}, shortCells, shortCells);
    walls.quad({-W, 0, L}, {W, 0, L}, {W, H, L}, {-W, H, L}, {0, 0, -1}, shortCells, shortCells);

    const char* drapeNames[3] = {"drapes-red", "drapes-blue", "drapes-green"};
    const MaterialId drapeMaterials[3] = {kRedDrape, kBlueDrape, kGreenDrape};
    for (int side = 0; side < 2; ++side) {
        const float sx = side == 0 ? -1.0f : 1.0f;
        const std::string prefix = side == 0 ? "west-" : "east-";
        const float cx = sx * kArcadeX;
        MeshBuilder& columns = part(prefix + "columns", kStone);
        MeshBuilder& arches = part(prefix + "arches", kStone);
        MeshBuilder& slabs = part(prefix + "galleries", kStone);
        for (int storey = 0; storey < 2; ++storey) {
            const float base = storey * kStoreyHeight + (storey > 0 ? kSlabThickness : 0.0f);
            const float springing = (storey + 1) * kStoreyHeight - kBayHalfSpan;
            for (int c = 0; c < kColumnsPerRow; ++c) {
                const float z = -L + kBayHalfSpan + kColumnSpacing * static_cast<float>(c);
                columns.cylinder({cx, base, z}, kColumnRadius, springing - base, t.columnSegments, t.columnRings);
            }
            for (int b = 0; b + 1 < kColumnsPerRow; ++b) {
                const float z = -L + 2.0f * kBayHalfSpan + kColumnSpacing * static_cast<float>(b);
                arches.archBay({cx, springing, z}, {0, 0, 1}, {1, 0, 0}, kBayHalfSpan, kBayInnerRadius, kBayDepth,
                               t.baySegments);
            }
            // End piers tie each row to the end walls. They reach the end columns' axes, where the end bays'
            // open ends are, so no gap shows the inside of a bay.
            const float top = (storey + 1) * kStoreyHeight;
            const float endZ = -L + kBayHalfSpan;
            columns.axisBox({cx - kColumnRadius, base, -L}, {cx + kColumnRadius, top, endZ}, true, 1);
            columns.axisBox({cx - kColumnRadius, base, -endZ}, {cx + kColumnRadius, top, L}, true, 1);
            // Gallery floor (storey 0) and roof (storey 1) from the arcade to the side wall.
            const float x0 = std::min(cx - sx * kColumnRadius, sx * W), x1 = std::max(cx - sx * kColumnRadius, sx * W);
            slabs.axisBox({x0, top, -L}, {x1, top + kSlabThickness, L}, true, t.slabCells);
        }
        // Drapes hang inside the upper gallery behind every bay, cycling red, blue, green, with folds.
        for (int b = 0; b + 1 < kColumnsPerRow; ++b) {
            const int colour = b % 3;
            MeshBuilder& drape = part(prefix + drapeNames[colour], drapeMaterials[colour]);
            const float zc = -L + 2.0f * kBayHalfSpan + kColumnSpacing * static_cast<float>(b);
            const float xd = cx + sx * kDrapeSetBack;
            const float yTop = 2.0f * kStoreyHeight - kDrapeTopBelowRoof;
            drape.surface(
                t.drapeCellsU, t.drapeCellsV,
                [=](float u, float v) {
                    // Folds 40 % as deep at the top, where the cloth is held, as at the hem.
                    const float fold =
                        kDrapeFoldDepth * std::sin(glm::two_pi<float>() * kDrapeFolds * u) * (0.4f + 0.6f * v);
                    return glm::vec3(xd + fold, yTop - kDrapeLength * v,
                                     zc - kDrapeHalfWidth + 2.0f * kDrapeHalfWidth * u);
                },
                {-sx, 0, 0});
        }
    }

    // Fountain: a basin wall, its water surface and a central spout column.
    MeshBuilder& fountain = part("fountain", kStone);
    // The water is level with the rim so the basin wall, one-sided, is only ever seen from outside.
    fountain.cylinder({0, 0, 0}, kBasinRadius, kBasinHeight, t.fountainSegments, 1);
    fountain.cylinder({0, 0, 0}, kSpoutRadius, kSpoutHeight, t.columnSegments, t.columnRings);
    fountain.disk({0, kSpoutHeight, 0}, kSpoutRadius, up, t.columnSegments);
    MeshBuilder& water = part("fountain-water", kWater);
    water.disk({0, kBasinHeight, 0}, kBasinRadius, up, t.fountainSegments);
}

size_t countTriangles(double density) {
    std::deque<Part> parts;  // stable references while parts are added
    generate(tessellationFor(density), true, parts);
    size_t n = 0;
    for (const Part& p : parts) n += p.builder.triangleCount();
    return n;
}

}  // namespace

Expected<Scene> buildAtrium(const SceneParams& params) {
    const double minTriangles = static_cast<double>(countTriangles(0.0));
    BOUNCE_TRY(const double target,
               numberParam(params, "atrium", "triangles", kDefaultTriangles, minTriangles, kMaxTriangles));

    // Every tessellation level is non-decreasing in the density, so the count is too: bisect.
    double lo = 0.0, hi = 1.0;
    while (static_cast<double>(countTriangles(hi)) < target) hi *= 2.0;
    constexpr int kBisections = 30;  // density to 1e-9 relative: below one tessellation step at any budget
    for (int i = 0; i < kBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        (static_cast<double>(countTriangles(mid)) < target ? lo : hi) = mid;
    }
    const double nLo = static_cast<double>(countTriangles(lo)), nHi = static_cast<double>(countTriangles(hi));
    const double density = (target - nLo < nHi - target) ? lo : hi;

    Scene s;
    s.name = "atrium";
    s.source = "builtin:atrium";
    const auto material = [&](const char* name, glm::vec3 albedo, bool twoSided) {
        Material m;
        m.name = name;
        m.baseColor = albedo;
        m.twoSided = twoSided;
        s.materials.push_back(m);
    };
    // Order matches MaterialId. Drapes are cloth seen from both sides.
    material("paving", {0.50f, 0.46f, 0.40f}, false);
    material("stone", {0.72f, 0.68f, 0.60f}, false);
    material("plaster", {0.80f, 0.58f, 0.36f}, false);
    material("red-drape", {0.72f, 0.07f, 0.06f}, true);
    material("blue-drape", {0.06f, 0.12f, 0.66f}, true);
    material("green-drape", {0.10f, 0.45f, 0.12f}, true);
    material("water", {0.20f, 0.34f, 0.42f}, false);

    std::deque<Part> parts;  // stable references while parts are added
    generate(tessellationFor(density), false, parts);
    // Merge parts of the same name (drapes of one colour come as one part per bay).
    for (Part& p : parts) {
        Mesh mesh = p.builder.take();
        auto it = std::find_if(s.objects.begin(), s.objects.end(), [&](const Object& o) { return o.name == mesh.name; });
        if (it != s.objects.end()) {
            Mesh& into = s.meshes[it->mesh];
            const auto offset = static_cast<uint32_t>(into.positions.size());
            into.positions.insert(into.positions.end(), mesh.positions.begin(), mesh.positions.end());
            into.normals.insert(into.normals.end(), mesh.normals.begin(), mesh.normals.end());
            into.uvs.insert(into.uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
            for (uint32_t i : mesh.indices) into.indices.push_back(i + offset);
            continue;
        }
        Object o;
        o.name = mesh.name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        o.material = p.material;
        s.meshes.push_back(std::move(mesh));
        s.objects.push_back(std::move(o));
    }

    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(kSunDirection);
    sun.irradiance = kSunIrradiance;
    s.lights.push_back(sun);

    // Standing near the south wall at eye height, looking north along the courtyard and a little up.
    s.camera.position = glm::vec3(0.0f, 1.7f, kHalfLength - 1.0f);  // metres; 1.7 m eye height
    s.camera.target = glm::vec3(0.0f, 3.5f, -kHalfLength);
    s.camera.verticalFov = glm::radians(60.0f);
    s.camera.nearPlane = 0.05f;  // metres
    s.camera.farPlane = 100.0f;  // metres
    return s;
}

}  // namespace bounce
