// The screen-space binary voxelization and its thick-ray march (techniques/screen_voxels, Nichols 2010
// §5.3.3): where a surface's bit lands (column and depth slice), how many bits a scene sets, and what
// voxelMarch says about segments through, beside, behind and outside the seen geometry.
#include "GpuTestSupport.h"
#include "gpu/Bindings.h"
#include "gpu/Objects.h"
#include "gpu/Program.h"
#include "render/SceneDrawer.h"
#include "render/SceneGpu.h"
#include "scene/MeshBuilder.h"
#include "techniques/screen_voxels/ScreenVoxels.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <bit>
#include <cstdio>
#include <cmath>
#include <vector>

using namespace bounce;

namespace {
class ScreenVoxelsGpuTest : public gputest::GpuTest {};

constexpr int kColumns = 128;  // the grid's default column count (ScreenVoxels.h, thesis 128^2)
constexpr int kBits = 128;     // one RGBA32UI layer, the thesis's 128 bits
constexpr int kSteps = 16;     // march samples per segment (the technique setting's default)
constexpr int kThickness = 1;  // bits each side of a sample's slice range (the setting's default)

// Adds `mesh` as one grey object.
void addObject(Scene& s, Mesh mesh) {
    if (s.materials.empty()) {
        Material grey;
        grey.name = "grey";
        grey.baseColor = glm::vec3(0.5f);
        s.materials.push_back(grey);
    }
    Object o;
    o.name = mesh.name;
    o.mesh = static_cast<uint32_t>(s.meshes.size());
    s.meshes.push_back(std::move(mesh));
    s.objects.push_back(o);
}

Mesh square(const std::string& name, glm::vec3 centre, glm::vec3 u, glm::vec3 v, glm::vec3 front) {
    MeshBuilder b(name);
    b.quad(centre - u - v, centre + u - v, centre + u + v, centre - u + v, front);
    return b.take();
}

// A 4 m floor (y = 0) and a 1 m marker square 1 m above its centre, seen from 8 m straight above (the
// 1 cm offset keeps the view direction off `up`): the floor is the far face of the scene's bounds and
// the marker the near face, so the grid spans exactly their depths.
constexpr float kFloorHalf = 2.0f, kMarkerHalf = 0.5f, kMarkerHeight = 1.0f, kEyeHeight = 8.0f;  // metres
Scene floorAndMarker() {
    Scene s;
    s.name = "floor-and-marker";
    addObject(s, square("floor", {0, 0, 0}, {kFloorHalf, 0, 0}, {0, 0, kFloorHalf}, {0, 1, 0}));
    addObject(s, square("marker", {0, kMarkerHeight, 0}, {kMarkerHalf, 0, 0}, {0, 0, kMarkerHalf}, {0, 1, 0}));
    s.camera.position = {0, kEyeHeight, 0.01f};
    s.camera.target = {0, 0, 0};
    s.camera.up = {0, 0, -1};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

// The occluder scene of the march tests, camera at z = 5 looking down -z (40 degree field of view: at
// the occluder's depth the view is 3.64 m wide): a 1 m occluder square at z = 0, a 6 m back wall at
// z = -2, a 2 m wall at z = 6 behind the camera and a 2 m wall at x = 2.5 beside the frustum (at depths
// 4-6 m the frustum reaches |x| = 1.46-2.18 m), all facing the camera's side.
Scene occluderScene() {
    Scene s;
    s.name = "occluders";
    addObject(s, square("occluder", {0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, {0, 0, 1}));
    addObject(s, square("back", {0, 0, -2}, {3, 0, 0}, {0, 3, 0}, {0, 0, 1}));
    addObject(s, square("behind-camera", {0, 0, 6}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}));
    addObject(s, square("outside", {2.5f, 0, 0}, {0, 0, 1}, {0, 1, 0}, {-1, 0, 0}));
    s.camera.position = {0, 0, 5};
    s.camera.target = {0, 0, 0};
    s.camera.up = {0, 1, 0};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

struct Grid {
    render::SceneGpu sceneGpu;
    render::SceneDrawer drawer;
    render::View camera;
    voxels::ScreenVoxels voxels;

    explicit Grid(const Scene& scene)
        : sceneGpu(scene), drawer(sceneGpu), camera(render::cameraView(scene.camera, {kColumns, kColumns})) {
        sceneGpu.update(0.0f);
        auto v = voxels::ScreenVoxels::create();
        EXPECT_TRUE(v.ok()) << v.error().message;
        voxels = std::move(*v);
        voxels.build(drawer, camera, voxels::GridSize{glm::ivec2(kColumns), kBits});
    }

    // The 128 bits of column (x, y), bottom row first (GL texture rows).
    std::vector<int> setSlices(int x, int y) const {
        std::vector<glm::uvec4> texels(static_cast<size_t>(kColumns) * kColumns);
        glGetTextureImage(voxels.bitsTexture().id(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                          static_cast<GLsizei>(texels.size() * sizeof(glm::uvec4)), texels.data());
        const glm::uvec4 t = texels[static_cast<size_t>(y) * kColumns + x];
        std::vector<int> slices;
        for (int s = 0; s < kBits; ++s)
            if ((t[s / 32] >> (s % 32)) & 1u) slices.push_back(s);
        return slices;
    }

    // The slice a view depth falls in, from the grid's own near plane and slice depth.
    int sliceOf(float viewDepth) const {
        const gpu::ScreenVoxelsGpu& u = voxels.uniforms();
        return static_cast<int>(std::floor((viewDepth - u.depth.x) * u.depth.z));
    }
    float viewDepth(glm::vec3 p) const { return -(camera.viewFromWorld * glm::vec4(p, 1.0f)).z; }
    float sliceDepth() const { return voxels.uniforms().depth.w; }

    // Where the camera ray through the centre of column (x, y) meets the plane y = height.
    glm::vec3 onHorizontalPlane(int x, int y, float height) const {
        const glm::mat4 worldFromClip = glm::inverse(camera.clipFromWorld());
        const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / float(kColumns) * 2.0f - 1.0f;
        glm::vec4 n = worldFromClip * glm::vec4(ndc, -1.0f, 1.0f), f = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
        const glm::vec3 a = glm::vec3(n) / n.w, b = glm::vec3(f) / f.w;
        return glm::mix(a, b, (height - a.y) / (b.y - a.y));
    }

    // Column centres whose camera ray meets the square |x|, |z| <= half at y = height.
    int coveredColumns(float half, float height) const {
        int n = 0;
        for (int y = 0; y < kColumns; ++y)
            for (int x = 0; x < kColumns; ++x) {
                const glm::vec3 p = onHorizontalPlane(x, y, height);
                n += std::abs(p.x) <= half && std::abs(p.z) <= half;
            }
        return n;
    }
};

struct Segment {
    glm::vec3 a, b;
};

enum class March { Uniform, Columns };  // voxelMarch (the thesis's samples), voxelTrace (every column)

// voxelMarch or voxelTrace (march.glsl) on each segment, through
// shaders/techniques/screen_voxels/march_probe.comp.
std::vector<float> march(const Grid& grid, const std::vector<Segment>& segments, March how, int thickness = kThickness,
                         int steps = kSteps) {
    auto program = gl::Program::build({"test.marchProbe", {{GL_COMPUTE_SHADER, "techniques/screen_voxels/march_probe.comp"}}});
    EXPECT_TRUE(program.ok()) << program.error().message;
    std::vector<glm::vec4> packed;
    for (const Segment& s : segments) {
        packed.emplace_back(s.a, static_cast<float>(steps));
        packed.emplace_back(s.b, static_cast<float>(thickness));
    }
    gl::Buffer in = gl::Buffer::create("test.marchSegments", packed.size() * sizeof(glm::vec4), packed.data());
    gl::Buffer out = gl::Buffer::create("test.marchFractions", segments.size() * sizeof(float));
    in.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    out.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
    grid.voxels.bind();
    program->set("u_count", static_cast<int>(segments.size()));
    program->set("u_trace", how == March::Columns ? 1 : 0);
    program->use();
    gl::Program::dispatch(static_cast<int>(segments.size()), 1, 1, 64);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> fractions(segments.size());
    out.download(0, fractions.size() * sizeof(float), fractions.data());
    return fractions;
}
}  // namespace

TEST_F(ScreenVoxelsGpuTest, EveryCoveredColumnGetsTheBitsOfItsSurfaces) {
    const Scene scene = floorAndMarker();
    Grid grid(scene);
    // Each covered column holds the bits of the depths each surface spans over it. Both squares face the
    // camera (their depth changes by 0.06 mm per column, a slice is 7.9 mm), so that is one bit per
    // surface, or two in a column whose footprint straddles a slice boundary: the floor's 5 mm of depth
    // cross at most one boundary, along one line of columns (at most its 88-column side).
    const int floorColumns = grid.coveredColumns(kFloorHalf, 0.0f);
    const int markerColumns = grid.coveredColumns(kMarkerHalf, kMarkerHeight);
    ASSERT_GT(floorColumns, kColumns * kColumns / 3);  // the floor covers about 47 % of the view
    ASSERT_GT(markerColumns, 200);
    const int floorSide = static_cast<int>(std::sqrt(static_cast<double>(floorColumns)));
    // Tolerance: the rasteriser and this count test the same column centres, so only a centre within
    // float rounding of a square's edge may go either way (GL's tie rule against the <= here); the
    // squares' perimeters cross about 450 columns. Measured: none.
    constexpr int kEdgeTies = 8;
    const auto occupied = static_cast<int>(grid.voxels.countOccupied());
    EXPECT_GE(occupied, floorColumns + markerColumns - kEdgeTies);
    EXPECT_LE(occupied, floorColumns + markerColumns + floorSide + kEdgeTies)
        << "floor " << floorColumns << " + marker " << markerColumns << " columns";
}

TEST_F(ScreenVoxelsGpuTest, SurfacesLandInTheSliceOfTheirViewDepth) {
    const Scene scene = floorAndMarker();
    Grid grid(scene);
    // The marker is the scene's nearest surface and the floor its farthest: the grid's first and last
    // slices (the depth range is the scene's bounds in view space).
    const int centre = kColumns / 2;
    const glm::vec3 floorPoint = grid.onHorizontalPlane(centre, centre, 0.0f);
    const glm::vec3 markerPoint = grid.onHorizontalPlane(centre, centre, kMarkerHeight);
    const int floorSlice = grid.sliceOf(grid.viewDepth(floorPoint));
    const int markerSlice = grid.sliceOf(grid.viewDepth(markerPoint));
    EXPECT_EQ(markerSlice, 0);
    EXPECT_EQ(floorSlice, kBits - 1);
    EXPECT_EQ(grid.setSlices(centre, centre), (std::vector<int>{markerSlice, floorSlice}));
    // A column the marker does not cover: the floor's bit alone, in the slice of its depth there.
    const int x = kColumns / 4, y = kColumns / 3;
    const glm::vec3 p = grid.onHorizontalPlane(x, y, 0.0f);
    ASSERT_LE(std::abs(p.x), kFloorHalf);
    ASSERT_GT(std::abs(p.x), kMarkerHalf);
    EXPECT_EQ(grid.setSlices(x, y), (std::vector<int>{grid.sliceOf(grid.viewDepth(p))}));
}

TEST_F(ScreenVoxelsGpuTest, MarchSeesTheVoxelizedOccludersOnly) {
    const Scene scene = occluderScene();
    Grid grid(scene);
    const std::vector<Segment> segments = {
        {{0.2f, 0.1f, 1.0f}, {-0.1f, -0.1f, -1.0f}},  // 0: through the occluder at its midpoint
        {{0.2f, 0.1f, 1.0f}, {-0.3f, 0.2f, 0.3f}},    // 1: in front of the occluder
        {{0.1f, 0.1f, -0.5f}, {-0.2f, 0.0f, -1.5f}},  // 2: hidden behind the occluder, in empty space
        {{0.5f, 0.5f, -1.0f}, {0.6f, 0.4f, -3.0f}},   // 3: through the back wall at its midpoint
        {{1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, -1.0f}},    // 4: past the occluder's side
        {{1.5f, 0.0f, 0.0f}, {3.0f, 0.0f, -0.5f}},    // 5: through the wall beside the frustum (at t = 2/3)
        {{0.3f, 0.0f, 4.0f}, {0.0f, 0.0f, 6.5f}},     // 6: through the wall behind the camera (at t = 0.8)
    };
    for (March how : {March::Uniform, March::Columns}) {
        SCOPED_TRACE(how == March::Uniform ? "voxelMarch" : "voxelTrace");
        const std::vector<float> f = march(grid, segments, how);
        // Blocked segments stop at their first occupied sample (voxelMarch: at most one step before the
        // crossing, and one more for the thick ray's extra bit each side) or column (voxelTrace: where
        // the segment enters the crossing's column, or one before it for the extra bit).
        const float step = 1.0f / kSteps;
        EXPECT_LE(f[0], 0.5f);
        EXPECT_GE(f[0], 0.5f - 2.0f * step);
        EXPECT_EQ(f[1], 1.0f);
        EXPECT_EQ(f[2], 1.0f) << "binary voxels see the empty space behind the first surface";
        EXPECT_LE(f[3], 0.5f);
        EXPECT_GE(f[3], 0.5f - 2.0f * step);
        EXPECT_EQ(f[4], 1.0f);
        // The documented limitation: the voxelization only holds what the camera sees, so occluders
        // outside its frustum (beside it, behind the camera) do not block.
        EXPECT_EQ(f[5], 1.0f);
        EXPECT_EQ(f[6], 1.0f);
    }
}

TEST_F(ScreenVoxelsGpuTest, OriginBiasKeepsASegmentOffItsOwnSurface) {
    const Scene scene = occluderScene();
    Grid grid(scene);
    // From a point on the occluder (facing the camera, normal +z) out into the free space in front.
    const glm::vec3 onSurface(0.1f, 0.1f, 0.0f), target(0.3f, 0.3f, 1.5f), normal(0, 0, 1);
    // Without bias the first sample's slice range holds the surface's own bit. Along a normal facing
    // the camera the origin clears its surface's slice, widened by the thickness, after thickness + 1
    // slice depths: the bias the techniques' rayBias is counted in.
    const float bias = (kThickness + 1) * grid.sliceDepth();
    for (March how : {March::Uniform, March::Columns}) {
        const std::vector<float> f = march(grid, {{onSurface, target}, {onSurface + bias * normal, target}}, how);
        EXPECT_EQ(f[0], 0.0f);
        EXPECT_EQ(f[1], 1.0f);
    }
}

namespace {
// A 4 cm board 0.76 m above a floor (a table top), 1.2 m x 0.8 m, seen from 3 m away at 1.1 m eye
// height: at 7-8 degrees, nearly edge-on, as furnished-room's table. A back wall 2 m behind it bounds
// the depth range.
constexpr float kBoardTop = 0.76f, kBoardThickness = 0.04f;  // metres
Scene boardScene() {
    Scene s;
    s.name = "board";
    addObject(s, square("floor", {0, 0, 0}, {3, 0, 0}, {0, 0, 3}, {0, 1, 0}));
    addObject(s, square("back", {0, 1.3f, -2}, {3, 0, 0}, {0, 1.3f, 0}, {0, 0, 1}));
    MeshBuilder board("board");
    board.axisBox({-0.6f, kBoardTop - kBoardThickness, -0.4f}, {0.6f, kBoardTop, 0.4f});
    addObject(s, board.take());
    s.camera.position = {0.3f, 1.1f, 3.0f};
    s.camera.target = {0, 0.5f, 0};
    s.camera.up = {0, 1, 0};
    s.camera.verticalFov = glm::radians(60.0f);
    s.camera.nearPlane = 0.01f;
    s.camera.farPlane = 20.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

// Vertical segments through the board from 5 cm above the floor to 2.6 m (a ceiling's height), on a grid
// over its top: the floor-to-ceiling paths of furnished-room's indirect shadow under its table.
std::vector<Segment> throughTheBoard() {
    std::vector<Segment> segments;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 24; ++i) {
            const glm::vec3 p(-0.55f + 0.0478f * i, 0.0f, -0.35f + 0.0467f * j);
            segments.push_back({p + glm::vec3(0, 0.05f, 0), p + glm::vec3(0, 2.6f, 0)});
        }
    return segments;
}
}  // namespace

TEST_F(ScreenVoxelsGpuTest, GrazingSurfacesHaveNoDepthGaps) {
    // Seen at 7-8 degrees, the board's top spans several slices of depth within one column (its
    // footprint); with only the centre's bit set, a segment crossing it elsewhere in the column found
    // an empty slice. Without the extra bit each side (thickness 0), every vertical segment through the
    // board must meet its bits in the column where it crosses.
    const Scene scene = boardScene();
    Grid grid(scene);
    const std::vector<float> f = march(grid, throughTheBoard(), March::Columns, /*thickness=*/0);
    int free = 0;
    for (float v : f) free += v >= 1.0f;
    EXPECT_EQ(free, 0) << "of " << f.size() << " segments through the board";
}

TEST_F(ScreenVoxelsGpuTest, UniformSamplesMissWhatTheColumnTraversalFinds) {
    // The thesis's uniform samples test one column per sample: a segment 2.55 m long has its 16 samples
    // 16 cm apart, several columns apart on screen, and finds the board only where a sample's slice
    // range (widened by the thick ray's bit) reaches the board's bits in that sample's column. The
    // column traversal tests every column the segment crosses. Measured: uniform misses 10 of 384
    // (5 with the derivative footprint, which over-reached past the board's edges; 145 when the
    // voxelization set only each column's centre depth), the traversal none (2 then).
    const Scene scene = boardScene();
    Grid grid(scene);
    const std::vector<Segment> segments = throughTheBoard();
    int missedUniform = 0, missedColumns = 0;
    for (float v : march(grid, segments, March::Uniform)) missedUniform += v >= 1.0f;
    for (float v : march(grid, segments, March::Columns)) missedColumns += v >= 1.0f;
    RecordProperty("missedUniform", missedUniform);
    std::printf("segments through the board missed: uniform %d, columns %d of %zu\n", missedUniform, missedColumns,
                segments.size());
    EXPECT_EQ(missedColumns, 0);
    EXPECT_GT(missedUniform, 0);
}

TEST_F(ScreenVoxelsGpuTest, FootprintsStayWithinTheirTriangles) {
    // Vertical segments 10 cm in front of the board's front face (two 5 cm slices of depth), from under the
    // board to above it: free. The board's top, seen edge-on, changes depth by about 20 cm from one row
    // of columns to the next; a fragment's footprint of +- half that, unclamped, reached 10 cm in front
    // of the board in the row above its front edge and blocked them.
    const Scene scene = boardScene();
    Grid grid(scene);
    std::vector<Segment> segments;
    for (int i = 0; i < 24; ++i) {
        const float x = -0.55f + 0.0478f * i;
        segments.push_back({{x, kBoardTop - 0.3f, 0.5f}, {x, kBoardTop + 0.3f, 0.5f}});
    }
    int blocked = 0;
    for (float v : march(grid, segments, March::Columns, /*thickness=*/0)) blocked += v < 1.0f;
    EXPECT_EQ(blocked, 0) << "of " << segments.size() << " segments in front of the board";
}

TEST_F(ScreenVoxelsGpuTest, ExactFootprintsLeaveRaysPastAnEdgeFree) {
    // The board of the tests above turned 30 degrees about the vertical and seen from 14 cm above its
    // top (at about 3 degrees: its top spans half a metre of depth per row of columns): the top's
    // triangles have a nearest corner up to 60 cm in front of the front edge where that edge is farthest
    // from it. Vertical segments 12 cm in front of the front face (three 4 cm slices of depth), from
    // under the board to above it: free. Clamping a fragment's derivative footprint to its triangle's
    // depth range (the fallback of voxelize.frag) set the slices from that nearest corner to the edge in
    // the row above the front edge and blocked them (measured 4 of 20); the triangle clipped to
    // each pixel sets only the depths it spans there.
    Scene scene = boardScene();
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0));
    scene.objects.back().transform = turn;
    scene.camera.position = {0.3f, kBoardTop + 0.14f, 3.0f};
    scene.camera.target = {0.0f, kBoardTop, 0.0f};
    ASSERT_TRUE(finalizeScene(scene).ok());
    Grid grid(scene);
    const glm::vec3 front = glm::vec3(turn * glm::vec4(0, 0, 1, 0));  // the front face's normal
    std::vector<Segment> segments;
    for (int i = 0; i < 20; ++i) {
        const glm::vec3 onEdge = glm::vec3(turn * glm::vec4(-0.55f + 0.0578f * i, 0.0f, 0.4f, 1.0f));
        const glm::vec3 p = onEdge + 0.12f * front;
        segments.push_back({{p.x, kBoardTop - 0.3f, p.z}, {p.x, kBoardTop + 0.3f, p.z}});
    }
    int blocked = 0;
    for (float v : march(grid, segments, March::Columns, /*thickness=*/0)) blocked += v < 1.0f;
    RecordProperty("blocked", blocked);
    EXPECT_EQ(blocked, 0) << "of " << segments.size() << " segments in front of the turned board";
}
