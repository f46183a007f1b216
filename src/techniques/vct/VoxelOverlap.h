#pragma once
// The triangle/voxel overlap test of Rauwendaal 2013 section 4.1 (after Schwarz & Seidel 2010 and
// Akenine-Moller 2005), GL-free: the factored per-triangle constants of Figs. 4.4 (26-separating,
// "conservative") and 4.5 (6-separating, "thin"), the dominant-axis swizzle of Eq. 4.1, the loop the
// triangle-parallel voxelizer runs, and an independent brute-force reference for the unit tests.
// shaders/techniques/vct/overlap.glsl mirrors setupTriangle / testXY / depthRange / testYZZX line for
// line, so this file is plain float math (no std algorithms, no early-outs the shader lacks).
//
// Voxel space: unit voxels; voxel p = (i, j, k) spans [i, i+1] x [j, j+1] x [k, k+1]; the grid is
// [0, grid.x) x [0, grid.y) x [0, grid.z).
//
// Boundary convention (ties). The 2D edge tests are closed (>= 0, as printed). The voxel ranges
// (bounding box and depth) are half-open, [k, k+1): a point exactly on the integer plane z = k counts
// for voxel k only. That is what floor() for both ends of every range gives (spec 2.1 erratum (b));
// it makes an axis-aligned triangle at an integer height one voxel thick instead of two. So the
// factored set lies between the closed reference (touching counts) and the open one (touching does
// not): overlapsReference(.., -eps) => voxelizeTriangle => overlapsReference(.., +eps). They differ
// only for voxels the triangle touches without entering (zero-measure contact).
//
// Errata applied (spec 2.1): (a) the printed listings evaluate the YZ and ZX tests with p.xy; here
// p.yz and p.zx. (b) conservative depth range [floor(zlo), floor(zhi)]. (c) thin depth range: Fig.
// 4.5 prints [floor(zint), ceil(zint)], which adds the voxel above every column (a two-voxel sheet);
// the voxel whose inscribed diamond the plane crosses is floor(zint) (see depthRange), so the range
// is [floor(zint), floor(zint)].
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace bounce::vct {

enum class Separability {
    Thin6,          // 6-separating: the voxel's inscribed diamond (octahedron) is tested (Fig. 4.5)
    Conservative26  // 26-separating: the whole voxel cube is tested (Fig. 4.4)
};

// Triangles with |cross(e0, e1)|^2 at or below this (voxel units^4, i.e. area below ~5e-11 voxels^2)
// are treated as zero-area and voxelize to nothing; it keeps the divisions by n.z finite.
inline constexpr float kDegenerateNormalLength2 = 1e-20f;

// The dominant axis of n (0 x, 1 y, 2 z); ties go to the lower axis: x if |n.x| >= |n.y|, |n.z|.
int dominantAxis(glm::vec3 n);
// Eq. 4.1: v.yzx when x dominates, v.zxy when y dominates, v otherwise; the depth axis becomes z.
glm::vec3 swizzleToDominant(glm::vec3 v, int axis);
glm::ivec3 swizzleToDominant(glm::ivec3 v, int axis);
// The inverse permutation (p.zxy for axis 0, p.yzx for axis 1).
glm::ivec3 unswizzleFromDominant(glm::ivec3 p, int axis);

// The per-triangle constants of Figs. 4.4 / 4.5, all in the swizzled frame (XY = plane of maximal
// projection, z = depth axis). Edge i is e_i = v[(i+1)%3] - v[i].
struct TriangleSetup {
    Separability separability = Separability::Conservative26;
    bool valid = false;                 // false for zero-area triangles (nothing is voxelized)
    int axis = 2;                       // dominant axis of the unswizzled normal
    glm::vec3 v[3] = {};                // swizzled vertices
    glm::vec3 n = {};                   // sign(n.z) * cross(e0, e1): n.z > 0
    glm::vec2 nXY[3] = {}, nYZ[3] = {}, nZX[3] = {};  // inward projected edge normals (unnormalized)
    float dXY[3] = {}, dYZ[3] = {}, dZX[3] = {};        // factored edge offsets
    float dMin = 0.0f, dMax = 0.0f;     // Conservative26: lowest / highest plane depth offsets
    float dCen = 0.0f;                  // Thin6: plane depth offset at the column centre
    glm::vec3 lo = {}, hi = {};         // swizzled bounding box of the vertices (voxel units)
};

TriangleSetup setupTriangle(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, Separability s);

// The swizzled voxel bounding box [floor(lo), floor(hi)] clamped to the (swizzled) grid. False when
// it is empty (the triangle misses the grid) or the triangle is invalid.
bool triangleVoxelBounds(const TriangleSetup& t, glm::ivec3 grid, glm::ivec3& bmin, glm::ivec3& bmax);
// Fig. 4.4/4.5 line 15/14: the 2D test in the plane of maximal projection; p = swizzled voxel corner.
bool testXY(const TriangleSetup& t, glm::ivec2 p);
// Lines 16-17 / 15-17: the voxels [result.x, result.y] of column p that the plane test leaves,
// clamped to [zLo, zHi] (empty when result.x > result.y).
glm::ivec2 depthRange(const TriangleSetup& t, glm::ivec2 p, int zLo, int zHi);
// Line 19 (with the p.yz / p.zx erratum): the two remaining projections; p = swizzled voxel corner.
bool testYZZX(const TriangleSetup& t, glm::ivec3 p);

// The factored algorithm: appends the (unswizzled) voxels of `grid` that the triangle overlaps, each
// once per call, in loop order. Zero-area triangles append nothing.
void voxelizeTriangle(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, Separability s, glm::ivec3 grid,
                      std::vector<glm::ivec3>& out);

// Independent brute-force reference (double precision, unfactored, no swizzle; see the .cpp for the
// derivation). Closed semantics: touching counts. `dilation` grows (> 0) or shrinks (< 0) the tested
// shape by that many voxels: the box for Conservative26, the diamond (and the bounding-box test's
// box) for Thin6; the tests use +-1e-4 to bracket the factored float code.
bool overlapsReference(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, glm::ivec3 voxel, Separability s,
                       double dilation = 0.0);

// Dense occupancy (1 = some triangle overlaps the voxel), index x + grid.x * (y + grid.y * z).
// positionsInVoxelSpace are indexed by `indices`, three per triangle.
std::vector<uint8_t> voxelizeMeshOccupancy(const std::vector<glm::vec3>& positionsInVoxelSpace,
                                           const std::vector<uint32_t>& indices, glm::ivec3 grid,
                                           Separability s);

}  // namespace bounce::vct
