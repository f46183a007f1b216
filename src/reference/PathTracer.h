#pragma once
// bounce's ground truth: a CPU path tracer (Embree 3 + TBB) over the same Scene the GPU techniques
// render. See docs/reference.md for the light-transport scopes, the sampling, the determinism
// guarantees and the noise estimate.
//
// Unidirectional path tracing with next-event estimation. Emitting surfaces (rectangular area
// lights, triangles of emissive materials) are reached both by light sampling and by BSDF sampling,
// combined by multiple importance sampling with the power heuristic; point, spot and directional
// lights are delta lights, reached by light sampling only. Paths end by Russian roulette, at the
// reflection limit of the chosen scope, on a miss (no environment light), or on an absorbing
// surface: the back of a one-sided surface (seen by a reflected ray; the camera sees through it, as
// the rasteriser culls it), or the emitting side of an area light, an opaque emitter that reflects
// nothing. From behind, an area light is not there at all.
//
// Sixteen paths run side by side: each step traces all their rays as one Embree packet, then
// shades the hits on untextured Lambertian surfaces with the SIMD kernel of LambertKernel.h
// and the others with scatter(); the kernel's results are bit-identical to scatter()'s.
#include "core/Error.h"
#include "core/Image.h"
#include "reference/CameraRays.h"
#include "reference/EmbreeScene.h"
#include "reference/LambertKernel.h"
#include "reference/LightSampler.h"
#include "reference/Rng.h"
#include "reference/TextureLookup.h"
#include "scene/Scene.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace bounce {

struct PathTracerSettings {
    int width = 512;   // pixels
    int height = 512;  // pixels
    uint32_t samplesPerPixel = 64;
    // Indirect bounces K: a path reflects at most K+1 times (direct light is one reflection).
    // kUnbounded: Russian roulette ends paths (with a safety cap of 1024 reflections).
    int bounces = kUnbounded;
    bool indirectOnly = false;  // keep only light that reflected at least twice (full minus direct)
    bool diffuseOnly = false;   // BRDF = Lambert lobe alone at every vertex after the first
    uint64_t seed = 0;
    // 0: no limit. Otherwise the image holds the passes that completed within the limit: a pass
    // still running at the deadline is abandoned (the first pass always completes).
    double timeLimitSeconds = 0.0;
    int threads = 0;                // 0: every hardware thread
    uint32_t frame = 0;             // render the scene at time scene.timeOfFrame(frame)
    // Shade untextured Lambertian hits lane-parallel (SIMD). The image is bit-identical
    // either way; false keeps every lane on the scalar code (tests compare the two).
    bool vectorized = true;
    // Diagnostic (docs/techniques/vct.md "The six cones' own bias"): when not empty, the first
    // reflection draws its direction from these cones instead of the cosine lobe (cone k with
    // probability weight_k / sum of weights, uniformly within it) and keeps the weight albedo, so the
    // image is the cone quadrature rho/pi sum_k W_k mean_k(L) of the exact incident radiance: what a
    // cone tracer with this cone set gives without any voxel error (sum W_k = pi: exact in a uniform
    // field). Directions are in the vct tracer's frame: normal +Y, x = normalize(cross(helper, n)),
    // z = cross(x, n), helper +Y unless |n.y| >= 0.99, then +X (trace.frag). Lambertian hits only.
    struct QuadratureCone {
        glm::vec3 direction{0.0f, 1.0f, 0.0f};  // unit, normal frame
        float halfAngle = 0.0f;                  // radians
        float weight = 0.0f;                     // W_k
    };
    std::vector<QuadratureCone> firstReflectionCones;

    static constexpr int kUnbounded = -1;
};

struct RenderProgress {
    uint32_t samplesDone = 0;    // per pixel, complete passes only
    uint32_t samplesTarget = 0;  // settings.samplesPerPixel
    double elapsedSeconds = 0.0;
};
// Called after every pass, on the calling thread.
using ProgressCallback = std::function<void(const RenderProgress&)>;

// How much noise is left, from per-pixel sums of the luminance Y and Y^2 over the n samples.
struct NoiseEstimate {
    // Mean over pixels of sem(Y)/mean(Y), sem = sqrt(sampleVariance / n); pixels with mean 0 are skipped.
    double meanPixelRelativeError = 0.0;
    // Standard error of the whole image's mean luminance, relative to that mean.
    double imageRelativeError = 0.0;
    uint64_t pixelsMeasured = 0;  // pixels with non-zero mean that entered the first figure
};

struct PathTracerResult {
    Image radiance;                   // linear RGB, W/(m^2 sr)
    // Per pixel and channel, the estimated variance of `radiance` (the sample variance over the n samples,
    // divided by n; 0 with one sample), (W/(m^2 sr))^2: what the noise floors of docs/metrics.md read.
    Image variance;
    uint32_t samplesPerPixel = 0;     // reached (less than asked when the time limit stopped it)
    bool stoppedByTimeLimit = false;
    double buildSeconds = 0.0;        // BVH and light list
    double renderSeconds = 0.0;       // tracing only, including an abandoned pass
    uint64_t paths = 0;               // camera paths = pixels * samplesPerPixel
    uint64_t rays = 0;                // rays given to Embree for the kept passes: camera, continuation, shadow
    uint64_t shadowRays = 0;
    uint64_t invalidSamples = 0;      // non-finite samples dropped (0 unless there is a bug)
    NoiseEstimate noise;

    double pathsPerSecond() const { return renderSeconds > 0.0 ? static_cast<double>(paths) / renderSeconds : 0.0; }
    double raysPerSecond() const { return renderSeconds > 0.0 ? static_cast<double>(rays) / renderSeconds : 0.0; }
};

class PathTracer {
public:
    // Checks the settings and the scene (a light source must exist, textures must be finite) and
    // builds the BVH and the light list at the frame's time. `scene` must outlive the tracer (its
    // materials and textures are read while rendering).
    static Expected<PathTracer> create(const Scene& scene, const PathTracerSettings& settings);

    PathTracerResult render(const ProgressCallback& progress = {}) const;

    const PathTracerSettings& settings() const noexcept { return m_settings; }
    float time() const noexcept { return m_time; }

    // Per Embree geometry, what shading needs, gathered once so the inner loop does no lookups.
    struct Shading {
        const Material* material = nullptr;  // null for area lights
        const Image* texture = nullptr;      // base-colour texture, or null
        glm::vec3 emitted{0.0f};             // radiance of the front side (both sides if twoSided)
        // Textured area lights: the radiance seen at a hit is emitted times this texture's texel there.
        const EmitterTexture* emitterTexture = nullptr;
        // Materials with an emission texture: emitted times its bilinear texel at the hit's uv.
        const Image* emissionTexture = nullptr;
        glm::vec3 diffuseAlbedo{0.0f};       // baseColor * (1 - metallic), before the texture
        const Image* metallicRoughnessTexture = nullptr;  // G scales roughness, B metallic (glTF), or null
        bool normalMapped = false;           // EmbreeScene::surface perturbs the shading normal
        bool emissive = false;
        bool twoSided = false;
        bool absorber = false;    // area-light rectangles: emit, never reflect (hit from the front only,
                                  // or from either side when two-sided)
        bool lambertian = false;  // no GGX lobe whatever the texture (specularF0 = 0, metallic = 0)
    };
    // The shading of every geometry of `embree` (built from `scene`, lights evaluated at `time`, area
    // lights' textures from `lights`): shared by the path tracer and the photon mapper so that both read
    // the scene the same way.
    static std::vector<Shading> gatherShading(const Scene& scene, const EmbreeScene& embree,
                                              const LightSampler& lights, float time);
    // The radiance a ray sees on an emitting geometry at Embree barycentrics (u, v) of triangle primId
    // (surface uv `uv`): the shading's emitted radiance, times the texel there on a textured area light
    // or a material with an emission texture.
    static glm::vec3 emittedAt(const Shading& shading, uint32_t primId, float u, float v, glm::vec2 uv) noexcept {
        if (shading.emissionTexture) return shading.emitted * lookupBilinearRepeat(*shading.emissionTexture, uv);
        if (!shading.emitterTexture) return shading.emitted;
        const EmitterTexture& t = *shading.emitterTexture;
        return shading.emitted * t.texel(t.texelAt(areaLightUv(primId, u, v)));
    }

private:
    static constexpr int kPacketSize = lambert::kLanes;  // paths traced side by side
    struct Counters;
    struct PixelSums;
    // One camera path in flight.
    struct PathState {
        Rng rng;
        glm::vec3 radiance{0.0f};
        glm::vec3 throughput{1.0f};
        glm::vec3 origin{0.0f};     // of the ray to trace next
        glm::vec3 direction{0.0f};  // unit
        float tMax = 0.0f;
        int reflections = 0;   // scattering events so far
        float bsdfPdf = 0.0f;  // solid-angle pdf of the BRDF sample that chose `direction`
        int culledCrossings = 0;
    };
    struct HitRecord {
        uint32_t geomId;  // RTC_INVALID_GEOMETRY_ID for a miss
        uint32_t primId;
        float u, v, t;
    };
    // The next-event estimation ray of one reflection and what it adds if it is not blocked.
    struct ShadowRay {
        bool active = false;
        glm::vec3 origin, direction;  // tMax in units of direction's length
        float tMax;
        glm::vec3 contribution;
    };
    enum class Step { Continue, Retrace, Stop };

    PathTracer(const Scene& scene, const PathTracerSettings& settings, EmbreeScene embree);
    void renderTile(int x0, int y0, int x1, int y1, uint32_t s0, uint32_t s1, PixelSums* sums,
                    Counters& counters) const;
    // Handles a hit of the path's current ray: emission, the reflection's shadow ray (left in
    // `shadow` for the caller to trace), and the next direction. Retrace: the camera ray crossed a
    // culled back face and must be traced again from there.
    Step scatter(PathState& path, const HitRecord& hit, ShadowRay& shadow) const;
    // What loadKernelLane() reads of a geometry: its arrays (owned by m_embree) and its shading.
    struct KernelGeometry {
        const glm::uvec3* triangles = nullptr;
        const glm::vec3* positions = nullptr;
        const glm::vec3* faceNormals = nullptr;
        const glm::vec3* normals = nullptr;  // vertex normals, or null for a flat mesh
        glm::vec3 albedo{0.0f}, emitted{0.0f};
        const LightSampler::Entry* emitter = nullptr;  // its (first) light entry if it emits
        bool emitterPerTriangle = false;                // entries emitter + primId
        bool shades = false;             // the kernel shades its hits: untextured Lambert, or an untextured area light
        bool shadesDiffuseOnly = false;  // ... after the first vertex, under --diffuse-only
        bool emissive = false, twoSided = false, absorber = false;
    };

    // Path state of one lane, in and out of the structure-of-arrays form.
    static PathState laneState(const lambert::Lanes& lanes, int i);
    static void setLaneState(lambert::Lanes& lanes, int i, const PathState& path);
    // Loads lane i's hit for the vectorised kernel if it is one the kernel shades.
    bool loadKernelLane(lambert::Lanes& lanes, int i) const;
    // One reflection of every active lane with a hit: the kernel for the lanes it shades, scatter()
    // for the others. Leaves stop, and the shadow ray, in the lanes.
    void shadeLanes(lambert::Lanes& lanes, const int* active) const;


    PathTracerSettings m_settings;
    float m_time;
    EmbreeScene m_embree;
    LightSampler m_lights;
    CameraRays m_camera;
    std::vector<Shading> m_shading;
    int m_maxReflections;
    std::vector<KernelGeometry> m_kernelGeometries;  // per Embree geometry
    double m_buildSeconds = 0.0;
};

}  // namespace bounce
