// Voxel cone tracing (Rauwendaal 2013), the GL-free core: the factored triangle/voxel overlap test
// against brute force, voxelized sheets, the SH basis and SH mipmap, the diffuse cone set, and the
// isotropic / anisotropic mip and RGBA8 running-average references.
#include "techniques/vct/ConeSet.h"
#include "techniques/vct/RadianceRange.h"
#include "techniques/vct/ShMath.h"
#include "techniques/vct/VoxelMip.h"
#include "techniques/vct/VoxelOverlap.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

using namespace bounce::vct;

namespace {

constexpr double kPi = glm::pi<double>();

// The factored test runs in float on coordinates up to ~10 voxels: its plane and edge values carry
// rounding errors of ~1e-6 voxels. Shrinking / growing the reference's shape by 1e-4 voxels brackets
// that with a 100x margin, so only voxels within 1e-4 of touching may differ (zero-measure ties).
constexpr double kTieBracket = 1e-4;

// Float evaluations of O(1) quantities: a few float roundings.
constexpr float kFloatTol = 2e-6f;

std::vector<uint8_t> factoredSet(glm::vec3 a, glm::vec3 b, glm::vec3 c, Separability s, glm::ivec3 grid) {
    std::vector<glm::ivec3> voxels;
    voxelizeTriangle(a, b, c, s, grid, voxels);
    std::vector<uint8_t> set(size_t(grid.x * grid.y * grid.z), 0);
    for (const glm::ivec3& p : voxels) {
        EXPECT_TRUE(p.x >= 0 && p.y >= 0 && p.z >= 0 && p.x < grid.x && p.y < grid.y && p.z < grid.z)
            << p.x << " " << p.y << " " << p.z;
        if (p.x < 0 || p.y < 0 || p.z < 0 || p.x >= grid.x || p.y >= grid.y || p.z >= grid.z) continue;
        uint8_t& cell = set[size_t(p.x + grid.x * (p.y + grid.y * p.z))];
        EXPECT_EQ(cell, 0) << "voxel appended twice: " << p.x << " " << p.y << " " << p.z;
        cell = 1;
    }
    return set;
}

std::vector<uint8_t> referenceSet(glm::vec3 a, glm::vec3 b, glm::vec3 c, Separability s, glm::ivec3 grid,
                                  double dilation) {
    std::vector<uint8_t> set(size_t(grid.x * grid.y * grid.z), 0);
    for (int z = 0; z < grid.z; ++z)
        for (int y = 0; y < grid.y; ++y)
            for (int x = 0; x < grid.x; ++x)
                set[size_t(x + grid.x * (y + grid.y * z))] = overlapsReference(a, b, c, glm::ivec3(x, y, z), s, dilation);
    return set;
}

struct Comparison {
    int missed = 0;     // in the shrunk reference (clearly overlapping) but not in the factored set
    int spurious = 0;   // in the factored set but not in the grown reference (clearly disjoint)
    int ties = 0;       // factored != exact closed reference: voxels only touched
    int factored = 0;   // size of the factored set
};

Comparison compareWithReference(glm::vec3 a, glm::vec3 b, glm::vec3 c, Separability s, glm::ivec3 grid) {
    std::vector<uint8_t> f = factoredSet(a, b, c, s, grid);
    std::vector<uint8_t> inner = referenceSet(a, b, c, s, grid, -kTieBracket);
    std::vector<uint8_t> exact = referenceSet(a, b, c, s, grid, 0.0);
    std::vector<uint8_t> outer = referenceSet(a, b, c, s, grid, kTieBracket);
    Comparison r;
    for (size_t i = 0; i < f.size(); ++i) {
        r.missed += inner[i] && !f[i];
        r.spurious += f[i] && !outer[i];
        r.ties += f[i] != exact[i];
        r.factored += f[i];
    }
    return r;
}

glm::ivec3 voxelOf(size_t index, glm::ivec3 grid) {
    int i = int(index);
    return glm::ivec3(i % grid.x, (i / grid.x) % grid.y, i / (grid.x * grid.y));
}

// Exact triangle / inscribed-diamond (octahedron |x - c|_1 <= r) intersection by the separating-axis
// theorem: the triangle normal, the 4 octahedron face normals (+-1, +-1, 1) and the 18 products of
// the triangle's edges with the octahedron's 6 edge directions. Used to show that Thin6 never misses
// a voxel whose diamond the triangle really meets (which is what makes it 6-separating).
bool triangleMeetsDiamond(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::ivec3 voxel, double r) {
    glm::dvec3 centre = glm::dvec3(voxel) + 0.5;
    glm::dvec3 t[3] = {glm::dvec3(a) - centre, glm::dvec3(b) - centre, glm::dvec3(c) - centre};
    glm::dvec3 e[3] = {t[1] - t[0], t[2] - t[1], t[0] - t[2]};
    std::vector<glm::dvec3> axes = {glm::cross(e[0], e[1]), {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    const glm::dvec3 octaEdges[6] = {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}};
    for (const glm::dvec3& edge : e)
        for (const glm::dvec3& o : octaEdges) axes.push_back(glm::cross(edge, o));
    for (const glm::dvec3& ax : axes) {
        double support = r * std::max({std::abs(ax.x), std::abs(ax.y), std::abs(ax.z)});
        if (support == 0.0) continue;
        double p0 = glm::dot(t[0], ax), p1 = glm::dot(t[1], ax), p2 = glm::dot(t[2], ax);
        if (std::min({p0, p1, p2}) > support || std::max({p0, p1, p2}) < -support) return false;
    }
    return true;
}

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    void quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        uint32_t base = uint32_t(positions.size());
        positions.insert(positions.end(), {a, b, c, d});
        indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
};

// World point from (u, v) in the plane of maximal projection and w along the depth axis `axis`
// (the inverse of Eq. 4.1's swizzle: world[axis] = w).
glm::vec3 fromDominantFrame(float u, float v, float w, int axis) {
    if (axis == 0) return glm::vec3(w, u, v);
    if (axis == 1) return glm::vec3(v, w, u);
    return glm::vec3(u, v, w);
}

size_t cellIndex(glm::ivec3 p, int n) { return size_t(p.x + n * (p.y + n * p.z)); }

}  // namespace

// ---------------------------------------------------------------------------------------------------
// Overlap test

TEST(VctOverlap, SwizzleIsEq41AndInverts) {
    EXPECT_EQ(dominantAxis(glm::vec3(-3, 1, 2)), 0);
    EXPECT_EQ(dominantAxis(glm::vec3(0.5f, -4, 2)), 1);
    EXPECT_EQ(dominantAxis(glm::vec3(0.5f, 1, -2)), 2);
    EXPECT_EQ(dominantAxis(glm::vec3(1, 1, 1)), 0);  // ties go to the lower axis
    // Eq. 4.1: x dominant -> v.yzx, y dominant -> v.zxy: the dominant axis becomes the depth axis z.
    EXPECT_EQ(swizzleToDominant(glm::vec3(1, 2, 3), 0), glm::vec3(2, 3, 1));
    EXPECT_EQ(swizzleToDominant(glm::vec3(1, 2, 3), 1), glm::vec3(3, 1, 2));
    EXPECT_EQ(swizzleToDominant(glm::vec3(1, 2, 3), 2), glm::vec3(1, 2, 3));
    for (int axis = 0; axis < 3; ++axis) {
        glm::ivec3 p(4, 7, 9);
        EXPECT_EQ(unswizzleFromDominant(swizzleToDominant(p, axis), axis), p);
        EXPECT_EQ(swizzleToDominant(fromDominantFrame(1, 2, 3, axis), axis), glm::vec3(1, 2, 3));
    }
}

// A triangle exactly in the integer plane z = 3 touches the voxel layers k = 2 (from below) and
// k = 3. The closed reference sets both; the factored ranges are half-open and keep only k = 3, the
// same columns, once. All coordinates are multiples of 1/4, so the float code is exact here.
TEST(VctOverlap, TriangleOnVoxelFace) {
    const glm::ivec3 grid(8);
    const glm::vec3 a(0.5f, 0.25f, 3.0f), b(3.75f, 0.5f, 3.0f), c(1.25f, 3.5f, 3.0f);
    for (Separability s : {Separability::Thin6, Separability::Conservative26}) {
        SCOPED_TRACE(s == Separability::Thin6 ? "Thin6" : "Conservative26");
        std::vector<uint8_t> f = factoredSet(a, b, c, s, grid);
        std::vector<uint8_t> exact = referenceSet(a, b, c, s, grid, 0.0);
        std::vector<uint8_t> inner = referenceSet(a, b, c, s, grid, -kTieBracket);
        int count = 0;
        for (size_t i = 0; i < f.size(); ++i) {
            glm::ivec3 p = voxelOf(i, grid);
            if (f[i]) {
                ++count;
                EXPECT_EQ(p.z, 3);
            }
            if (p.z == 3) {
                EXPECT_EQ(f[i], exact[i]) << p.x << " " << p.y;
            } else if (p.z == 2) {
                EXPECT_EQ(exact[i], exact[i + 64]) << "the layer below touches the same columns";
            } else {
                EXPECT_EQ(exact[i], 0);
            }
            EXPECT_EQ(inner[i], 0) << "a flat triangle on z = 3 enters no shrunk voxel";
        }
        EXPECT_GT(count, 4);
    }
    // The thin set is the columns whose inscribed 2D diamond meets the triangle: a subset.
    std::vector<uint8_t> thin = factoredSet(a, b, c, Separability::Thin6, grid);
    std::vector<uint8_t> cons = factoredSet(a, b, c, Separability::Conservative26, grid);
    for (size_t i = 0; i < thin.size(); ++i) EXPECT_LE(thin[i], cons[i]);
}

// A triangle well inside one voxel: the conservative set is that voxel; the thin set is too when the
// triangle passes through the voxel's centre (so it meets the diamond).
TEST(VctOverlap, TriangleInsideOneVoxel) {
    const glm::ivec3 grid(8);
    const glm::vec3 a(2.3f, 3.4f, 4.45f), b(2.7f, 3.45f, 4.55f), c(2.5f, 3.7f, 4.5f);
    for (Separability s : {Separability::Thin6, Separability::Conservative26}) {
        std::vector<uint8_t> f = factoredSet(a, b, c, s, grid);
        for (size_t i = 0; i < f.size(); ++i)
            EXPECT_EQ(f[i], voxelOf(i, grid) == glm::ivec3(2, 3, 4) ? 1 : 0);
        Comparison r = compareWithReference(a, b, c, s, grid);
        EXPECT_EQ(r.missed, 0);
        EXPECT_EQ(r.spurious, 0);
        EXPECT_EQ(r.ties, 0);
    }
    // A small triangle in a corner of voxel (2, 3, 4), far from its diamond: conservative keeps the
    // voxel; thin agrees with the reference definition either way (SS10's edge tests may accept it).
    const glm::vec3 p(2.02f, 3.03f, 4.05f), q(2.1f, 3.05f, 4.02f), w(2.05f, 3.1f, 4.08f);
    std::vector<uint8_t> cons = factoredSet(p, q, w, Separability::Conservative26, grid);
    for (size_t i = 0; i < cons.size(); ++i) EXPECT_EQ(cons[i], voxelOf(i, grid) == glm::ivec3(2, 3, 4) ? 1 : 0);
    Comparison thin = compareWithReference(p, q, w, Separability::Thin6, grid);
    EXPECT_EQ(thin.missed + thin.spurious + thin.ties, 0);
    EXPECT_LE(thin.factored, 1);
    EXPECT_FALSE(triangleMeetsDiamond(p, q, w, glm::ivec3(2, 3, 4), 0.5));
}

// A triangle through the grid point (4, 4, 4) (all coordinates dyadic, the float code exact): the
// plane enters 6 of the 8 voxels around the corner and only touches the 2 in the octants along +-n.
TEST(VctOverlap, TriangleThroughVoxelCorner) {
    const glm::ivec3 grid(8);
    const glm::vec3 P(4.0f), A(0.75f, -0.5f, 0.25f), B(-0.25f, 0.625f, 0.5f);
    const glm::vec3 a = P + A, b = P + B, c = P - 0.75f * (A + B);
    for (Separability s : {Separability::Thin6, Separability::Conservative26}) {
        SCOPED_TRACE(s == Separability::Thin6 ? "Thin6" : "Conservative26");
        Comparison r = compareWithReference(a, b, c, s, grid);
        EXPECT_EQ(r.missed, 0);
        EXPECT_EQ(r.spurious, 0);
    }
    int touching = 0, entered = 0, factoredCorner = 0;
    std::vector<uint8_t> f = factoredSet(a, b, c, Separability::Conservative26, grid);
    for (int k = 0; k < 8; ++k) {
        glm::ivec3 v(3 + (k & 1), 3 + ((k >> 1) & 1), 3 + ((k >> 2) & 1));
        touching += overlapsReference(a, b, c, v, Separability::Conservative26, 0.0);
        entered += overlapsReference(a, b, c, v, Separability::Conservative26, -kTieBracket);
        factoredCorner += f[cellIndex(v, 8)];
    }
    EXPECT_EQ(touching, 8);
    EXPECT_EQ(entered, 6);
    EXPECT_GE(factoredCorner, 6);
    EXPECT_LE(factoredCorner, 7);  // half-open: at most the touched voxel [4,5)^3 that holds the corner
}

// A near-degenerate sliver (width ~0.02 voxels, dyadic coordinates so that the float normal is
// exact) still voxelizes to a set bracketed by the reference, and the conservative set holds every
// voxel the sliver's long edge passes through. Zero-area triangles voxelize to nothing.
TEST(VctOverlap, SliverAndDegenerate) {
    const glm::ivec3 grid(8);
    const glm::vec3 a(1.25f, 1.5f, 1.75f), b(6.5f, 5.25f, 3.0f);
    const glm::vec3 c = 0.5f * (a + b) + glm::vec3(1.0f / 64, -1.0f / 64, 1.0f / 128);
    for (Separability s : {Separability::Thin6, Separability::Conservative26}) {
        Comparison r = compareWithReference(a, b, c, s, grid);
        EXPECT_EQ(r.missed, 0);
        EXPECT_EQ(r.spurious, 0);
        EXPECT_GE(r.factored, s == Separability::Thin6 ? 4 : 12);  // ~7 voxels long; thin keeps the diamonds it crosses
    }
    std::vector<uint8_t> cons = factoredSet(a, b, c, Separability::Conservative26, grid);
    for (int i = 0; i <= 1000; ++i) {
        glm::vec3 x = a + (b - a) * (float(i) / 1000.0f);
        glm::vec3 frac = x - glm::floor(x);  // skip samples within rounding of a voxel boundary
        if (glm::min(frac.x, glm::min(frac.y, frac.z)) < 1e-4f || glm::max(frac.x, glm::max(frac.y, frac.z)) > 1.0f - 1e-4f) continue;
        EXPECT_TRUE(cons[cellIndex(glm::ivec3(glm::floor(x)), 8)]) << i;
    }
    std::vector<glm::ivec3> out;
    for (Separability s : {Separability::Thin6, Separability::Conservative26}) {
        voxelizeTriangle(a, b, a, s, grid, out);                // two equal vertices
        voxelizeTriangle(a, b, 0.5f * (a + b), s, grid, out);  // exactly collinear (dyadic midpoint)
        voxelizeTriangle(a, a, a, s, grid, out);
    }
    EXPECT_TRUE(out.empty());
}

// ~2000 random triangles of all sizes (0.05 to 8 voxels), partly outside the 8^3 grid; half with
// continuous coordinates, half snapped to 1/16 so that edges run exactly through voxel corners and
// faces (ties). For both separabilities the factored set lies between the reference shrunk and
// grown by 1e-4 voxels; it equals the exact closed reference except for touched-only voxels.
// Also: Thin6 is a subset of Conservative26, and Thin6 holds every voxel whose inscribed diamond the
// triangle really meets.
TEST(VctOverlap, RandomTrianglesMatchReference) {
    const glm::ivec3 grid(8);
    std::mt19937 rng(20130826);
    std::uniform_real_distribution<float> centre(-0.5f, 8.5f), unit(-1.0f, 1.0f), logScale(std::log(0.05f), std::log(8.0f));
    int missed = 0, spurious = 0, ties = 0, total = 0, thinNotConservative = 0, diamondMissed = 0, thinBeyondDiamond = 0;
    int tiesContinuous = 0, degenerate = 0, totalThin = 0;
    for (int n = 0; n < 2000; ++n) {
        glm::vec3 m(centre(rng), centre(rng), centre(rng));
        float scale = std::exp(logScale(rng));
        glm::vec3 v[3];
        for (glm::vec3& p : v) {
            p = m + scale * glm::vec3(unit(rng), unit(rng), unit(rng));
            if (n % 2 == 1) p = glm::round(p * 16.0f) / 16.0f;
        }
        if (!setupTriangle(v[0], v[1], v[2], Separability::Thin6).valid) {
            // Snapping small triangles to 1/16 makes some collinear: they voxelize to nothing (the
            // reference would treat them as segments).
            ++degenerate;
            for (Separability s : {Separability::Thin6, Separability::Conservative26})
                EXPECT_EQ(compareWithReference(v[0], v[1], v[2], s, grid).factored, 0);
            continue;
        }
        std::vector<uint8_t> sets[2];
        for (int si = 0; si < 2; ++si) {
            Separability s = si == 0 ? Separability::Thin6 : Separability::Conservative26;
            Comparison r = compareWithReference(v[0], v[1], v[2], s, grid);
            missed += r.missed;
            spurious += r.spurious;
            ties += r.ties;
            if (n % 2 == 0) tiesContinuous += r.ties;
            total += r.factored;
            if (si == 0) totalThin += r.factored;
            sets[si] = factoredSet(v[0], v[1], v[2], s, grid);
        }
        for (size_t i = 0; i < sets[0].size(); ++i) {
            thinNotConservative += sets[0][i] && !sets[1][i];
            bool entersDiamond = triangleMeetsDiamond(v[0], v[1], v[2], voxelOf(i, grid), 0.5 - kTieBracket);
            bool touchesDiamond = triangleMeetsDiamond(v[0], v[1], v[2], voxelOf(i, grid), 0.5 + kTieBracket);
            diamondMissed += entersDiamond && !sets[0][i];
            thinBeyondDiamond += sets[0][i] && !touchesDiamond;
        }
    }
    EXPECT_EQ(missed, 0);
    EXPECT_EQ(spurious, 0);
    EXPECT_EQ(thinNotConservative, 0);
    EXPECT_EQ(diamondMissed, 0);
    EXPECT_GT(total, 10000);  // the test is not vacuous
    EXPECT_LT(degenerate, 100);
    // Ties: the quantized half touches voxel boundaries often, the continuous half essentially never
    // (a float rounding would have to land within ~1e-6 of a boundary).
    EXPECT_LE(tiesContinuous, 2);
    std::printf("[ VctOverlap ] %d factored voxels, %d touched-only differences from the closed reference "
                "(%d continuous), %d of %d thin voxels whose diamond the triangle misses (SS10's 2D edge tests), "
                "%d degenerate triangles\n",
                total, ties, tiesContinuous, thinBeyondDiamond, totalThin, degenerate);
}

// ---------------------------------------------------------------------------------------------------
// Voxelized sheets

// An axis-aligned square spanning the grid at a non-integer (3.37) and an integer (5) coordinate
// along each axis: exactly N^2 voxels, all in layer floor(coordinate), for both separabilities.
TEST(VctSheet, AxisAlignedPlaneIsOneVoxelThick) {
    const int N = 16;
    for (int axis = 0; axis < 3; ++axis)
        for (float height : {3.37f, 5.0f}) {
            Mesh mesh;
            mesh.quad(fromDominantFrame(-1, -1, height, axis), fromDominantFrame(N + 1, -1, height, axis),
                      fromDominantFrame(N + 1, N + 1, height, axis), fromDominantFrame(-1, N + 1, height, axis));
            for (Separability s : {Separability::Thin6, Separability::Conservative26}) {
                SCOPED_TRACE(testing::Message() << "axis " << axis << " height " << height << " sep " << int(s));
                std::vector<uint8_t> occ = voxelizeMeshOccupancy(mesh.positions, mesh.indices, glm::ivec3(N), s);
                int count = 0;
                for (size_t i = 0; i < occ.size(); ++i) {
                    if (!occ[i]) continue;
                    ++count;
                    EXPECT_EQ(voxelOf(i, glm::ivec3(N))[axis], int(std::floor(height)));
                }
                EXPECT_EQ(count, N * N);
            }
        }
}

// A tilted plane w = 4 + 1/16 + 0.75 u - 0.5 v spanning the grid (and leaving it through both depth
// faces), for each dominant axis. Its depth at column centres is never within 1/16 of an integer or
// a voxel centre, so there are no ties.
//  - Thin6: exactly one voxel in every column where the plane is inside the grid, none elsewhere.
//  - Thin6 is 6-separating: no two face-adjacent empty voxels have centres on opposite sides.
//  - Conservative26 contains Thin6 and is 26-separating (no such pair among the 26 neighbours).
TEST(VctSheet, TiltedPlaneSeparability) {
    const int N = 16;
    auto depth = [](float u, float v) { return 4.0625f + 0.75f * u - 0.5f * v; };
    for (int axis = 0; axis < 3; ++axis) {
        SCOPED_TRACE(testing::Message() << "dominant axis " << axis);
        Mesh mesh;
        mesh.quad(fromDominantFrame(-2, -2, depth(-2, -2), axis), fromDominantFrame(N + 2, -2, depth(N + 2, -2), axis),
                  fromDominantFrame(N + 2, N + 2, depth(N + 2, N + 2), axis),
                  fromDominantFrame(-2, N + 2, depth(-2, N + 2), axis));
        std::vector<uint8_t> thin = voxelizeMeshOccupancy(mesh.positions, mesh.indices, glm::ivec3(N), Separability::Thin6);
        std::vector<uint8_t> cons =
            voxelizeMeshOccupancy(mesh.positions, mesh.indices, glm::ivec3(N), Separability::Conservative26);
        auto at = [&](const std::vector<uint8_t>& occ, int u, int v, int w) {
            return occ[cellIndex(glm::ivec3(glm::floor(fromDominantFrame(float(u), float(v), float(w), axis))), N)];
        };
        // Signed depth of the voxel centre (u, v, w) above the plane.
        auto side = [&](int u, int v, int w) { return (w + 0.5f) - depth(u + 0.5f, v + 0.5f); };
        for (int u = 0; u < N; ++u)
            for (int v = 0; v < N; ++v) {
                int inColumn = 0;
                for (int w = 0; w < N; ++w) inColumn += at(thin, u, v, w);
                float d = depth(u + 0.5f, v + 0.5f);
                EXPECT_EQ(inColumn, (d >= 0.0f && d < float(N)) ? 1 : 0) << u << " " << v;
            }
        int tunnels6 = 0, tunnels26 = 0, thinNotCons = 0;
        for (int u = 0; u < N; ++u)
            for (int v = 0; v < N; ++v)
                for (int w = 0; w < N; ++w) {
                    thinNotCons += at(thin, u, v, w) && !at(cons, u, v, w);
                    for (int du = -1; du <= 1; ++du)
                        for (int dv = -1; dv <= 1; ++dv)
                            for (int dw = -1; dw <= 1; ++dw) {
                                int u2 = u + du, v2 = v + dv, w2 = w + dw;
                                if (u2 < 0 || v2 < 0 || w2 < 0 || u2 >= N || v2 >= N || w2 >= N) continue;
                                if (side(u, v, w) >= 0.0f || side(u2, v2, w2) <= 0.0f) continue;  // below -> above
                                bool faceNeighbour = std::abs(du) + std::abs(dv) + std::abs(dw) == 1;
                                if (faceNeighbour && !at(thin, u, v, w) && !at(thin, u2, v2, w2)) ++tunnels6;
                                if (!at(cons, u, v, w) && !at(cons, u2, v2, w2)) ++tunnels26;
                            }
                }
        EXPECT_EQ(tunnels6, 0);
        EXPECT_EQ(tunnels26, 0);
        EXPECT_EQ(thinNotCons, 0);
    }
}

// Dense occupancy: index x + grid.x * (y + grid.y * z) on a non-cubic grid; a triangle partly
// outside the grid is clipped; a bad index list throws.
TEST(VctOccupancy, IndexOrderAndClipping) {
    const glm::ivec3 grid(4, 5, 6);
    std::vector<glm::vec3> positions = {{3.2f, 1.3f, 2.4f}, {3.8f, 1.4f, 2.5f}, {3.4f, 1.7f, 2.6f}};
    std::vector<uint32_t> indices = {0, 1, 2};
    std::vector<uint8_t> occ = voxelizeMeshOccupancy(positions, indices, grid, Separability::Conservative26);
    ASSERT_EQ(occ.size(), size_t(4 * 5 * 6));
    for (size_t i = 0; i < occ.size(); ++i) EXPECT_EQ(occ[i], i == size_t(3 + 4 * (1 + 5 * 2)) ? 1 : 0) << i;

    positions = {{-3.0f, 2.5f, -3.0f}, {20.0f, 2.5f, -3.0f}, {-3.0f, 2.5f, 20.0f}};  // the plane y = 2.5
    occ = voxelizeMeshOccupancy(positions, indices, grid, Separability::Thin6);
    int count = 0;
    for (size_t i = 0; i < occ.size(); ++i) {
        if (!occ[i]) continue;
        ++count;
        EXPECT_EQ(voxelOf(i, grid).y, 2);
    }
    EXPECT_EQ(count, 4 * 6);  // the triangle covers the whole x-z footprint of the grid
    indices = {0, 1};
    EXPECT_THROW(voxelizeMeshOccupancy(positions, indices, grid, Separability::Thin6), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// Spherical harmonics

namespace {

// Midpoint rule in (theta, phi): error O(h^2) for smooth integrands, O(h) near the clamped
// cosine's kink; with 400 x 800 cells both are below 1e-4 for the O(1) integrands used here.
template <typename F>
double integrateSphere(F f, int nTheta = 400) {
    const int nPhi = 2 * nTheta;
    const double dTheta = kPi / nTheta, dPhi = 2.0 * kPi / nPhi;
    double sum = 0.0;
    for (int i = 0; i < nTheta; ++i) {
        double theta = (i + 0.5) * dTheta;
        double st = std::sin(theta), ct = std::cos(theta);
        for (int j = 0; j < nPhi; ++j) {
            double phi = (j + 0.5) * dPhi;
            sum += f(glm::vec3(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct))) * st;
        }
    }
    return sum * dTheta * dPhi;
}
constexpr double kQuadratureTol = 1e-4;

std::vector<glm::vec3> testDirections() {
    std::vector<glm::vec3> out = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::mt19937 rng(7);
    std::normal_distribution<float> g;
    for (int i = 0; i < 50; ++i) out.push_back(glm::normalize(glm::vec3(g(rng), g(rng), g(rng))));
    return out;
}

// Solid angle of the rectangle [x1, x2] x [y1, y2] in the plane at distance h, seen from the origin
// (inclusion-exclusion of corner rectangles, Omega = atan(x y / (h sqrt(x^2 + y^2 + h^2)))).
double rectangleSolidAngle(double x1, double x2, double y1, double y2, double h) {
    auto F = [h](double x, double y) { return std::atan(x * y / (h * std::sqrt(x * x + y * y + h * h))); };
    return F(x2, y2) - F(x1, y2) - F(x2, y1) + F(x1, y1);
}

}  // namespace

TEST(VctSh, BasisIsOrthonormalWithThesisSigns) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double v = integrateSphere([&](glm::vec3 d) { return double(shBasis(d)[i]) * double(shBasis(d)[j]); });
            EXPECT_NEAR(v, i == j ? 1.0 : 0.0, kQuadratureTol) << i << " " << j;
        }
    // Fig. B.3: (Y00, Y1-1 ~ -y, Y10 ~ +z, Y11 ~ -x).
    EXPECT_NEAR(shBasis({1, 0, 0}).w, -0.488602512f, kFloatTol);
    EXPECT_NEAR(shBasis({0, 1, 0}).y, -0.488602512f, kFloatTol);
    EXPECT_NEAR(shBasis({0, 0, 1}).z, 0.488602512f, kFloatTol);
    EXPECT_NEAR(shBasis({0, 0, 1}).x, 0.2820947918f, kFloatTol);
    EXPECT_NEAR(double(kShY00), 0.5 / std::sqrt(kPi), 3e-8);  // float constant: 1 ulp = 3e-8
    EXPECT_NEAR(double(kShY1), std::sqrt(3.0) / (2.0 * std::sqrt(kPi)), 6e-8);
}

TEST(VctSh, ProjectedConstantEvaluatesBack) {
    for (float L : {0.0f, 0.7f, 12.5f})
        for (glm::vec3 d : testDirections()) EXPECT_NEAR(shEvaluate(shProjectConstant(L), d), L, kFloatTol * (1 + L));
    // And it is the actual projection: integral of L * Y_i.
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(integrateSphere([&](glm::vec3 d) { return 0.7 * shBasis(d)[i]; }), shProjectConstant(0.7f)[i], kQuadratureTol);
}

// The cosine lobe is the projection of max(0, d . w): numerically, as an identity (its evaluation is
// 1/4 + (d . w) / 2 in any direction), and its DC term integrates to pi (integral of the clamped
// cosine over the sphere).
TEST(VctSh, CosineLobeIsProjectionOfClampedCosine) {
    for (glm::vec3 d : {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(0.3f, -0.8f, 0.5f))}) {
        glm::vec4 lobe = shCosineLobe(d);
        for (int i = 0; i < 4; ++i) {
            double projected = integrateSphere([&](glm::vec3 w) { return std::max(0.0, double(glm::dot(d, w))) * shBasis(w)[i]; });
            EXPECT_NEAR(projected, lobe[i], 1e-3) << i;  // cells cut by the kink add an O(h^2) ~ 1e-4 error
        }
        for (glm::vec3 w : testDirections()) EXPECT_NEAR(shEvaluate(lobe, w), 0.25f + 0.5f * glm::dot(d, w), kFloatTol);
        // integral of sum_i c_i Y_i = c_0 * integral Y00 = c_0 * 4 pi Y00.
        EXPECT_NEAR(lobe.x * 4.0 * kPi * kShY00, kPi, 1e-6);
    }
}

// Eqs. 5.2-5.4: the two face solid angles by the thesis's integral (midpoint rule, 4096^2 cells:
// error ~h^2/24 * |Laplacian| ~ 1e-7) and in closed form; near + far faces tile the sphere.
TEST(VctSh, FaceSolidAngles) {
    EXPECT_NEAR(faceSolidAngleNumerical(true, 4096), 3.113997196, 1e-6);
    EXPECT_NEAR(faceSolidAngleNumerical(false, 4096), 1.074793009, 1e-6);
    EXPECT_NEAR(rectangleSolidAngle(-1, 3, -3, 1, 1), 3.113997196, 1e-9);
    EXPECT_NEAR(rectangleSolidAngle(-1, 3, -3, 1, 3), 1.074793009, 1e-9);
    EXPECT_NEAR(double(kShNearFaceSolidAngle), 3.113997196, 1e-6);  // float constants: 1 ulp ~ 2.4e-7
    EXPECT_NEAR(double(kShFarFaceSolidAngle), 1.074793009, 1e-6);
    EXPECT_NEAR(3.0 * kShNearFaceSolidAngle + 3.0 * kShFarFaceSolidAngle, 4.0 * kPi, 1e-6);
}

// d_face, near/far, and which solid angle each of the 48 child/face pairs subtends: the face of
// parent [-2, 2]^3 seen from child centre c in {+-1}^3, computed in closed form.
TEST(VctSh, ChildFaceGeometry) {
    EXPECT_NEAR(glm::distance(childFaceDirection(0, 1), glm::vec3(-1, 1, 1) / std::sqrt(3.0f)), 0.0f, kFloatTol);
    EXPECT_NEAR(glm::distance(childFaceDirection(0, 0), glm::vec3(3, 1, 1) / std::sqrt(11.0f)), 0.0f, kFloatTol);
    for (int child = 0; child < 8; ++child) {
        glm::dvec3 centre((child & 1) ? 1 : -1, (child & 2) ? 1 : -1, (child & 4) ? 1 : -1);
        int near = 0;
        for (int face = 0; face < 6; ++face) {
            int axis = face / 2;
            double sign = face % 2 == 0 ? 1.0 : -1.0;
            double h = 2.0 - sign * centre[axis];  // distance from the child centre to the face plane
            glm::dvec3 faceCentre(0.0);
            faceCentre[axis] = 2.0 * sign;
            glm::vec3 expected = glm::vec3(glm::normalize(faceCentre - centre));
            EXPECT_NEAR(glm::distance(childFaceDirection(child, face), expected), 0.0f, kFloatTol);
            EXPECT_NEAR(glm::length(childFaceDirection(child, face)), 1.0f, kFloatTol);
            EXPECT_EQ(isNearFace(child, face), h == 1.0);
            int u = (axis + 1) % 3, w = (axis + 2) % 3;
            double omega = rectangleSolidAngle(-2 - centre[u], 2 - centre[u], -2 - centre[w], 2 - centre[w], h);
            EXPECT_NEAR(omega, isNearFace(child, face) ? kShNearFaceSolidAngle : kShFarFaceSolidAngle, 1e-6);
            near += isNearFace(child, face);
        }
        EXPECT_EQ(near, 3);
    }
}

TEST(VctShMip, IdenticalIsotropicChildrenKeepTheirRadiance) {
    const glm::vec3 radiance(0.3f, 0.6f, 0.9f);
    std::array<std::optional<ShRgb>, 8> children;
    for (auto& c : children) c = shProjectConstantRgb(radiance);
    ShRgb normalised = shMipParent(children);
    ShRgb literal = shMipParent(children, false);
    for (const glm::vec4* c : {&normalised.r, &normalised.g, &normalised.b})
        for (int i = 1; i < 4; ++i) EXPECT_NEAR((*c)[i], 0.0f, 1e-5f);  // band 1 cancels (sums of ~10 terms of size ~4)
    for (glm::vec3 d : testDirections()) {
        glm::vec3 a = shEvaluateRgb(normalised, d), b = shEvaluateRgb(literal, d);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(a[k], radiance[k], 1e-5f);
            EXPECT_NEAR(b[k], float(kPi) * radiance[k], 3e-5f);  // Eq. 5.9 as printed gains pi per level
        }
    }
}

// Spec 2.9: one unit-radiance child in the (-,-,-) corner gives, averaged over the active children
// (the thesis) and before the division by pi, pi +- D/2 along +-X with D = Omega_near / sqrt(3) +
// 5 Omega_far / sqrt(11): 4.85 vs 1.43. Premultiplied (the GPU's convention) the parent is an eighth of
// that, its opacity being 1/8. The lobe leans towards the parent centre, +(1, 1, 1).
TEST(VctShMip, SingleCornerChildLeansTowardsParentCentre) {
    std::array<std::optional<ShRgb>, 8> children;
    children[0] = shProjectConstantRgb(glm::vec3(1.0f));
    ShRgb literal = shMipParent(children, false);
    ShRgb normalised = shMipParent(children);
    const double D = 3.113997196 / std::sqrt(3.0) + 5.0 * 1.074793009 / std::sqrt(11.0);
    for (int axis = 0; axis < 3; ++axis) {
        glm::vec3 d(0.0f);
        d[axis] = 1.0f;
        EXPECT_NEAR(8.0 * shEvaluateRgb(literal, d).r, kPi + D / 2, 1e-5);
        EXPECT_NEAR(8.0 * shEvaluateRgb(literal, -d).r, kPi - D / 2, 1e-5);
        EXPECT_NEAR(8.0 * shEvaluateRgb(normalised, d).g, (kPi + D / 2) / kPi, 1e-5);
    }
    EXPECT_NEAR(8.0 * shEvaluateRgb(literal, {1, 0, 0}).b, 4.85, 0.005);  // the spec's rounded values
    EXPECT_NEAR(8.0 * shEvaluateRgb(literal, {-1, 0, 0}).b, 1.43, 0.005);
    glm::vec3 towardsCentre = glm::normalize(glm::vec3(1.0f));
    for (glm::vec3 d : testDirections()) EXPECT_LE(shEvaluateRgb(normalised, d).r, shEvaluateRgb(normalised, towardsCentre).r + kFloatTol);
}

TEST(VctShMip, NoActiveChildrenGiveZero) {
    std::array<std::optional<ShRgb>, 8> children;
    ShRgb p = shMipParent(children);
    for (const glm::vec4* c : {&p.r, &p.g, &p.b}) EXPECT_EQ(*c, glm::vec4(0.0f));
}

// ---------------------------------------------------------------------------------------------------
// Cones

TEST(VctCones, SixDiffuseConesOfEq68) {
    const float printed[6][3] = {{0.000000f, 1.000000f, 0.000000f},  {0.000000f, 0.500000f, 0.866025f},
                                 {0.823639f, 0.500000f, 0.267617f},  {0.509037f, 0.500000f, -0.700629f},
                                 {-0.509037f, 0.500000f, -0.700629f}, {-0.823639f, 0.500000f, 0.267617f}};
    for (int k = 0; k < 6; ++k) {
        const glm::vec3& d = kDiffuseConeDirections[size_t(k)];
        EXPECT_NEAR(glm::length(d), 1.0f, kFloatTol);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(d[i], printed[k][i], 1e-6f);  // printed to 6 decimals
    }
    EXPECT_EQ(kDiffuseConeDirections[0], glm::vec3(0, 1, 0));
    for (int k = 1; k < 6; ++k) {
        const glm::vec3& d = kDiffuseConeDirections[size_t(k)];
        EXPECT_NEAR(std::acos(d.y) * 180.0 / kPi, 60.0, 1e-4);  // ring cones 60 degrees from the normal
        const glm::vec3& e = kDiffuseConeDirections[size_t(k % 5 + 1)];
        double cosAzimuth = (d.x * e.x + d.z * e.z) / (std::hypot(d.x, d.z) * std::hypot(e.x, e.z));
        EXPECT_NEAR(std::acos(cosAzimuth) * 180.0 / kPi, 72.0, 1e-4);  // neighbours 72 degrees apart
    }
}

TEST(VctCones, WeightsAreCosineIntegralsSummingToPi) {
    double sum = 0.0;
    for (float w : kDiffuseConeWeights) sum += w;
    EXPECT_NEAR(sum, kPi, 1e-6);
    // Eq. 6.9: integral of cos(theta) sin(theta) over the cap theta < 30 degrees and a 72-degree
    // wedge of 30..90 degrees.
    EXPECT_NEAR(kDiffuseConeCentralWeight, 2.0 * kPi * 0.5 * std::pow(std::sin(kPi / 6), 2), 1e-7);
    EXPECT_NEAR(kDiffuseConeRingWeight, 2.0 * kPi / 5 * 0.5 * (1.0 - std::pow(std::sin(kPi / 6), 2)), 1e-7);
    EXPECT_NEAR(kDiffuseConeCentralWeight, kPi / 4, 1e-7);
    EXPECT_NEAR(kDiffuseConeRingWeight, 3 * kPi / 20, 1e-7);
}

TEST(VctCones, ConeRatioStartDistanceAndExtent) {
    EXPECT_NEAR(coneRatio(kDiffuseConeAperture), 1.0f, kFloatTol);
    EXPECT_NEAR(coneRatio(0.0f), 0.0f, kFloatTol);
    EXPECT_NEAR(coneRatio(float(kPi / 2)), std::sqrt(0.5) / (1 - std::sqrt(0.5)), 1e-5);
    // d_s = clamp(fMin |v| / (n.w), fMin |v|, fMax |v|), here |v| = 2, fMin = 1.5, fMax = 6.
    EXPECT_NEAR(coneStartDistance(1.0f, 2.0f, 1.5f, 6.0f), 3.0f, kFloatTol);
    EXPECT_NEAR(coneStartDistance(0.5f, 2.0f, 1.5f, 6.0f), 6.0f, kFloatTol);
    EXPECT_NEAR(coneStartDistance(0.3f, 2.0f, 1.5f, 6.0f), 10.0f, kFloatTol);
    EXPECT_NEAR(coneStartDistance(0.25f, 2.0f, 1.5f, 6.0f), 12.0f, kFloatTol);  // n.w = fMin / fMax
    EXPECT_NEAR(coneStartDistance(0.1f, 2.0f, 1.5f, 6.0f), 12.0f, kFloatTol);
    EXPECT_NEAR(coneStartDistance(0.0f, 2.0f, 1.5f, 6.0f), 12.0f, kFloatTol);
    EXPECT_NEAR(coneStartDistance(-0.4f, 2.0f, 1.5f, 6.0f), 12.0f, kFloatTol);
    EXPECT_NEAR(coneStartDistance(1.0001f, 2.0f, 1.5f, 6.0f), 3.0f, kFloatTol);
    EXPECT_NEAR(voxelExtent(Separability::Conservative26, {1, 2, 3}), std::sqrt(14.0f), kFloatTol);
    EXPECT_EQ(voxelExtent(Separability::Thin6, {1, 3, 2}), 3.0f);
}

// ---------------------------------------------------------------------------------------------------
// Isotropic and anisotropic mips, RGBA8 running average

namespace {
const glm::vec4 kRed(1, 0, 0, 1), kGreen(0, 1, 0, 1), kEmpty(0);
void expectVec4Near(glm::vec4 a, glm::vec4 b, float tol = kFloatTol) {
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}
}  // namespace

TEST(VctMip, IsotropicOpacityWeightedAverage) {
    std::array<glm::vec4, 8> children;
    children.fill(glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
    expectVec4Near(isotropicMipParent(children), glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
    // Half-empty block: the colour of the occupied half at half the opacity, premultiplied.
    children = {kRed, kRed, kGreen, kGreen, kEmpty, kEmpty, kEmpty, kEmpty};
    expectVec4Near(isotropicMipParent(children), 0.5f * glm::vec4(0.5f, 0.5f, 0.0f, 1.0f));
    // Opacity weights the colour: 1 * red + 0.25 * blue (premultiplied (0, 0, 0.25, 0.25)), i.e. the
    // straight colour (0.8, 0, 0.2) at opacity 1.25 / 8.
    children = {kRed, glm::vec4(0, 0, 0.25f, 0.25f), kEmpty, kEmpty, kEmpty, kEmpty, kEmpty, kEmpty};
    expectVec4Near(isotropicMipParent(children), (1.25f / 8.0f) * glm::vec4(0.8f, 0.0f, 0.2f, 1.0f));
    children.fill(kEmpty);
    expectVec4Near(isotropicMipParent(children), kEmpty);
}

// Red in the -x half, green in the +x half, level 0 duplicated to the faces: looking along +X the
// front (-x) layer hides the back one, and along -X the other way round; across the layers (+-Y,
// +-Z) the pairs do not occlude each other and the colours average.
TEST(VctMip, AnisotropicFrontLayerHidesBackLayer) {
    std::array<AnisoVoxel, 8> children;
    for (int c = 0; c < 8; ++c) children[size_t(c)] = anisoFromIsotropic((c & 1) ? kGreen : kRed);
    AnisoVoxel p = anisotropicMipParent(children);
    expectVec4Near(p[0], kRed);    // +X
    expectVec4Near(p[1], kGreen);  // -X
    for (int face = 2; face < 6; ++face) expectVec4Near(p[size_t(face)], glm::vec4(0.5f, 0.5f, 0.0f, 1.0f));

    // A half-transparent red front (premultiplied (0.5, 0, 0, 0.5)): 0.5 red + 0.5 * green behind it.
    for (int c = 0; c < 8; ++c) children[size_t(c)] = anisoFromIsotropic((c & 1) ? kGreen : glm::vec4(0.5f, 0, 0, 0.5f));
    p = anisotropicMipParent(children);
    expectVec4Near(p[0], glm::vec4(0.5f, 0.5f, 0.0f, 1.0f));
    expectVec4Near(p[1], kGreen);

    // Only the -x half occupied: opaque along +-X (every pair has one opaque child), half-opaque
    // along +-Y, +-Z (two of the four pairs are empty); the colour is red everywhere (premultiplied:
    // half red at half opacity).
    for (int c = 0; c < 8; ++c) children[size_t(c)] = anisoFromIsotropic((c & 1) ? kEmpty : kRed);
    p = anisotropicMipParent(children);
    expectVec4Near(p[0], kRed);
    expectVec4Near(p[1], kRed);
    for (int face = 2; face < 6; ++face) expectVec4Near(p[size_t(face)], glm::vec4(0.5f, 0.0f, 0.0f, 0.5f));

    // The near child of each face: the one a ray along the face direction meets first.
    EXPECT_EQ(anisoNearChild(0, 6), 6);  // +X: bit 0 clear
    EXPECT_EQ(anisoNearChild(1, 6), 7);  // -X: bit 0 set
    EXPECT_EQ(anisoNearChild(2, 5), 5);  // +Y: bit 1 clear
    EXPECT_EQ(anisoNearChild(5, 3), 7);  // -Z: bit 2 set
}

// Face values are used per face: a child whose +Y face differs only changes the parent's +Y face.
TEST(VctMip, AnisotropicUsesEachFacesOwnValues) {
    std::array<AnisoVoxel, 8> children;
    for (auto& c : children) c = anisoFromIsotropic(kRed);
    children[0][2] = kGreen;  // child 0 (near for +Y in its pair) seen along +Y
    AnisoVoxel p = anisotropicMipParent(children);
    expectVec4Near(p[2], glm::vec4(0.75f, 0.25f, 0.0f, 1.0f));
    for (int face : {0, 1, 3, 4, 5}) expectVec4Near(p[size_t(face)], kRed);
}

TEST(VctPack, RgbCountRoundTripAndClamp) {
    for (uint32_t v : {0u, 0x01020304u, 0xFF00FF00u, 0xFFFFFFFFu}) EXPECT_EQ(packRgbCount(unpackRgbCount(v)), v);
    EXPECT_EQ(unpackRgbCount(0x04030201u), glm::vec4(1, 2, 3, 4));  // r in the low byte, count in the high one
    EXPECT_EQ(packRgbCount(glm::vec4(300.0f, -5.0f, 254.6f, 7.9f)), 0x07FF00FFu);  // clamp, round rgb, truncate count
}

// Fig. B.1's running average: successive writes give the mean of the written colours (each update
// rounds to 1/255: an error made at update k of n is scaled by k/n afterwards, so the total stays
// within (n + 1)/4 / 255 = 2.75/255 for n = 10), the count is the number of writes, and it
// saturates at 255 without disturbing a steady colour.
TEST(VctPack, RunningAverage) {
    uint32_t v = averageRgba8(0u, glm::vec3(1, 0, 0));
    EXPECT_EQ(v, packRgbCount(glm::vec4(255, 0, 0, 1)));
    v = averageRgba8(v, glm::vec3(0, 0, 1));
    EXPECT_EQ(unpackRgbCount(v), glm::vec4(128, 0, 128, 2));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    glm::vec3 sum(0.0f);
    v = 0;
    for (int i = 0; i < 10; ++i) {
        glm::vec3 c(u01(rng), u01(rng), u01(rng));
        sum += c;
        v = averageRgba8(v, c);
    }
    glm::vec4 stored = unpackRgbCount(v);
    EXPECT_EQ(stored.a, 10.0f);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(stored[k] / 255.0f, sum[k] / 10.0f, 2.75f / 255.0f);
    v = 0;
    for (int i = 0; i < 300; ++i) v = averageRgba8(v, glm::vec3(0.25f, 0.5f, 0.75f));
    EXPECT_EQ(unpackRgbCount(v), glm::vec4(64, 128, 191, 255));  // round(63.75), round(127.5), round(191.25)
}

TEST(VctShMip, ChildMatricesEqualTheSixFaceSum) {
    // The GPU mip multiplies each child's coefficients by shMipChildMatrix; it must be the literal
    // per-face sum of Eq. 5.9 for any coefficients (float sums of 6 terms: 1e-5 relative).
    const glm::vec4 v(0.7f, -0.3f, 0.2f, 0.45f);
    for (int i = 0; i < 8; ++i) {
        std::array<std::optional<bounce::vct::ShRgb>, 8> one;
        one[static_cast<size_t>(i)] = bounce::vct::ShRgb{v, v, v};
        const glm::vec4 literal = 8.0f * bounce::vct::shMipParent(one, false).r;  // the parent is the eighth
        const glm::vec4 viaMatrix = bounce::vct::shMipChildMatrix(i) * v;
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(viaMatrix[k], literal[k], 1e-5f * (1.0f + std::abs(literal[k]))) << i << " " << k;
    }
}

// The automatic radiance range (RadianceRange.h): a 2 m grey plane 1 m under a point light reflects at
// most rho / pi * I / 1 m^2, straight under the light; 16,384 area-weighted samples come within a few
// millimetres of that point (cos^3 falloff: 1 - 1.5 r^2), so the estimate is within 0.1 % below it.
TEST(VctRadianceRange, BrightestReflectionOfAPlaneUnderAPointLight) {
    bounce::Scene s;
    bounce::Mesh m;
    m.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    m.normals.assign(4, glm::vec3(0, 1, 0));
    m.indices = {0, 2, 1, 0, 3, 2};
    s.meshes.push_back(m);
    bounce::Material mat;
    mat.baseColor = glm::vec3(0.2f, 0.6f, 0.4f);
    s.materials.push_back(mat);
    s.objects.push_back(bounce::Object{});
    bounce::Light l;
    l.type = bounce::LightType::Point;
    l.position = {0, 1, 0};
    l.intensity = glm::vec3(3.0f);
    const auto samples = rangeSamples(s, 16384);
    ASSERT_EQ(samples.size(), 16384u);
    for (const RangeSample& r : samples) EXPECT_NEAR(r.normal.y, 1.0f, 1e-6f);
    const float exact = 0.6f / float(kPi) * 3.0f;
    const float got = brightestReflectedRadiance(samples, s, {l}, 0.0f);
    EXPECT_LE(got, exact * 1.0001f);
    EXPECT_GT(got, exact * 0.999f);
    // A light behind the one-sided plane lights nothing.
    l.position = {0, -1, 0};
    EXPECT_EQ(brightestReflectedRadiance(samples, s, {l}, 0.0f), 0.0f);
}
