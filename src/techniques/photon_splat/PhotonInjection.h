#pragma once
// The CPU half of photon splatting (seed 004, "photon splatting with orthographic bundles", §3.2,
// §3.2.1, §3.3, §4.2, §4.3): photon injection by shooting from the lights through the ray-casting
// service, the optional 3D stratification of the photons, and the placement of each photon's
// orthographic bundle (a ray along its direction to the first hit, then a step back). GL-free: the
// GPU half (depth maps, splatting, normalisation) is PhotonSplatTechnique; the unit tests use this
// directly.
#include "reference/RayCaster.h"
#include "scene/Scene.h"

#include <cstdint>
#include <vector>

namespace bounce::photonsplat {

// One photon: an indirect light source (Table 1: position, colour, direction = 36 bytes).
struct Photon {
    glm::vec3 position{0.0f};   // world, metres: where it was stored (a diffuse hit)
    glm::vec3 power{0.0f};      // W per channel: the light's flux share times the albedo(s) of its hits
    glm::vec3 direction{0.0f};  // unit: cosine-distributed in the hemisphere of the surface normal
    glm::vec3 normal{0.0f};     // unit geometric normal at the hit, on the side the light came from
};
static_assert(sizeof(Photon) == 48);  // Table 1's 36 B plus the surface normal the bundles' emitter plane needs

struct InjectionSettings {
    uint32_t photons = 1024;  // photons shot from the lights (split over them by flux)
    uint32_t bounces = 1;     // photons are stored at the first `bounces` diffuse hits
    uint64_t seed = 0;
};

// Shoots `photons` photons from the scene's lights at time t (point: uniform sphere; spot: uniform in
// the cone, power weighted by the falloff; directional: the rectangle across the light that holds the
// scene's box; area: uniform points, cosine directions) and stores one photon at each of the first `bounces` diffuse hits,
// with power = emitted share x the albedo of every surface it reflected from (the photon then leaves
// in a cosine-distributed direction about the normal). Light that leaves the scene stores nothing.
// Deterministic for a seed. Lights with no flux are skipped; no lights give no photons.
void injectPhotons(const Scene& scene, float time, const RayCaster& caster, const InjectionSettings& settings, std::vector<Photon>& out);
inline std::vector<Photon> injectPhotons(const Scene& scene, float time, const RayCaster& caster, const InjectionSettings& settings) {
    std::vector<Photon> out;
    injectPhotons(scene, time, caster, settings, out);
    return out;
}

// §3.2.1 / §4.2: a grid of `gridSize`^3 cells over [lo, hi]; photons are binned by position; the grid
// is walked in 2x2x2 blocks: a block with any cell holding fewer than `threshold` photons (an empty
// cell too: it holds 0, as §4.2 words the rule) becomes one photon (power = the block's summed
// power, position/direction/normal of one photon chosen at random among the block's), otherwise
// every cell becomes one photon (its summed power, a random representative). Power is conserved
// exactly; the count is at most the number of cells. Photons outside the grid are kept as they are.
// The grid is held as one sorted 16-byte entry per photon, not as dense cells.
struct StratifyStats {
    size_t inputPhotons = 0, outputPhotons = 0, mergedBlocks = 0;
    size_t gridBytes = 0;  // bytes the grid's entries were allocated
};
std::vector<Photon> stratify(const std::vector<Photon>& photons, glm::vec3 lo, glm::vec3 hi, int gridSize, int threshold,
                             uint64_t seed, StratifyStats* stats = nullptr);

// An orthographic bundle (§3.3, Fig. 4): the photon's ray hits the scene at distance d; the bundle's
// frustum starts at C = P + (d - b) w and looks along w (its volume: BundleVolume.h).
struct Bundle {
    glm::vec3 origin{0.0f};     // C
    glm::vec3 direction{0.0f};  // w
    glm::vec3 right{0.0f}, up{0.0f};  // unit axes of the frustum's cross-section
    glm::vec3 power{0.0f};      // the photon's power, W
    float hitDistance = 0.0f;   // d
    glm::vec3 hitNormal{0.0f};  // unit geometric normal at the hit, on the side the ray arrived from
    uint32_t photon = 0;        // index of its photon in placeBundles' input
    bool escaped = false;       // the ray hit nothing: d is where it leaves the scene's box, hitNormal = -w
};
struct BundleSettings {
    float stepBack = 0.05f;  // b, metres (at most the hit distance d: C never lies behind P; infinity = d)
    float maxDistance = 1e30f;
    // Photons whose ray hits nothing still get a bundle (escaped) when the box [lo, hi] is not empty:
    // the rays of its cross-section beside its axis may hit the scene. Otherwise they give none.
    glm::vec3 lo{0.0f}, hi{-1.0f};
};
// The out-parameter forms refill `out` (and the ray scratch) in place: a renderer calling them every
// frame keeps their allocations instead of freeing and taking megabytes each frame.
struct BundleScratch {
    std::vector<CastRay> rays;
    std::vector<std::optional<RayHit>> hits;
};
void placeBundles(const std::vector<Photon>& photons, const RayCaster& caster, const BundleSettings& settings, std::vector<Bundle>& out,
                  BundleScratch& scratch);
inline std::vector<Bundle> placeBundles(const std::vector<Photon>& photons, const RayCaster& caster, const BundleSettings& settings) {
    std::vector<Bundle> out;
    BundleScratch scratch;
    placeBundles(photons, caster, settings, out, scratch);
    return out;
}

// Any unit vectors completing w to a right-handed frame (right x up = w).
void bundleAxes(glm::vec3 w, glm::vec3& right, glm::vec3& up);

}  // namespace bounce::photonsplat
