#pragma once
// Photon mapping (Jensen 1996, "Global Illumination using Photon Maps"; Jensen 2001, "Realistic
// Image Synthesis Using Photon Mapping"): the CPU ground truth of photon splatting (issue 13,
// /work/shared/specs/photon-splatting-orthographic-bundles.md §2.8). GL-free, on the same Embree
// scene, light list and BRDF as the path tracer, so both mean the same thing by every quantity.
//
// Pass 1, photon tracing: N photons leave the scene's light sources (the path tracer's light list:
// point, spot, directional and rectangular area lights and every emissive triangle), each light
// chosen with probability pmf proportional to its flux luminance, so every photon starts with the
// power Phi_light / (pmf N). Photons bounce off surfaces by the BRDF's sampling and end by Russian
// roulette on the reflectance of each bounce (or at the scope's reflection limit). A photon is
// stored at a hit when the light it carries has reflected j times before arriving, with
//     j >= 1 (indirectOnly) or j >= 0 (full scope), and j <= K (bounces K; unbounded: no limit),
// so that reflecting it once more at a camera hit gives exactly the camera-path components
// k = j + 1 that `bounce reference --bounces K [--indirect-only]` counts (docs/reference.md,
// "Light-transport scopes"). docs/techniques/photon-map.md explains the choice.
// Pass 2, a kd-tree (nanoflann) over the stored photons' positions.
// Pass 3, the radiance estimate at camera-ray hits (box-filtered, jittered samples per pixel):
//     L(x, wo) = Le(x, wo) [full scope only] + sum_{i < k} f(x, wo, wi_i) Phi_i / (pi r_k^2)
// over the k - 1 nearest accepted photons inside the distance r_k of the k-th (the unbiased
// k-nearest-neighbour density estimate; for Lambert f = rho / pi). Photons are accepted only when
// they lie on the query's tangent plane and side: their surface normal within 60 degrees of the
// query's, their incoming direction in the query's hemisphere, and their offset from the tangent
// plane at most a tenth of their distance (the thesis's "tangent-plane" and "90 degree" rejections).
//
// Deterministic: photon i and pixel sample (p, s) draw from their own random streams, photons are
// stored in emission order, so the image depends on the seed alone, never on the thread count.
#include "core/Error.h"
#include "core/Image.h"
#include "scene/Scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace bounce {

struct PhotonMapSettings {
    int width = 512;   // pixels
    int height = 512;  // pixels
    uint64_t photons = 1'000'000;  // emitted (stored photons are fewer or more: one per stored hit)
    int k = 100;                   // nearest photons of the estimate (k - 1 are summed), >= 2
    // Indirect bounces K as in PathTracerSettings: camera paths reflect at most K + 1 times, so
    // stored photons have reflected at most K times. kUnbounded: Russian roulette alone.
    int bounces = kUnbounded;
    bool indirectOnly = false;  // light that reflected at least twice (no emission, no direct light)
    bool diffuseOnly = false;   // photons bounce by the Lambert lobe alone (the gather keeps the full BRDF)
    float maxRadius = 0.0f;     // gather radius cap in metres; 0: none
    uint32_t samplesPerPixel = 4;  // jittered camera rays per pixel (a box filter, as the reference)
    uint64_t seed = 0;
    // 0: no limit. Otherwise photon tracing stops after the last pass of kPhotonsPerPass photons
    // that started within the limit (the first always runs); the gather always completes.
    double timeLimitSeconds = 0.0;
    int threads = 0;         // 0: every hardware thread
    uint32_t frame = 0;      // the scene at time scene.timeOfFrame(frame)

    static constexpr int kUnbounded = -1;
    static constexpr uint64_t kPhotonsPerPass = 1u << 18;
};

// One stored photon: 48 bytes (the thesis's 36 plus the surface normal the rejection needs).
struct Photon {
    glm::vec3 position{0.0f};
    glm::vec3 power{0.0f};     // W, already divided by the number of photons emitted
    glm::vec3 incoming{0.0f};  // unit, from the hit towards where the photon came from
    glm::vec3 normal{0.0f};    // unit geometric normal of the side it arrived on
};

struct PhotonGatherParams {
    int k = 100;
    float maxRadius = 0.0f;  // 0: none
    // The tangent-plane rejection; false keeps every neighbour (for tests of the rejection itself).
    bool rejectOffPlane = true;
};

struct PhotonGather {
    float radius = 0.0f;        // r_k (or the cap, or the last candidate's distance)
    uint32_t candidates = 0;    // neighbours examined
    std::vector<uint32_t> accepted;  // photon indices summed by the estimate
};

// The photon map: photons and a kd-tree over their positions.
class PhotonMap {
public:
    explicit PhotonMap(std::vector<Photon> photons);
    ~PhotonMap();
    PhotonMap(PhotonMap&&) noexcept;
    PhotonMap& operator=(PhotonMap&&) noexcept;

    std::span<const Photon> photons() const noexcept { return m_photons; }
    // Photon array plus tree nodes and index.
    size_t memoryBytes() const noexcept;

    // The accepted neighbours of the estimate at x (normal n of the side seen, unit) and its radius.
    // `out` is reused between calls to avoid allocations. Thread-safe.
    void gather(glm::vec3 x, glm::vec3 n, const PhotonGatherParams& params, PhotonGather& out,
                std::vector<uint32_t>& indexScratch, std::vector<float>& distScratch) const;

    // sum_{accepted} Phi_i / (pi r^2): the irradiance estimate, W/m^2 (Lambert: L = rho/pi * this).
    glm::vec3 irradiance(glm::vec3 x, glm::vec3 n, const PhotonGatherParams& params) const;

private:
    struct Tree;
    std::vector<Photon> m_photons;
    std::unique_ptr<Tree> m_tree;
};

struct PhotonMapProgress {
    enum class Phase { Tracing, Gathering };
    Phase phase = Phase::Tracing;
    uint64_t done = 0;    // photons emitted, or image rows gathered
    uint64_t target = 0;
    double elapsedSeconds = 0.0;
};
using PhotonMapProgressCallback = std::function<void(const PhotonMapProgress&)>;

struct PhotonMapResult {
    Image radiance;  // linear RGB, W/(m^2 sr)
    uint64_t photonsEmitted = 0;  // reached (less than asked when the time limit stopped tracing)
    uint64_t photonsStored = 0;
    bool stoppedByTimeLimit = false;
    double buildSeconds = 0.0;   // BVH and light list
    double traceSeconds = 0.0;   // photon tracing
    double treeSeconds = 0.0;    // kd-tree build
    double gatherSeconds = 0.0;  // camera rays and estimates
    uint64_t photonRays = 0;     // rays traced for photons
    uint64_t cameraRays = 0;
    uint64_t mapBytes = 0;       // PhotonMap::memoryBytes()
    double meanGatherRadius = 0.0;  // metres, over gathers
    uint64_t gathers = 0;
    uint64_t shortGathers = 0;   // gathers that found fewer than k accepted photons (cap or candidates)
    uint64_t invalidSamples = 0; // non-finite estimates dropped (0 unless there is a bug)
    double renderSeconds() const { return traceSeconds + treeSeconds + gatherSeconds; }
};

class PhotonMapper {
public:
    // Checks the settings and the scene (a light source must exist) and builds the BVH and the
    // light list at the frame's time. `scene` must outlive the mapper.
    static Expected<PhotonMapper> create(const Scene& scene, const PhotonMapSettings& settings);
    ~PhotonMapper();
    PhotonMapper(PhotonMapper&&) noexcept;
    PhotonMapper& operator=(PhotonMapper&&) noexcept;

    // Traces photons [first, first + count) of the seed's sequence and returns the photons they
    // store, in order, with power Phi / (pmf * powerDivisor). rays, if given, counts the rays traced.
    std::vector<Photon> tracePhotons(uint64_t first, uint64_t count, double powerDivisor,
                                     uint64_t* rays = nullptr) const;

    // All three passes.
    PhotonMapResult render(const PhotonMapProgressCallback& progress = {}) const;
    // Pass 3 alone, on a given map (tests).
    Image renderImage(const PhotonMap& map, PhotonMapResult* stats = nullptr) const;

    const PhotonMapSettings& settings() const noexcept;

private:
    struct Impl;
    explicit PhotonMapper(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

}  // namespace bounce
