// courtyard: the Sponza-class built-in scene (docs/scene.md "courtyard"). The atrium's arcaded
// courtyard (two storeys of columns and arches, drapes hanging in the upper galleries, a fountain)
// plus what makes real scenes hard for GI techniques and none of the other built-ins has: alpha-masked
// foliage (potted bushes of crossed leaf cards and ivy hanging from the gallery roofs, a procedural
// leaf mask) at a triangle count a parameter sets, lit by the sun (`light=sun`) or by a sky-sized
// area light over the open roof (`light=sky`). Generated in code: no downloaded asset.
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace bounce {

namespace {

// Triangle budget: the default sits in the 100K-300K range of Sponza-class scenes (Sponza: 66K-262K);
// CI uses a few thousand. The largest is the atrium's.
constexpr double kDefaultTriangles = 150000.0;
constexpr double kMaxTriangles = 2.0e7;

// Courtyard layout, the atrium's (AtriumScene.cpp): x in [-6, 6], z in [-10, 10], walls 9 m high,
// arcade columns (radius 0.25 m) at |x| = 3.5 m, 2 m apart along z from -9 to 9, storeys 4 m, roofs at 8 m.
constexpr float kHalfWidth = 6.0f, kHalfLength = 10.0f, kWallHeight = 9.0f;
constexpr float kArcadeX = 3.5f, kStoreyHeight = 4.0f;

// Foliage (bounce's design): a planter in front of every other arcade bay on the courtyard side,
// a bush of crossed leaf cards in it; ivy cards hanging from the gallery roof's edge over every
// third bay. Sizes in metres.
constexpr float kPlanterInset = 0.9f;        // from the column axis toward the courtyard's centre
constexpr float kPlanterHalf = 0.3f;         // square planter, half side
constexpr float kPlanterHeight = 0.45f;
constexpr float kBushRadius = 0.55f;         // leaf cards' half width
constexpr float kBushHeight = 1.1f;          // above the planter's rim
constexpr int kBushCards = 4;                // vertical cards around the axis, 45 degrees apart
constexpr float kIvyLength = 2.2f;           // hanging down from under the roof slab
constexpr float kIvyHalfWidth = 0.8f;
constexpr float kIvyInset = 0.05f;           // in front of the arcade's courtyard face

// The leaf mask: kMaskSize^2 texels; kLeaves ellipses per tile, the tile repeating (GL_REPEAT and the
// reference's bilinear-repeat lookup agree on a tiling texture). About half the texels are covered,
// so masking removes a large share of the cards' area, and a technique that ignores the mask shows it.
constexpr int kMaskSize = 128;
constexpr int kLeaves = 40;
constexpr float kLeafLength = 0.16f, kLeafWidth = 0.06f;  // ellipse semi-axes, in texture units

// Sky variant: a downward-facing rectangle just above the wall tops covering the whole opening. The
// paving under its centre sees it with a view factor of 0.46 (parallel 12 m x 20 m rectangle 9 m up),
// E = pi L 0.46; radiance (3.2, 3.5, 4.0) W/(m^2 sr), bluish, gives the paving (albedo 0.5) about
// 0.5 * 1.45 * 3.5 / pi = 0.8 W/(m^2 sr) before interreflection: exposed like the sun variant.
constexpr float kSkyAboveWalls = 0.05f;  // metres
constexpr glm::vec3 kSkyRadiance{3.2f, 3.5f, 4.0f};

// A deterministic hash in [0, 1) (leaf placement must not depend on a library's random engine).
float hash01(uint32_t i, uint32_t salt) {
    uint32_t x = i * 747796405u + salt * 2891336453u + 1u;
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return static_cast<float>(x >> 8) / 16777216.0f;
}

// Coverage (1 inside a leaf, 0 outside; every channel) and colour (greens, linear) of the leaf tile.
void leafTextures(Image& mask, Image& colour) {
    mask = Image(kMaskSize, kMaskSize, glm::vec3(0.0f));
    colour = Image(kMaskSize, kMaskSize, glm::vec3(0.10f, 0.22f, 0.06f));
    for (int leaf = 0; leaf < kLeaves; ++leaf) {
        const glm::vec2 centre(hash01(leaf, 1), hash01(leaf, 2));
        const float angle = glm::pi<float>() * hash01(leaf, 3);
        const glm::vec2 axis(std::cos(angle), std::sin(angle));
        const glm::vec3 green = glm::mix(glm::vec3(0.08f, 0.30f, 0.05f), glm::vec3(0.25f, 0.45f, 0.08f), hash01(leaf, 4));
        for (int y = 0; y < kMaskSize; ++y)
            for (int x = 0; x < kMaskSize; ++x) {
                glm::vec2 d = (glm::vec2(x, y) + 0.5f) / static_cast<float>(kMaskSize) - centre;
                d -= glm::round(d);  // the tile repeats
                const float a = glm::dot(d, axis) / kLeafLength;
                const float b = (axis.x * d.y - axis.y * d.x) / kLeafWidth;
                if (a * a + b * b <= 1.0f) {
                    mask.at(x, y) = glm::vec3(1.0f);
                    colour.at(x, y) = green;
                }
            }
    }
}

}  // namespace

Expected<Scene> buildCourtyard(const SceneParams& params) {
    BOUNCE_TRY(const std::string light, choiceParam(params, "courtyard", "light", "sun", {"sun", "sky"}));

    // Foliage first: its triangles come out of the budget the atrium's tessellation gets.
    MeshBuilder planters("planters"), bushes("foliage-bushes"), ivy("foliage-ivy");
    for (int side = 0; side < 2; ++side) {
        const float sx = side == 0 ? -1.0f : 1.0f;
        for (int bay = 0; bay < 9; ++bay) {
            const float z = -kHalfLength + 2.0f + 2.0f * static_cast<float>(bay);  // bay centres, between columns
            if (bay % 2 == 0) {
                const float x = sx * (kArcadeX - kPlanterInset);
                planters.axisBox({x - kPlanterHalf, 0.0f, z - kPlanterHalf}, {x + kPlanterHalf, kPlanterHeight, z + kPlanterHalf});
                for (int c = 0; c < kBushCards; ++c) {
                    const float a = glm::pi<float>() * static_cast<float>(c) / kBushCards;
                    const glm::vec3 r(kBushRadius * std::cos(a), 0.0f, kBushRadius * std::sin(a));
                    const glm::vec3 base(x, kPlanterHeight * 0.8f, z), top = base + glm::vec3(0, kBushHeight, 0);
                    // a, b at the top (v = 0, the image's first row), d, c at the bottom.
                    bushes.quad(top - r, top + r, base + r, base - r, glm::vec3(-r.z, 0.0f, r.x));
                }
            }
            if (bay % 3 == 1) {
                // Hanging from under the upper gallery's roof slab, in front of the arches.
                const float x = sx * (kArcadeX - 0.25f - kIvyInset);
                const float yTop = 2.0f * kStoreyHeight - 0.01f, yBottom = yTop - kIvyLength;
                ivy.quad({x, yTop, z - kIvyHalfWidth}, {x, yTop, z + kIvyHalfWidth}, {x, yBottom, z + kIvyHalfWidth},
                         {x, yBottom, z - kIvyHalfWidth}, {-sx, 0.0f, 0.0f});
            }
        }
    }
    const size_t foliageTriangles = planters.triangleCount() + bushes.triangleCount() + ivy.triangleCount();

    SceneParams atriumParams;
    BOUNCE_TRY(const double target, numberParam(params, "courtyard", "triangles", kDefaultTriangles,
                                                1916.0 + static_cast<double>(foliageTriangles), kMaxTriangles));
    atriumParams["triangles"] = std::to_string(target - static_cast<double>(foliageTriangles));
    BOUNCE_TRY(Scene s, buildAtrium(atriumParams));
    s.name = "courtyard";
    s.source = "builtin:courtyard";

    // The leaf tile: colour (base-colour texture) and coverage (alpha texture) of one material.
    Image mask, colour;
    leafTextures(mask, colour);
    const int colourIndex = static_cast<int>(s.textures.size());
    s.textures.push_back({"courtyard:leaves-colour", std::move(colour)});
    const int maskIndex = static_cast<int>(s.textures.size());
    s.textures.push_back({"courtyard:leaves-mask", std::move(mask)});
    Material leaves;
    leaves.name = "leaves";
    leaves.baseColor = glm::vec3(1.0f);
    leaves.baseColorTexture = colourIndex;
    leaves.alphaTexture = maskIndex;
    leaves.alphaCutoff = 0.5f;  // glTF's default cutoff
    leaves.twoSided = true;     // cards are seen from both sides
    const auto leavesMaterial = static_cast<uint32_t>(s.materials.size());
    s.materials.push_back(leaves);
    Material terracotta;
    terracotta.name = "terracotta";
    terracotta.baseColor = glm::vec3(0.55f, 0.27f, 0.16f);
    const auto planterMaterial = static_cast<uint32_t>(s.materials.size());
    s.materials.push_back(terracotta);
    for (auto [builder, material] : {std::pair{&planters, planterMaterial}, std::pair{&bushes, leavesMaterial},
                                     std::pair{&ivy, leavesMaterial}}) {
        Object o;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        s.meshes.push_back(builder->take());
        o.name = s.meshes.back().name;
        o.material = material;
        s.objects.push_back(std::move(o));
    }

    if (light == "sky") {
        s.lights.clear();
        Light sky;
        sky.name = "sky";
        sky.type = LightType::Area;
        sky.position = glm::vec3(0.0f, kWallHeight + kSkyAboveWalls, 0.0f);
        sky.edgeU = glm::vec3(2.0f * kHalfWidth, 0.0f, 0.0f);
        sky.edgeV = glm::vec3(0.0f, 0.0f, 2.0f * kHalfLength);  // cross(edgeU, edgeV) = -y: emits downward
        sky.radiance = kSkyRadiance;
        s.lights.push_back(sky);
    }
    return s;
}

}  // namespace bounce
