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

#include <bit>
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

// voxelMarch (march.glsl) on each segment, through shaders/techniques/screen_voxels/march_probe.comp.
std::vector<float> march(const Grid& grid, const std::vector<Segment>& segments, int steps = kSteps,
                         int thickness = kThickness) {
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
    program->use();
    gl::Program::dispatch(static_cast<int>(segments.size()), 1, 1, 64);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> fractions(segments.size());
    out.download(0, fractions.size() * sizeof(float), fractions.data());
    return fractions;
}
}  // namespace

TEST_F(ScreenVoxelsGpuTest, EveryCoveredColumnGetsOneBitPerSurface) {
    const Scene scene = floorAndMarker();
    Grid grid(scene);
    // Each covered column holds one bit per surface over it (the floor and the marker lie in one
    // depth slice per column): the bit count is the floor's covered columns plus the marker's.
    const int floorColumns = grid.coveredColumns(kFloorHalf, 0.0f);
    const int markerColumns = grid.coveredColumns(kMarkerHalf, kMarkerHeight);
    ASSERT_GT(floorColumns, kColumns * kColumns / 3);  // the floor covers about 47 % of the view
    ASSERT_GT(markerColumns, 200);
    // Tolerance: the rasteriser and this count test the same column centres, so only a centre within
    // float rounding of a square's edge may go either way (GL's tie rule against the <= here); the
    // squares' perimeters cross about 450 columns. Measured: exact.
    constexpr double kEdgeTies = 8.0;
    EXPECT_NEAR(static_cast<double>(grid.voxels.countOccupied()), floorColumns + markerColumns, kEdgeTies)
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
    const std::vector<float> f = march(grid, segments);
    // Blocked segments stop at their first occupied sample: at most one step before the crossing, and
    // one more for the thick ray's extra bit each side.
    const float step = 1.0f / kSteps;
    EXPECT_LE(f[0], 0.5f);
    EXPECT_GE(f[0], 0.5f - 2.0f * step);
    EXPECT_EQ(f[1], 1.0f);
    EXPECT_EQ(f[2], 1.0f) << "binary voxels see the empty space behind the first surface";
    EXPECT_LE(f[3], 0.5f);
    EXPECT_GE(f[3], 0.5f - 2.0f * step);
    EXPECT_EQ(f[4], 1.0f);
    // The documented limitation: the voxelization only holds what the camera sees, so occluders outside
    // its frustum (beside it, behind the camera) do not block.
    EXPECT_EQ(f[5], 1.0f);
    EXPECT_EQ(f[6], 1.0f);
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
    const std::vector<float> f = march(grid, {{onSurface, target}, {onSurface + bias * normal, target}});
    EXPECT_EQ(f[0], 0.0f);
    EXPECT_EQ(f[1], 1.0f);
}
