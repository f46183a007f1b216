// area-screen: the set-up of Nichols 2010 ch. 5 (multiresolution textured area lights): a large,
// one-sided, textured and animated screen (a TV or video wall) as the only light, facing a small stage
// of diffuse and glossy objects, so that the light's texture, its motion and its size (soft shadows)
// all show. pattern=bars plays a colour-bar test card of four frames generated here; pattern=square
// the thesis's white square bouncing on black (section 5.4.7), its pathological case for sampling.
// Details: docs/scene.md "area-screen".
#include "core/ToneMap.h"
#include "scene/AreaTexture.h"
#include "scene/BuiltinScenes.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <cmath>

namespace bounce {

namespace {

// The stage: floor x in [-2, 2], z in [-1.5, 2] m; a back wall behind the screen and two side walls,
// 2.5 m high; open at the top and the front (where the camera is), as a studio set.
constexpr float kHalfWidth = 2.0f;   // m
constexpr float kBackZ = -1.5f;      // m
constexpr float kFrontZ = 2.0f;      // m
constexpr float kWallHeight = 2.5f;  // m

// The screen: a 16:9 panel of 1.6 m x 0.9 m (a 72-inch television, the "TV/video wall" of the issue),
// centred 1.25 m above the floor (bottom edge at 0.8 m), 2 cm in front of the back wall so that it is
// not coplanar with it, facing the stage (+z). One-sided: the wall behind gets nothing from it.
constexpr float kScreenWidth = 1.6f;     // m
constexpr float kScreenHeight = 0.9f;    // m
constexpr float kScreenCentreY = 1.25f;  // m
constexpr float kScreenGap = 0.02f;      // m, in front of the back wall

// Colour bars (pattern=bars): 64 x 36 texels (16:9, square texels on the screen). The top two thirds are
// the seven bars of SMPTE EG 1-1990 at 75 % (white, yellow, cyan, green, magenta, red, blue; video level
// 0.75, decoded from sRGB to the linear multiplier 0.52), the bottom third black with a 100 % white block
// a quarter of the width wide. Each frame shifts the bars by one to the left and the block by a quarter
// to the right: four frames at 2 frames per second, a 2 s loop, so the light changes colour and moves.
constexpr int kBarsWidth = 64, kBarsHeight = 36;  // texels
constexpr int kBarsFrames = 4;
constexpr float kBarsFrameRate = 2.0f;  // frames per second
constexpr float kBarVideoLevel = 0.75f;  // 75 % bars, sRGB-encoded
constexpr std::array<glm::vec3, 7> kBarColours = {glm::vec3(1, 1, 1), glm::vec3(1, 1, 0), glm::vec3(0, 1, 1), glm::vec3(0, 1, 0),
                                                  glm::vec3(1, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)};

// Bouncing square (pattern=square): 64^2 texels, by default side a quarter of the screen's (parameter
// squareSize, a fraction of the screen's sides), the AreaTexture defaults for its motion. The
// resolution is raised so that the square spans at least two texels (a smaller one would be lost in
// the texel grid, not undersampled by the VPLs, which is what squareSize is for).
constexpr int kSquareResolution = 64;
constexpr double kDefaultSquareSize = 0.25;
constexpr double kMinSquareSize = 1.0 / 256.0;  // 2 texels at kMaxSquareResolution
constexpr int kMaxSquareResolution = 512;

// Radiance: the floor just in front of the objects sees the screen at about 1.9 m, 40 degrees off its
// axis and 50 degrees off the floor's normal: E ~ L_mean A cos cos / d^2 = 0.19 L_mean, a radiance of
// 0.55 E / pi = 0.033 L_mean, falling off towards the front and the sides. The bars' mean multiplier is
// 0.28 (4/7 of 0.52 over two thirds, 1/4 below). L = 80 W/(m^2 sr) puts the floor in view at a mean of
// 0.19 W/(m^2 sr) direct and 0.28 with interreflection, the objects at 0.24 and 0.32 (measured with the
// reference, 128^2, 256 spp, frame 0): lit like the other built-in scenes' main surfaces, brighter
// near the screen. The screen itself is then 42 W/(m^2 sr) in its white bar: a TV in a dark
// room, saturated by ACES at 0 EV. The square's mean is 1/16, so its radiance is scaled by (bars' mean) /
// (1/16) to emit the same mean flux: the two patterns are exposed alike (measured: floor 0.20 direct).
constexpr float kBarsRadiance = 80.0f;  // W/(m^2 sr), times the texture

// Materials (linear RGB albedos). The glossy ones are dielectrics (specularF0 0.04, glTF's and most
// plastics') with GGX roughness 0.2 and 0.3: sharp enough that the screen's reflection shows its
// colours, rough enough that they are lit by the whole screen.
constexpr glm::vec3 kFloorAlbedo{0.55f};
constexpr glm::vec3 kWallAlbedo{0.6f};
constexpr glm::vec3 kCrateAlbedo{0.75f, 0.72f, 0.68f};  // warm white
constexpr glm::vec3 kPillarAlbedo{0.25f, 0.35f, 0.65f};  // blue
constexpr glm::vec3 kMatteSphereAlbedo{0.7f};
constexpr glm::vec3 kRedPlasticAlbedo{0.8f, 0.25f, 0.2f};
constexpr glm::vec3 kBlackPlasticAlbedo{0.05f};
constexpr float kDielectricF0 = 0.04f;
constexpr float kSphereRoughness = 0.25f;
constexpr float kBoxRoughness = 0.3f;

// Sphere tessellation: 16 segments x 8 rings (224 triangles), smooth normals: round enough at the
// default view. (Chosen when hemicube radiosity made a patch per triangle; its charts no longer do,
// issue 30, and the tessellation stays for the scene's recorded measurements.)
constexpr int kSphereSegments = 16, kSphereRings = 8;

// Camera: at eye height 1.45 m, 1.4 m in front of the stage's open front (4.9 m from the screen),
// looking at its middle with a 45 degree vertical field of view: the whole screen, the objects and the
// floor in front of them (where their shadows fall) are in view for aspects from 1:1 to 16:9.
constexpr glm::vec3 kCameraPosition{1.7f, 1.45f, 3.0f};   // m
constexpr glm::vec3 kCameraTarget{-0.15f, 0.7f, -0.6f};    // m
constexpr float kCameraFovDegrees = 45.0f;

// A UV sphere centred at the origin with outward normals; counter-clockwise seen from outside.
Mesh uvSphere(const std::string& name, float radius, int segments, int rings) {
    Mesh m;
    m.name = name;
    for (int j = 0; j <= rings; ++j) {
        const float theta = glm::pi<float>() * static_cast<float>(j) / static_cast<float>(rings);
        for (int i = 0; i <= segments; ++i) {
            const float phi = glm::two_pi<float>() * static_cast<float>(i) / static_cast<float>(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            m.positions.push_back(radius * n);
            m.normals.push_back(n);
        }
    }
    const auto at = [&](int i, int j) { return static_cast<uint32_t>(j * (segments + 1) + i); };
    for (int j = 0; j < rings; ++j)
        for (int i = 0; i < segments; ++i) {
            // Rows run from the top pole down, columns counter-clockwise seen from above (phi about +y
            // with z = -sin): a, d below a, b beside it.
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (j != 0) m.indices.insert(m.indices.end(), {a, d, b});  // the poles' rows have one triangle
            if (j != rings - 1) m.indices.insert(m.indices.end(), {b, d, c});
        }
    return m;
}

// Frame k of the colour bars (see kBarColours): linear multipliers, row 0 at the top (v = 1).
Image colourBarsFrame(int k) {
    const float level = srgbDecode(kBarVideoLevel);
    Image image(kBarsWidth, kBarsHeight);
    const int barRows = 2 * kBarsHeight / 3;
    for (int y = 0; y < kBarsHeight; ++y)
        for (int x = 0; x < kBarsWidth; ++x) {
            glm::vec3 c(0.0f);
            if (y < barRows) {
                const int bar = (x * static_cast<int>(kBarColours.size()) / kBarsWidth + k) % static_cast<int>(kBarColours.size());
                c = level * kBarColours[static_cast<size_t>(bar)];
            } else {
                const int block = x * 4 / kBarsWidth;  // quarters of the width
                c = glm::vec3(block == k % 4 ? 1.0f : 0.0f);
            }
            image.at(x, y) = c;
        }
    return image;
}

}  // namespace

Expected<Scene> buildAreaScreen(const SceneParams& params) {
    BOUNCE_TRY(const std::string pattern, choiceParam(params, "area-screen", "pattern", "bars", {"bars", "square"}));
    BOUNCE_TRY(const double squareSizeParam,
               numberParam(params, "area-screen", "squareSize", kDefaultSquareSize, kMinSquareSize, 1.0));
    const float squareSize = static_cast<float>(squareSizeParam);
    Scene s;
    s.name = "area-screen";
    s.source = "builtin:area-screen";

    const auto material = [&](const char* name, glm::vec3 albedo, float roughness, float f0) {
        Material m;
        m.name = name;
        m.baseColor = albedo;
        m.roughness = roughness;
        m.metallic = 0.0f;
        m.specularF0 = f0;
        s.materials.push_back(m);
        return static_cast<uint32_t>(s.materials.size() - 1);
    };
    const uint32_t floorMat = material("floor", kFloorAlbedo, 1.0f, 0.0f);
    const uint32_t wallMat = material("wall", kWallAlbedo, 1.0f, 0.0f);
    const uint32_t crateMat = material("crate", kCrateAlbedo, 1.0f, 0.0f);
    const uint32_t pillarMat = material("pillar", kPillarAlbedo, 1.0f, 0.0f);
    const uint32_t matteMat = material("matte-sphere", kMatteSphereAlbedo, 1.0f, 0.0f);
    const uint32_t redMat = material("red-plastic", kRedPlasticAlbedo, kSphereRoughness, kDielectricF0);
    const uint32_t blackMat = material("black-plastic", kBlackPlasticAlbedo, kBoxRoughness, kDielectricF0);

    const auto object = [&](Mesh mesh, uint32_t mat, const glm::mat4& transform = glm::mat4(1.0f)) {
        Object o;
        o.name = mesh.name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        o.material = mat;
        o.transform = transform;
        s.meshes.push_back(std::move(mesh));
        s.objects.push_back(std::move(o));
    };
    const auto quad = [&](const char* name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 front, uint32_t mat) {
        MeshBuilder mb(name);
        mb.quad(a, b, c, d, front);
        object(mb.take(), mat);
    };
    const float x0 = -kHalfWidth, x1 = kHalfWidth, h = kWallHeight;
    quad("floor", {x0, 0, kBackZ}, {x1, 0, kBackZ}, {x1, 0, kFrontZ}, {x0, 0, kFrontZ}, {0, 1, 0}, floorMat);
    quad("back-wall", {x0, 0, kBackZ}, {x1, 0, kBackZ}, {x1, h, kBackZ}, {x0, h, kBackZ}, {0, 0, 1}, wallMat);
    quad("left-wall", {x0, 0, kBackZ}, {x0, 0, kFrontZ}, {x0, h, kFrontZ}, {x0, h, kBackZ}, {1, 0, 0}, wallMat);
    quad("right-wall", {x1, 0, kBackZ}, {x1, 0, kFrontZ}, {x1, h, kFrontZ}, {x1, h, kBackZ}, {-1, 0, 0}, wallMat);

    // A box of size `size` standing on the floor at `base`, turned by `degrees` about +y.
    const auto box = [&](const char* name, glm::vec3 size, glm::vec3 base, float degrees, uint32_t mat) {
        MeshBuilder mb(name);
        mb.axisBox(glm::vec3(-0.5f * size.x, 0.0f, -0.5f * size.z), glm::vec3(0.5f * size.x, size.y, 0.5f * size.z));
        const glm::mat4 t = glm::rotate(glm::translate(glm::mat4(1.0f), base), glm::radians(degrees), glm::vec3(0, 1, 0));
        object(mb.take(), mat, t);
    };
    box("crate", glm::vec3(0.45f), {-0.75f, 0.0f, -0.3f}, 25.0f, crateMat);
    box("pillar", {0.3f, 0.9f, 0.3f}, {0.85f, 0.0f, -0.6f}, -15.0f, pillarMat);
    box("glossy-box", {0.35f, 0.3f, 0.35f}, {0.6f, 0.0f, 0.55f}, 40.0f, blackMat);
    const auto sphere = [&](const char* name, float radius, glm::vec3 centre, uint32_t mat) {
        object(uvSphere(name, radius, kSphereSegments, kSphereRings), mat, glm::translate(glm::mat4(1.0f), centre));
    };
    sphere("glossy-sphere", 0.25f, {0.1f, 0.25f, 0.15f}, redMat);
    sphere("matte-sphere", 0.18f, {-0.4f, 0.18f, 0.5f}, matteMat);

    Light screen;
    screen.name = "screen";
    screen.type = LightType::Area;
    screen.position = {0.0f, kScreenCentreY, kBackZ + kScreenGap};
    // edgeU to the right and edgeV up seen from the stage: cross(+x, +y) = +z faces it, the picture upright.
    screen.edgeU = {kScreenWidth, 0.0f, 0.0f};
    screen.edgeV = {0.0f, kScreenHeight, 0.0f};
    screen.texture.kind = AreaTexture::Kind::Images;
    screen.texture.frameRate = kBarsFrameRate;
    for (int k = 0; k < kBarsFrames; ++k) {
        screen.texture.frames.push_back(static_cast<uint32_t>(s.textures.size()));
        s.textures.push_back({"area-screen:bars-" + std::to_string(k), colourBarsFrame(k)});
    }
    screen.radiance = glm::vec3(kBarsRadiance);
    if (pattern == "square") {
        // Same mean flux as the bars: frame 0's mean multiplier over the square's (the other frames'
        // means differ by under 1 %: 64 columns do not split into 7 equal bars).
        const float barsMean = luminance(imageMean(s.textures.front().image));
        s.textures.clear();
        screen.texture = AreaTexture{};
        screen.texture.kind = AreaTexture::Kind::BouncingSquare;
        screen.texture.resolution = kSquareResolution;
        while (squareSize * static_cast<float>(screen.texture.resolution) < 2.0f &&
               screen.texture.resolution < kMaxSquareResolution)
            screen.texture.resolution *= 2;
        screen.texture.squareSize = squareSize;
        screen.radiance = glm::vec3(kBarsRadiance * barsMean / (squareSize * squareSize));
    }
    s.lights.push_back(screen);

    s.camera.position = kCameraPosition;
    s.camera.target = kCameraTarget;
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.verticalFov = glm::radians(kCameraFovDegrees);
    s.camera.nearPlane = 0.01f;  // m
    s.camera.farPlane = 12.0f;   // m, beyond the stage's far corners (about 5.8 m away)
    return s;
}

}  // namespace bounce
