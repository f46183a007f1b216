// Rauwendaal 2013 section 4.1, Figs. 4.4 and 4.5: the factored triangle/voxel overlap test. The
// factored part (setupTriangle .. voxelizeTriangle) is written so that overlap.glsl can repeat it
// line for line: float math, GLSL's sign() (0 at 0), floor(), no library algorithms.
#include "techniques/vct/VoxelOverlap.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bounce::vct {

namespace {

// GLSL's sign(): -1, 0 or +1. A zero normal component makes that projection's edge normals zero, so
// its tests pass: the projection is a segment, and the plane test already decides (see the
// reference's derivation below).
float signf(float x) { return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f); }
float maxf(float a, float b) { return a > b ? a : b; }
float minf(float a, float b) { return a < b ? a : b; }
float absf(float a) { return a < 0.0f ? -a : a; }
// Clamp that maps NaN to lo (GLSL's clamp leaves NaN undefined; converting NaN to int is UB in C++).
float clampf(float x, float lo, float hi) { return x >= lo ? (x <= hi ? x : hi) : lo; }

}  // namespace

int dominantAxis(glm::vec3 n) {
    float ax = absf(n.x), ay = absf(n.y), az = absf(n.z);
    if (ax >= ay && ax >= az) return 0;
    return ay >= az ? 1 : 2;
}

glm::vec3 swizzleToDominant(glm::vec3 v, int axis) {
    return axis == 0 ? glm::vec3(v.y, v.z, v.x) : (axis == 1 ? glm::vec3(v.z, v.x, v.y) : v);
}

glm::ivec3 swizzleToDominant(glm::ivec3 v, int axis) {
    return axis == 0 ? glm::ivec3(v.y, v.z, v.x) : (axis == 1 ? glm::ivec3(v.z, v.x, v.y) : v);
}

glm::ivec3 unswizzleFromDominant(glm::ivec3 p, int axis) {
    return axis == 0 ? glm::ivec3(p.z, p.x, p.y) : (axis == 1 ? glm::ivec3(p.y, p.z, p.x) : p);
}

TriangleSetup setupTriangle(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, Separability s) {
    TriangleSetup t;
    t.separability = s;
    const bool conservative = s == Separability::Conservative26;
    // The cyclic swizzle permutes cross-product components exactly, so the normal of the swizzled
    // triangle below is this one swizzled, bit for bit.
    glm::vec3 nWorld = glm::cross(v1 - v0, v2 - v1);
    t.valid = glm::dot(nWorld, nWorld) > kDegenerateNormalLength2;
    t.axis = dominantAxis(nWorld);
    t.v[0] = swizzleToDominant(v0, t.axis);
    t.v[1] = swizzleToDominant(v1, t.axis);
    t.v[2] = swizzleToDominant(v2, t.axis);
    glm::vec3 e[3] = {t.v[1] - t.v[0], t.v[2] - t.v[1], t.v[0] - t.v[2]};
    glm::vec3 n = glm::cross(e[0], e[1]);
    float sx = signf(n.x), sy = signf(n.y), sz = signf(n.z);
    for (int i = 0; i < 3; ++i) {
        // Inward edge normals of the three projections (XY, YZ, ZX: the 2D coordinates are (x, y),
        // (y, z), (z, x)); a projection is counter-clockwise when the matching normal component is
        // positive, and (-e.v, e.u) is e rotated by +90 degrees.
        t.nXY[i] = sz * glm::vec2(-e[i].y, e[i].x);
        t.nYZ[i] = sx * glm::vec2(-e[i].z, e[i].y);
        t.nZX[i] = sy * glm::vec2(-e[i].x, e[i].z);
        glm::vec2 vXY(t.v[i].x, t.v[i].y), vYZ(t.v[i].y, t.v[i].z), vZX(t.v[i].z, t.v[i].x);
        if (conservative) {
            // Fig. 4.4 lines 7-9: <nE, p + c - v_i> >= 0 with the critical corner c = (nE > 0).
            t.dXY[i] = -glm::dot(t.nXY[i], vXY) + maxf(0.0f, t.nXY[i].x) + maxf(0.0f, t.nXY[i].y);
            t.dYZ[i] = -glm::dot(t.nYZ[i], vYZ) + maxf(0.0f, t.nYZ[i].x) + maxf(0.0f, t.nYZ[i].y);
            t.dZX[i] = -glm::dot(t.nZX[i], vZX) + maxf(0.0f, t.nZX[i].x) + maxf(0.0f, t.nZX[i].y);
        } else {
            // Fig. 4.5 lines 7-9: the 2D diamond inscribed in the voxel's square, centre p + 0.5,
            // radius 0.5, has support 0.5 * max(|nE.x|, |nE.y|) in direction nE.
            t.dXY[i] = glm::dot(t.nXY[i], glm::vec2(0.5f) - vXY) + 0.5f * maxf(absf(t.nXY[i].x), absf(t.nXY[i].y));
            t.dYZ[i] = glm::dot(t.nYZ[i], glm::vec2(0.5f) - vYZ) + 0.5f * maxf(absf(t.nYZ[i].x), absf(t.nYZ[i].y));
            t.dZX[i] = glm::dot(t.nZX[i], glm::vec2(0.5f) - vZX) + 0.5f * maxf(absf(t.nZX[i].x), absf(t.nZX[i].y));
        }
    }
    n = sz * n;  // n.z > 0, so the lower plane offset gives the lower depth (line 10)
    t.n = n;
    if (conservative) {
        // Lines 11-12: the plane's depth over the column [p.x, p.x+1] x [p.y, p.y+1] is
        // z(q) = (<n, v0> - <n.xy, q>) / n.z, lowest at the corner q = p + (n.xy > 0) and highest at
        // q = p + (n.xy < 0).
        t.dMin = glm::dot(n, t.v[0]) - maxf(0.0f, n.x) - maxf(0.0f, n.y);
        t.dMax = glm::dot(n, t.v[0]) - minf(0.0f, n.x) - minf(0.0f, n.y);
    } else {
        // Line 11: the plane's depth at the column centre p.xy + 0.5.
        t.dCen = glm::dot(n, t.v[0]) - 0.5f * n.x - 0.5f * n.y;
    }
    t.lo = glm::vec3(minf(t.v[0].x, minf(t.v[1].x, t.v[2].x)), minf(t.v[0].y, minf(t.v[1].y, t.v[2].y)),
                     minf(t.v[0].z, minf(t.v[1].z, t.v[2].z)));
    t.hi = glm::vec3(maxf(t.v[0].x, maxf(t.v[1].x, t.v[2].x)), maxf(t.v[0].y, maxf(t.v[1].y, t.v[2].y)),
                     maxf(t.v[0].z, maxf(t.v[1].z, t.v[2].z)));
    return t;
}

bool triangleVoxelBounds(const TriangleSetup& t, glm::ivec3 grid, glm::ivec3& bmin, glm::ivec3& bmax) {
    glm::ivec3 g = swizzleToDominant(grid, t.axis);
    // Half-open voxels: the voxels [floor(lo), floor(hi)], clamped in float before the conversion.
    bmin = glm::ivec3(int(clampf(std::floor(t.lo.x), 0.0f, float(g.x))), int(clampf(std::floor(t.lo.y), 0.0f, float(g.y))),
                      int(clampf(std::floor(t.lo.z), 0.0f, float(g.z))));
    bmax = glm::ivec3(int(clampf(std::floor(t.hi.x), -1.0f, float(g.x - 1))),
                      int(clampf(std::floor(t.hi.y), -1.0f, float(g.y - 1))),
                      int(clampf(std::floor(t.hi.z), -1.0f, float(g.z - 1))));
    return t.valid && bmin.x <= bmax.x && bmin.y <= bmax.y && bmin.z <= bmax.z;
}

bool testXY(const TriangleSetup& t, glm::ivec2 p) {
    glm::vec2 q(float(p.x), float(p.y));
    return glm::dot(t.nXY[0], q) + t.dXY[0] >= 0.0f && glm::dot(t.nXY[1], q) + t.dXY[1] >= 0.0f &&
           glm::dot(t.nXY[2], q) + t.dXY[2] >= 0.0f;
}

glm::ivec2 depthRange(const TriangleSetup& t, glm::ivec2 p, int zLo, int zHi) {
    float base = -(t.n.x * float(p.x) + t.n.y * float(p.y));
    float zmin, zmax;
    if (t.separability == Separability::Conservative26) {
        // Every voxel k with [k, k+1) meeting [zlo, zhi] (erratum (b)).
        zmin = std::floor((base + t.dMin) / t.n.z);
        zmax = std::floor((base + t.dMax) / t.n.z);
    } else {
        // The inscribed diamond of voxel k meets the plane iff the plane crosses its centre segment
        // z in [k, k+1] over the column centre: |n.z| = max |n_i| after the swizzle, so the diamond's
        // support r * max|n_i| along n is r * |n.z| (erratum (c)).
        float zint = (base + t.dCen) / t.n.z;
        zmin = std::floor(zint);
        zmax = zmin;
    }
    return glm::ivec2(int(clampf(zmin, float(zLo), float(zHi + 1))), int(clampf(zmax, float(zLo - 1), float(zHi))));
}

bool testYZZX(const TriangleSetup& t, glm::ivec3 p) {
    glm::vec2 yz(float(p.y), float(p.z)), zx(float(p.z), float(p.x));
    return glm::dot(t.nYZ[0], yz) + t.dYZ[0] >= 0.0f && glm::dot(t.nYZ[1], yz) + t.dYZ[1] >= 0.0f &&
           glm::dot(t.nYZ[2], yz) + t.dYZ[2] >= 0.0f && glm::dot(t.nZX[0], zx) + t.dZX[0] >= 0.0f &&
           glm::dot(t.nZX[1], zx) + t.dZX[1] >= 0.0f && glm::dot(t.nZX[2], zx) + t.dZX[2] >= 0.0f;
}

void voxelizeTriangle(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, Separability s, glm::ivec3 grid,
                      std::vector<glm::ivec3>& out) {
    TriangleSetup t = setupTriangle(v0, v1, v2, s);
    glm::ivec3 bmin, bmax;
    if (!triangleVoxelBounds(t, grid, bmin, bmax)) return;
    for (int x = bmin.x; x <= bmax.x; ++x) {
        for (int y = bmin.y; y <= bmax.y; ++y) {
            if (!testXY(t, glm::ivec2(x, y))) continue;
            glm::ivec2 range = depthRange(t, glm::ivec2(x, y), bmin.z, bmax.z);
            for (int z = range.x; z <= range.y; ++z) {
                if (testYZZX(t, glm::ivec3(x, y, z))) out.push_back(unswizzleFromDominant(glm::ivec3(x, y, z), t.axis));
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------------
// The brute-force reference. Derivation (shared by both separabilities): a closed triangle T and a
// closed convex body K are disjoint iff some axis separates their projections (separating-axis
// theorem). For a convex polytope K the candidate axes are T's normal, K's face normals, and the
// cross products of T's edges with K's edge directions.
//
// Conservative26, K = the voxel box B = [p, p+1]^3 (Akenine-Moller 2005): 13 axes, the 3 box
// normals, n = cross(e0, e1) and the 9 products e_i x u_j with the coordinate axes u_j. The box's
// projection onto a is [c.a - h |a|_1, c.a + h |a|_1] (centre c, half-edge h = 0.5 + dilation). This
// is exactly what Fig. 4.4 factors: the bounding box loop is the 3 box normals, the depth range is
// the plane axis n, and the 2D edge tests are the axes e_i x u_j (the inward normal of edge i in the
// projection along u_j is +-(e_i x u_j) restricted to that plane, and "the most interior corner is
// inside" is "the projections overlap on that axis").
//
// Thin6 (Schwarz & Seidel 2010, 6-separating; what Fig. 4.5 factors). D = the octahedron (diamond)
// inscribed in the voxel, vertices c +- r u_j, r = 0.5 + dilation. A voxel is set iff
//   (1) the triangle's bounding box meets the voxel's box (the loop range; box dilated too),
//   (2) the plane of T meets D: n.(x - v0) takes both signs (or 0) over the 6 vertices of D,
//   (3) for each projection P in {XY, YZ, ZX} whose image of T has non-zero area, and each edge i of
//       that image, some vertex of the 2D diamond P(D) (centre P(c), radius r) lies in the closed
//       inward half-plane of edge i: the 2D edge-function test against the diamond's critical point.
// (3) is SS10's test, which uses only the triangle's edge normals as separating axes in 2D, not the
// diamond's own edge normals (+-1, +-1); it therefore also accepts a voxel whose diamond misses T
// only in a corner region of the voxel's square (SS10 and the thesis accept these: a superset only
// thickens the sheet, never opens a 6-tunnel). When a projection has zero area, T's image is a
// segment on the image of T's plane; the plane test (2) already implies that line meets P(D), so
// skipping that projection loses nothing, as Fig. 4.5's sign(0) = 0 normals do. A triangle with
// zero normal has no plane: the reference returns false for Thin6 (the factored code skips it too).
// ---------------------------------------------------------------------------------------------------
namespace {

bool satConservative(const glm::dvec3 tri[3], const glm::dvec3& centre, double h) {
    glm::dvec3 a = tri[0] - centre, b = tri[1] - centre, c = tri[2] - centre;
    glm::dvec3 f[3] = {b - a, c - b, a - c};
    glm::dvec3 axes[13];
    int count = 0;
    axes[count++] = glm::dvec3(1, 0, 0);
    axes[count++] = glm::dvec3(0, 1, 0);
    axes[count++] = glm::dvec3(0, 0, 1);
    axes[count++] = glm::cross(f[0], f[1]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            glm::dvec3 u(0.0);
            u[j] = 1.0;
            axes[count++] = glm::cross(f[i], u);
        }
    for (const glm::dvec3& ax : axes) {
        if (ax.x == 0.0 && ax.y == 0.0 && ax.z == 0.0) continue;  // a degenerate axis separates nothing
        double pa = glm::dot(a, ax), pb = glm::dot(b, ax), pc = glm::dot(c, ax);
        double tmin = std::min({pa, pb, pc}), tmax = std::max({pa, pb, pc});
        double r = h * (std::abs(ax.x) + std::abs(ax.y) + std::abs(ax.z));
        if (tmin > r || tmax < -r) return false;
    }
    return true;
}

bool thinReference(const glm::dvec3 tri[3], const glm::ivec3& voxel, double dilation) {
    double r = 0.5 + dilation;
    glm::dvec3 lo(voxel), c = lo + 0.5;
    // (1) bounding boxes.
    for (int k = 0; k < 3; ++k) {
        double tmin = std::min({tri[0][k], tri[1][k], tri[2][k]}), tmax = std::max({tri[0][k], tri[1][k], tri[2][k]});
        if (tmax < lo[k] - dilation || tmin > lo[k] + 1.0 + dilation) return false;
    }
    // (2) plane against the 6 diamond vertices.
    glm::dvec3 n = glm::cross(tri[1] - tri[0], tri[2] - tri[1]);
    if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) return false;
    double smin = 0.0, smax = 0.0;
    for (int k = 0; k < 6; ++k) {
        glm::dvec3 vertex = c;
        vertex[k / 2] += (k % 2 == 0) ? r : -r;
        double s = glm::dot(n, vertex - tri[0]);
        smin = k == 0 ? s : std::min(smin, s);
        smax = k == 0 ? s : std::max(smax, s);
    }
    if (smin > 0.0 || smax < 0.0) return false;
    // (3) the three projections; projection `drop` keeps the cyclic pair (drop+1, drop+2): XY for z,
    // YZ for x, ZX for y.
    for (int drop = 0; drop < 3; ++drop) {
        int u = (drop + 1) % 3, w = (drop + 2) % 3;
        glm::dvec2 q[3];
        for (int i = 0; i < 3; ++i) q[i] = glm::dvec2(tri[i][u], tri[i][w]);
        glm::dvec2 e01 = q[1] - q[0], e02 = q[2] - q[0];
        double area2 = e01.x * e02.y - e01.y * e02.x;
        if (area2 == 0.0) continue;
        double orient = area2 > 0.0 ? 1.0 : -1.0;
        glm::dvec2 c2(c[u], c[w]);
        glm::dvec2 diamond[4] = {c2 + glm::dvec2(r, 0), c2 - glm::dvec2(r, 0), c2 + glm::dvec2(0, r), c2 - glm::dvec2(0, r)};
        for (int i = 0; i < 3; ++i) {
            glm::dvec2 edge = q[(i + 1) % 3] - q[i];
            glm::dvec2 inward = orient * glm::dvec2(-edge.y, edge.x);
            double best = glm::dot(inward, diamond[0] - q[i]);
            for (int k = 1; k < 4; ++k) best = std::max(best, glm::dot(inward, diamond[k] - q[i]));
            if (best < 0.0) return false;
        }
    }
    return true;
}

}  // namespace

bool overlapsReference(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, glm::ivec3 voxel, Separability s,
                       double dilation) {
    if (0.5 + dilation < 0.0) return false;
    glm::dvec3 tri[3] = {glm::dvec3(v0), glm::dvec3(v1), glm::dvec3(v2)};
    if (s == Separability::Conservative26) return satConservative(tri, glm::dvec3(voxel) + 0.5, 0.5 + dilation);
    return thinReference(tri, voxel, dilation);
}

std::vector<uint8_t> voxelizeMeshOccupancy(const std::vector<glm::vec3>& positionsInVoxelSpace,
                                           const std::vector<uint32_t>& indices, glm::ivec3 grid,
                                           Separability s) {
    if (indices.size() % 3 != 0) throw std::invalid_argument("voxelizeMeshOccupancy: index count is not a multiple of 3");
    if (grid.x <= 0 || grid.y <= 0 || grid.z <= 0) return {};
    std::vector<uint8_t> occupancy(size_t(grid.x) * size_t(grid.y) * size_t(grid.z), 0);
    std::vector<glm::ivec3> voxels;
    for (size_t i = 0; i < indices.size(); i += 3) {
        voxels.clear();
        voxelizeTriangle(positionsInVoxelSpace.at(indices[i]), positionsInVoxelSpace.at(indices[i + 1]),
                         positionsInVoxelSpace.at(indices[i + 2]), s, grid, voxels);
        for (const glm::ivec3& p : voxels)
            occupancy[size_t(p.x) + size_t(grid.x) * (size_t(p.y) + size_t(grid.y) * size_t(p.z))] = 1;
    }
    return occupancy;
}

}  // namespace bounce::vct
