// Radiosity's charts (PatchModel.h, radiosity.md "Charts, not the mesh's faces"): elements decoupled
// from the mesh's triangulation. A plane of many small triangles gets about area / elementSize^2
// elements (the per-face quads before issue 30 gave it at least 2 x 2 per triangle pair), element
// areas sum to the surface area, every triangle vertex's (s, t) maps back onto it, curved surfaces
// stay cheap, and the automatic element size follows the scene's area.
#include "scene/MeshBuilder.h"
#include "scene/SceneLoader.h"
#include "techniques/radiosity/PatchModel.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace bounce;
using namespace bounce::radiosity;

namespace {

// A 2 x 2 m square at y = 0 facing +y, cut into `cells` x `cells` squares of two triangles each, with an
// emissive material (the patch model needs something to shoot).
Scene finelyCutSquare(int cells) {
    Scene s;
    s.name = "square";
    Material m;
    m.baseColor = glm::vec3(0.5f);
    m.emission = glm::vec3(1.0f);
    s.materials = {m};
    Mesh mesh;
    const float side = 2.0f;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            mesh.positions.push_back({side * i / cells - 1.0f, 0.0f, 1.0f - side * j / cells});
            mesh.normals.push_back({0, 1, 0});
            mesh.uvs.push_back({float(i) / cells, float(j) / cells});
        }
    const auto at = [&](int i, int j) { return static_cast<uint32_t>(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            // Alternating diagonals, so no two neighbouring pairs form the same quad pattern.
            if ((i + j) % 2 == 0) {
                mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            } else {
                mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
                mesh.indices.insert(mesh.indices.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        }
    s.meshes = {mesh};
    s.objects = {Object{}};
    return s;
}

double elementArea(const PatchModel& pm) {
    double a = 0.0;
    for (const Element& e : pm.elements()) a += e.area;
    return a;
}

}  // namespace

TEST(RadiosityCharts, ManySmallTrianglesGetElementsByAreaNotByTriangle) {
    // 100 x 100 cells = 20,000 triangles of 0.02 m. At 0.1 m the square is one chart of 21 x 21 texels
    // (texel centres on the edges: (2 / 0.1 + 1)^2 = 441 for area / size^2 = 400). The per-face quads
    // gave 10,000 quads of 2 x 2 texels, 40,000 elements.
    const Scene s = finelyCutSquare(100);
    ASSERT_EQ(s.meshes[0].triangleCount(), 20000u);
    auto pm = PatchModel::build(s, PatchOptions{0.1f, 0.1f});
    ASSERT_TRUE(pm.ok()) << pm.error().message;
    EXPECT_EQ(pm->quads().size(), 1u);
    EXPECT_EQ(pm->elements().size(), 441u);
    EXPECT_EQ(pm->activeElementCount(), 441u) << "the square covers its rectangle: no ghosts";
    // Areas: interior cells 0.01 m^2, edge cells half, corners a quarter, summing to the 4 m^2.
    EXPECT_NEAR(elementArea(*pm), 4.0, 4e-5);
    EXPECT_NEAR(pm->quads()[0].area, 4.0f, 4e-5f);
    const Quad& q = pm->quads()[0];
    for (const Element& e : pm->elements()) {
        const bool edgeI = e.i == 0 || e.i == q.nu - 1, edgeJ = e.j == 0 || e.j == q.nv - 1;
        EXPECT_NEAR(e.area, 0.01f * (edgeI ? 0.5f : 1.0f) * (edgeJ ? 0.5f : 1.0f), 1e-6f) << e.i << "," << e.j;
        EXPECT_NEAR(e.position.y, 0.0f, 1e-6f);
        EXPECT_NEAR(e.albedo.x, 0.5f, 1e-6f);
    }
    // Every triangle vertex's (s, t) in the chart maps back onto the vertex (the display's and hemicubes'
    // interpolation of the atlas coordinate is exact on a planar chart).
    const Mesh& mesh = s.meshes[0];
    for (size_t t = 0; t < mesh.triangleCount(); t += 97) {
        const TriangleRef& ref = pm->triangles()[t];
        ASSERT_EQ(ref.quad, 0u);
        for (int k = 0; k < 3; ++k)
            EXPECT_LT(glm::length(PatchModel::pointAt(q, ref.st[k]) - mesh.positions[mesh.indices[3 * t + static_cast<size_t>(k)]]), 1e-4f)
                << "triangle " << t << " vertex " << k;
    }
    // A coarser pitch: elements follow it, the triangles stay 20,000.
    auto coarse = PatchModel::build(s, PatchOptions{0.5f, 0.5f});
    ASSERT_TRUE(coarse.ok());
    EXPECT_EQ(coarse->elements().size(), 25u);
    EXPECT_NEAR(elementArea(*coarse), 4.0, 4e-5);
}

TEST(RadiosityCharts, TiltedIrregularPlaneSumsToItsArea) {
    // The same square rotated off every axis and cut irregularly (a fan of thin triangles around one
    // corner, which no triangle pairing turns into quads): one chart, its element areas the surface's.
    Scene s = finelyCutSquare(1);
    Mesh& mesh = s.meshes[0];
    mesh.positions.clear();
    mesh.normals.clear();
    mesh.uvs.clear();
    mesh.indices.clear();
    const glm::vec3 o(0.3f, 0.1f, -0.2f), u = glm::normalize(glm::vec3(1.0f, 0.4f, 0.2f));
    const glm::vec3 v = glm::normalize(glm::cross(glm::normalize(glm::vec3(0.1f, 1.0f, -0.3f)), u));
    const glm::vec3 n = glm::cross(u, v);
    // 1.5 x 0.8 m rectangle; the fan from corner (0, 0) over 400 points along the two far edges.
    const float w = 1.5f, h = 0.8f;
    mesh.positions.push_back(o);
    std::vector<glm::vec2> rim;
    for (int k = 0; k <= 200; ++k) rim.push_back({w, h * k / 200.0f});
    for (int k = 199; k >= 0; --k) rim.push_back({w * k / 200.0f, h});
    for (const glm::vec2& r : rim) mesh.positions.push_back(o + r.x * u + r.y * v);
    for (uint32_t k = 1; k + 1 < mesh.positions.size(); ++k) mesh.indices.insert(mesh.indices.end(), {0u, k, k + 1});
    mesh.normals.assign(mesh.positions.size(), n);
    mesh.uvs.assign(mesh.positions.size(), glm::vec2(0.0f));
    // The fan's last edge closes on (0, h) -> (0, 0): the rectangle minus the triangle (0,0) (w,0) ...
    // is covered exactly, area w h.
    auto pm = PatchModel::build(s, PatchOptions{0.1f, 0.1f});
    ASSERT_TRUE(pm.ok()) << pm.error().message;
    EXPECT_EQ(pm->quads().size(), 1u);
    EXPECT_NEAR(elementArea(*pm), w * h, 1e-4);
    // The tight rectangle is the 1.5 x 0.8 m one (16 x 9 texels), not an axis-aligned box around it.
    const Quad& q = pm->quads()[0];
    EXPECT_EQ(q.nu * q.nv, 16 * 9);
    EXPECT_EQ(pm->activeElementCount(), pm->elements().size());
    EXPECT_NEAR(std::abs(glm::dot(q.normal, n)), 1.0f, 1e-5f);
    for (const Element& e : pm->elements()) EXPECT_NEAR(glm::dot(e.position - o, n), 0.0f, 1e-4f) << "samples on the plane";
}

TEST(RadiosityCharts, CurvedSurfacesStayCheap) {
    // A 64-segment column side (r 0.25 m, 2 m high, 2 rings): 256 triangles of 2.5 cm width. The per-face
    // quads gave each of its 128 quads at least 2 x 2 texels (at 0.1 m: 2 x 21, 5,376 elements); charts
    // within the 20-degree normal cone take several faces each: about area / size^2 = 314 elements.
    MeshBuilder b("column");
    b.cylinder({0, 0, 0}, 0.25f, 2.0f, 64, 2);
    Scene s = finelyCutSquare(1);
    s.meshes = {b.take()};
    auto pm = PatchModel::build(s, PatchOptions{0.1f, 0.1f});
    ASSERT_TRUE(pm.ok()) << pm.error().message;
    const double area = 64 * 2.0 * 0.25 * std::sin(glm::pi<double>() / 64.0) * 2.0;  // the prism's 64 faces
    EXPECT_NEAR(elementArea(*pm), area, 1e-4 * area);
    EXPECT_LT(pm->elements().size(), 3 * 314u);
    EXPECT_LE(pm->quads().size(), 64u / 4u) << "at least four 5.6-degree faces per 20-degree chart";
    // Every sample lies on the plane of one of the column's faces near the faces: not inside the prism
    // (the centroid of pieces on several faces would be, by up to the 20-degree cone's sag, 1.5 cm), at
    // most 5 mm outside it (a face's plane beyond the face, within a 0.1 m cell).
    const float apothem = 0.25f * std::cos(glm::pi<float>() / 64.0f);
    for (const Element& e : pm->elements()) {
        const float r = std::sqrt(e.position.x * e.position.x + e.position.z * e.position.z);
        EXPECT_LE(r, 0.25f + 0.005f);
        EXPECT_GE(r, apothem - 1e-4f);
    }
}

TEST(RadiosityCharts, AutomaticElementSizeFollowsTheSceneArea) {
    // elementSize 0 derives sqrt(area / kAutoTargetElements); the square's 4 m^2 (plus nothing else) gives
    // 0.0632 m, so about 1,000 elements; explicit sizes win.
    const Scene s = finelyCutSquare(10);
    EXPECT_NEAR(autoElementSize(s), std::sqrt(4.0 / kAutoTargetElements), 1e-6);
    auto pm = PatchModel::build(s, PatchOptions{});
    ASSERT_TRUE(pm.ok()) << pm.error().message;
    EXPECT_NEAR(pm->elementSize(), std::sqrt(4.0f / static_cast<float>(kAutoTargetElements)), 1e-6f);
    EXPECT_EQ(pm->dynamicElementSize(), pm->elementSize());
    const double n = static_cast<double>(pm->elements().size());
    EXPECT_GT(n, kAutoTargetElements);
    EXPECT_LT(n, 1.3 * kAutoTargetElements) << "border texels add (1 + size / side)^2 at most";
    auto given = PatchModel::build(s, PatchOptions{0.5f, 0.0f});
    ASSERT_TRUE(given.ok());
    EXPECT_EQ(given->elementSize(), 0.5f);
    EXPECT_EQ(given->elements().size(), 25u);
}

TEST(RadiosityCharts, ScaledObjectsGetWorldAreasAndWorldPitch) {
    // The 2 x 2 m square scaled 3x along x and 0.5x along z (a 6 x 1 m^2 square in the world): at a
    // 0.1 m pitch the chart has (6 / 0.1 + 1) x (1 / 0.1 + 1) = 61 x 11 texels, and its elements sum to
    // 6 m^2. Object-space sizing (before) gave 21 x 21 texels and 4 m^2: shooting 2/3 of the flux.
    Scene s = finelyCutSquare(10);
    s.objects[0].transform = glm::scale(glm::mat4(1.0f), glm::vec3(3.0f, 1.0f, 0.5f));
    auto pm = PatchModel::build(s, PatchOptions{0.1f, 0.1f});
    ASSERT_TRUE(pm.ok()) << pm.error().message;
    ASSERT_EQ(pm->quads().size(), 1u);
    const Quad& q = pm->quads()[0];
    EXPECT_EQ(std::min(q.nu, q.nv), 11);
    EXPECT_EQ(std::max(q.nu, q.nv), 61);
    EXPECT_NEAR(elementArea(*pm), 6.0, 6e-5);
    EXPECT_NEAR(q.area, 6.0f, 6e-5f);
    // A uniform 10x scale: 100x the area, and the automatic pitch (sqrt(area / 1000)) 10x.
    Scene big = finelyCutSquare(10);
    big.objects[0].transform = glm::scale(glm::mat4(1.0f), glm::vec3(10.0f));
    auto small = PatchModel::build(finelyCutSquare(10), PatchOptions{});
    auto large = PatchModel::build(big, PatchOptions{});
    ASSERT_TRUE(small.ok() && large.ok());
    EXPECT_NEAR(large->elementSize(), 10.0f * small->elementSize(), 1e-4f * large->elementSize());
    EXPECT_EQ(large->elements().size(), small->elements().size());
    EXPECT_NEAR(elementArea(*large), 100.0 * elementArea(*small), 1e-3);
}
