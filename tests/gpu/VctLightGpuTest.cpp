// Voxel cone tracing (Rauwendaal 2013): where the light goes. Tests that pin the fixes of issue 28
// (docs/techniques/vct.md, "Where the light goes"): the GPU mips against the GL-free mirror
// (src/techniques/vct/VoxelMip, the same premultiplied convention), the two level-0 write modes on a
// voxel two surfaces share, a lone lit plane that must not light itself, and the energy over grid
// resolutions.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "techniques/vct/VctTechnique.h"
#include "techniques/vct/VoxelMip.h"

#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class VctLightGpuTest : public gputest::GpuTest {};

VctTechnique& vctOf(Pipeline& p) { return dynamic_cast<VctTechnique&>(p.technique()); }

double meanOf(const Image& img) {
    double sum = 0.0;
    for (const glm::vec3& p : img.pixels()) sum += (p.r + p.g + p.b) / 3.0;
    return sum / static_cast<double>(img.pixelCount());
}

Image oneBounceReference(const Scene& scene, int size, uint32_t spp, bool diffuseOnly = false) {
    PathTracerSettings pts;
    pts.width = pts.height = size;
    pts.samplesPerPixel = spp;
    pts.bounces = 1;
    pts.indirectOnly = true;
    pts.diffuseOnly = diffuseOnly;
    auto tracer = PathTracer::create(scene, pts);
    EXPECT_TRUE(tracer.ok());
    return tracer->render().radiance;
}

Mesh quad(const std::string& name, glm::vec3 corner, glm::vec3 u, glm::vec3 v, glm::vec3 normal) {
    Mesh m;
    m.name = name;
    m.positions = {corner, corner + u, corner + u + v, corner + v};
    m.normals.assign(4, normal);
    m.indices = {0, 1, 2, 0, 2, 3};
    if (glm::dot(glm::cross(u, v), normal) < 0.0f) m.indices = {0, 2, 1, 0, 3, 2};
    return m;
}

void addObject(Scene& s, Mesh mesh, glm::vec3 albedo) {
    Material m;
    m.name = mesh.name;
    m.baseColor = albedo;
    s.materials.push_back(m);
    s.meshes.push_back(std::move(mesh));
    Object o;
    o.name = s.meshes.back().name;
    o.mesh = static_cast<uint32_t>(s.meshes.size() - 1);
    o.material = static_cast<uint32_t>(s.materials.size() - 1);
    s.objects.push_back(o);
}

Light sun(glm::vec3 direction, float irradiance) {
    Light l;
    l.type = LightType::Directional;
    l.direction = direction;
    l.irradiance = glm::vec3(irradiance);
    return l;
}

}  // namespace

// Two surfaces inside one voxel layer: a red plane facing -x lit from -x and a green plane 1 cm
// behind it facing +x lit from +x. Every voxel of the layer is written by both (Fig. B.1's running
// average) or keeps the larger packed value (imageAtomicMax, alpha then blue then green then red
// compared). Catches an average that keeps the last write only (r or g alone) and a max that averages.
TEST_F(VctLightGpuTest, AverageAndMaxResolveTwoSurfacesInOneVoxel) {
    Scene s;
    s.name = "two-planes";
    addObject(s, quad("red", {0.04f, -1.0f, -1.0f}, {0, 2, 0}, {0, 0, 2}, {-1, 0, 0}), {0.8f, 0.0f, 0.0f});
    addObject(s, quad("green", {0.05f, -1.0f, -1.0f}, {0, 2, 0}, {0, 0, 2}, {1, 0, 0}), {0.0f, 0.8f, 0.0f});
    s.lights = {sun({1, 0, 0}, 2.0f), sun({-1, 0, 0}, 2.0f)};
    s.camera.position = {-3.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    ASSERT_TRUE(finalizeScene(s).ok());
    // A 3.2 m grid of 32 voxels of 0.1 m centred at the origin: the planes at x = 0.04 and 0.05 share
    // the layer [0, 0.1) and no voxel face.
    const std::map<std::string, std::string> grid = {{"resolution", "32"}, {"boxSide", "3.2"}, {"storage", "iso"},
                                                     {"voxelizer", "triangle"}, {"separability", "thin"}};
    std::map<std::string, std::vector<uint32_t>> level0;
    for (const char* atomic : {"average", "max"}) {
        auto settings = grid;
        settings["atomic"] = atomic;
        auto p = makePipeline(s, "vct", settings, 16);
        p->renderFrame(0);
        level0[atomic] = vctOf(*p).downloadIso(0);
    }
    const int n = 32, layer = 16;  // x in [0, 0.1) is voxel 16
    size_t checked = 0;
    for (int z = 7; z < 25; ++z)  // the planes span -1..1 m: voxels 6..25, their edges excluded
        for (int y = 7; y < 25; ++y) {
            const size_t k = static_cast<size_t>(layer + n * (y + n * z));
            const uint32_t avg = level0["average"][k], mx = level0["max"][k];
            const float ar = float(avg & 0xFF), ag = float((avg >> 8) & 0xFF), mr = float(mx & 0xFF), mg = float((mx >> 8) & 0xFF);
            ASSERT_GT(ag + ar, 0.0f) << "voxel " << y << " " << z << " not written";
            // The average of one red and one or two green writes (a plane's two triangles both write
            // the voxels on their shared diagonal): red share 1/3 .. 1/2, never 0 or 1.
            const float share = ar / (ar + ag);
            EXPECT_GT(share, 0.3f) << y << " " << z;
            EXPECT_LT(share, 0.55f) << y << " " << z;
            // Max: green's packed value (g in byte 1) beats red's (r in byte 0): pure green.
            EXPECT_EQ(mr, 0.0f) << y << " " << z;
            EXPECT_GT(mg, 0.0f) << y << " " << z;
            ++checked;
        }
    EXPECT_GT(checked, 300u);  // 18 x 18 voxels
}

// The anisotropic mip (5.3.2) on the GPU equals the GL-free mirror vct::anisotropicMipParent (the
// same premultiplied front-to-back pairs) to 8-bit rounding; the isotropic volume the aniso format
// keeps as its opacity equals vct::isotropicMipParent. Catches a swapped near/far child.
TEST_F(VctLightGpuTest, MipsMatchTheGlFreeMirror) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    auto p = makePipeline(*scene, "vct", {{"storage", "aniso"}, {"resolution", "32"}}, 16);
    p->renderFrame(0);
    VctTechnique& v = vctOf(*p);
    const int n = 32, h = 16;
    std::vector<std::vector<float>> faces0(6), faces1(6);
    for (int f = 0; f < 6; ++f) {
        faces0[f] = v.downloadVolume(f, 0);
        faces1[f] = v.downloadVolume(f, 1);
    }
    const auto iso0 = v.downloadIso(0), iso1 = v.downloadIso(1);
    auto unpack = [](uint32_t c) { return glm::vec4(c & 0xFF, (c >> 8) & 0xFF, (c >> 16) & 0xFF, (c >> 24) & 0xFF) / 255.0f; };
    double worstAniso = 0.0, worstIso = 0.0;
    size_t occupied = 0, directional = 0;
    for (int z = 0; z < h; ++z)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < h; ++x) {
                std::array<vct::AnisoVoxel, 8> children;
                std::array<glm::vec4, 8> isoChildren;
                for (int i = 0; i < 8; ++i) {
                    const size_t k = static_cast<size_t>((2 * x + (i & 1)) + n * ((2 * y + ((i >> 1) & 1)) + n * (2 * z + ((i >> 2) & 1))));
                    for (int f = 0; f < 6; ++f)
                        children[size_t(i)][size_t(f)] = glm::vec4(faces0[f][4 * k], faces0[f][4 * k + 1], faces0[f][4 * k + 2], faces0[f][4 * k + 3]);
                    isoChildren[size_t(i)] = unpack(iso0[k]);
                }
                const vct::AnisoVoxel want = vct::anisotropicMipParent(children);
                const size_t k = static_cast<size_t>(x + h * (y + h * z));
                bool differs = false;
                for (int f = 0; f < 6; ++f) {
                    const glm::vec4 got(faces1[f][4 * k], faces1[f][4 * k + 1], faces1[f][4 * k + 2], faces1[f][4 * k + 3]);
                    for (int j = 0; j < 4; ++j) worstAniso = std::max(worstAniso, double(std::abs(got[j] - want[size_t(f)][j])));
                    differs |= std::abs(want[size_t(f)].a - want[0].a) > 0.1f;
                }
                const glm::vec4 isoWant = vct::isotropicMipParent(isoChildren), isoGot = unpack(iso1[k]);
                for (int j = 0; j < 4; ++j) worstIso = std::max(worstIso, double(std::abs(isoGot[j] - isoWant[j])));
                occupied += isoWant.a > 0.0f;
                directional += differs;
            }
    ASSERT_GT(occupied, 100u);
    // The walls make faces differ (opaque along the wall's normal, half-transparent across it): the
    // comparison is not one of identical faces.
    ASSERT_GT(directional, 50u);
    // One 8-bit step (plus float slack): the GPU rounds each stored value to 1/255.
    EXPECT_LE(worstAniso, 1.01 / 255.0);
    EXPECT_LE(worstIso, 1.01 / 255.0);
}

// A lone lit plane receives no indirect light (nothing else is there). With the thesis's cones the
// receiver lit itself: the filtered volume spreads its own voxels over the cones' first samples, and
// the ring cones, 60 degrees wide and 60 degrees from the normal, graze its plane (measured 0.49 of
// the direct light with the specialised tracer, aniso, before the tangent cap). The tangent cap keeps
// every footprint above the receiver's tangent plane: measured exactly 0.
TEST_F(VctLightGpuTest, ALoneLitPlaneDoesNotLightItself) {
    Scene s;
    s.name = "lone-plane";
    addObject(s, quad("floor", {-4.0f, 0.0f, -4.0f}, {8, 0, 0}, {0, 0, 8}, {0, 1, 0}), glm::vec3(0.7f));
    s.lights = {sun({0, -1, 0}, 3.0f)};
    s.camera.position = {0.0f, 3.0f, 3.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    ASSERT_TRUE(finalizeScene(s).ok());
    for (const char* storage : {"aniso", "iso", "sh-f32"}) {
        auto p = makePipeline(s, "vct", {{"storage", storage}}, 32);
        p->renderFrame(0);
        const double indirect = meanOf(p->readback(Component::Indirect)), direct = meanOf(p->readback(Component::Direct));
        RecordProperty(std::string(storage) + "_selfLight", std::to_string(indirect / direct));
        ASSERT_GT(direct, 0.0);
        // 0.2 % of the direct light: float noise only; without the cap 0.10-0.35 (aniso, iso).
        EXPECT_LT(indirect / direct, 0.002) << storage;
    }
    // The thesis's own tracer, as printed (no cap): the receiver lights itself; the setting exists to
    // show it (docs/techniques/vct.md).
    auto p = makePipeline(s, "vct", {{"tracer", "specialised"}}, 32);
    p->renderFrame(0);
    EXPECT_GT(meanOf(p->readback(Component::Indirect)) / meanOf(p->readback(Component::Direct)), 0.05);
}

// Energy must converge as the grid refines, not fall: before issue 28 the default lost 28 % from 64^3
// to 128^3 on a large scene (coarse levels turning thin walls transparent). cornell-box and atrium
// at 32^3, 64^3 and 128^3 against the one-bounce reference.
TEST_F(VctLightGpuTest, EnergyDoesNotFallAsTheGridRefines) {
    for (const char* name : {"cornell-box", "atrium"}) {
        auto scene = loadScene(name, {{"triangles", "20000"}});
        if (std::string(name) == "cornell-box") scene = loadScene(name);
        ASSERT_TRUE(scene.ok()) << name;
        constexpr int kSize = 48;
        const double ref = meanOf(oneBounceReference(*scene, kSize, 256));
        std::vector<double> energy;
        for (const char* res : {"32", "64", "128"}) {
            energy.push_back(meanOf(renderIndirect(*scene, "vct", {{"resolution", res}}, kSize)) / ref);
            RecordProperty(std::string(name) + "_energy" + res, std::to_string(energy.back()));
        }
        for (size_t i = 1; i < energy.size(); ++i) {
            // A refinement may bring the energy down to the reference but not lose more than 10 % of
            // it below (measured: cornell-box 1.07 -> 1.03 -> 0.98, atrium 1.19 -> 1.03 -> 0.95,
            // converging on the reference from above; before issue 28 the default fell 0.85 -> 0.61).
            EXPECT_GT(energy[i], std::min(energy[i - 1], 1.0) - 0.1) << name << " step " << i;
            // And every resolution stays within the fidelity bound of +-25 % of the reference.
            EXPECT_NEAR(energy[i], 1.0, 0.25) << name << " step " << i;
        }
    }
}


// The specular cone (6.5): a glossy black floor (F0 0.5, roughness 0.2, no diffuse) in front of a
// white wall lit by a directional light. Seen from the camera the floor mirrors the wall, so its
// one-bounce light (light -> wall -> floor's GGX lobe -> eye) is the specular cone's alone; against
// the path tracer's one-bounce image with the full BRDF, on the floor more than 1 m (15 voxels) from
// the wall: nearer, the reflected cone meets the wall before Eq. 6.2's start distance (fMax |v| =
// 6.9 voxels at grazing angles) and sees nothing, a limit of the thesis's offset.
TEST_F(VctLightGpuTest, SpecularConeMirrorsALitWall) {
    Scene s;
    s.name = "glossy-floor-and-wall";
    addObject(s, quad("floor", {-2.0f, 0.0f, -2.0f}, {4, 0, 0}, {0, 0, 4}, {0, 1, 0}), glm::vec3(0.0f));
    s.materials.back().specularF0 = 0.5f;
    s.materials.back().roughness = 0.2f;
    addObject(s, quad("wall", {-2.0f, 0.0f, -2.0f}, {4, 0, 0}, {0, 3, 0}, {0, 0, 1}), glm::vec3(0.8f));
    s.lights = {sun({0.0f, -0.3f, -1.0f}, 2.0f)};
    s.camera.position = {0.0f, 1.0f, 2.0f};
    s.camera.target = {0.0f, 0.0f, -0.5f};
    ASSERT_TRUE(finalizeScene(s).ok());
    constexpr int kSize = 48;
    const Image ref = oneBounceReference(s, kSize, 256);
    std::map<std::string, double> energy;
    for (const char* specular : {"true", "false"}) {
        auto p = makePipeline(s, "vct", {{"specular", specular}}, kSize);
        p->renderFrame(0);
        const Image img = p->readback(Component::Indirect);
        const std::vector<glm::vec4> position = readLevel(p->gbuffer().position(), 0, {kSize, kSize});
        double sum = 0.0, sumRef = 0.0;
        size_t floorPixels = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const glm::vec4 q = position[static_cast<size_t>(y * kSize + x)];  // GL rows from the bottom
                if (q.w <= 0.0f || q.y > 0.01f || q.z < -1.0f) continue;
                ++floorPixels;
                const glm::vec3 a = img.at(x, kSize - 1 - y), b = ref.at(x, kSize - 1 - y);  // Image rows from the top
                sum += (a.r + a.g + a.b) / 3.0;
                sumRef += (b.r + b.g + b.b) / 3.0;
            }
        ASSERT_GT(floorPixels, 200u);
        ASSERT_GT(sumRef, 0.0);
        energy[specular] = sum / sumRef;
        RecordProperty(std::string("floorEnergy_specular_") + specular, std::to_string(energy[specular]));
    }
    // Measured 1.02 (the cone's Schlick Fresnel at n.v against the GGX lobe's integral); +-15 %, the
    // fidelity bound: a cone multiplied by 0 (0.0 without it) or halved fails.
    EXPECT_NEAR(energy["true"], 1.0, 0.15);
    EXPECT_EQ(energy["false"], 0.0);
}
