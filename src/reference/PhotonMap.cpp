#include "reference/PhotonMap.h"

#include "core/ImageIo.h"
#include "reference/Bsdf.h"
#include "scene/AreaTexture.h"
#include "reference/CameraRays.h"
#include "reference/EmbreeScene.h"
#include "reference/LightSampler.h"
#include "reference/PathTracer.h"
#include "reference/Rng.h"
#include "reference/Sampling.h"
#include "reference/TextureLookup.h"

#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

namespace bounce {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The path tracer's safety cap on reflections (PathTracer.cpp): photons stop there too.
constexpr int kMaxUnboundedReflections = 1024;
// As in the path tracer: a camera ray crosses at most this many culled back faces.
constexpr int kMaxCulledCrossings = 64;
// Photons traced by one task: small enough to balance two cores, large enough to amortise the task.
constexpr uint64_t kPhotonsPerChunk = 4096;
// Random-stream salts, so that photon i and pixel i never share a stream.
constexpr uint64_t kPhotonStream = 0x70686f746f6e0001ull;
constexpr uint64_t kGatherStream = 0x6761746865720002ull;
// Tangent-plane rejection: a neighbour counts when its surface normal is within 60 degrees of the
// query's (cos 60 = 0.5: curved tessellations such as atrium's columns keep their neighbours, the
// other side of a wall and a perpendicular wall are rejected), and when its offset from the query's
// tangent plane is at most a tenth of its distance (about 6 degrees: the top of a box beside a floor
// point is rejected; a surface of curvature radius R keeps neighbours out to 0.2 R).
constexpr float kNormalCos = 0.5f;
constexpr float kPlaneSlope = 0.1f;
// Absolute slack of the plane test: float rounding of positions a few metres from the origin.
constexpr float kPlaneSlack = 1e-5f;
// The kNN search asks for 2k candidates and doubles up to this many times k when rejections leave
// fewer than k accepted; past that, the estimate uses what it has inside the last candidate.
constexpr int kMaxCandidateFactor = 16;

using Shading = PathTracer::Shading;

// Flux (W, per channel) of one light-list entry: what it emits in total (a textured rectangle: as if
// every texel were 1; tracePhoton weighs each photon by its texel and the texel's pdf).
glm::vec3 entryFlux(const LightSampler::Entry& e, float sceneRadius) {
    switch (e.kind) {
        case LightSampler::Kind::Point: return 4.0f * kPi * e.emitted;
        case LightSampler::Kind::Spot: {
            const float c0 = std::max(0.0f, e.cosCutoff);  // cos(alpha) is clamped at 0 past 90 degrees
            const float n1 = e.exponent + 1.0f;
            return e.emitted * (2.0f * kPi * (1.0f - std::pow(c0, n1)) / n1);
        }
        case LightSampler::Kind::Directional: return e.emitted * (kPi * sceneRadius * sceneRadius);
        case LightSampler::Kind::Area: return e.emitted * (kPi * e.area * (e.twoSided ? 2.0f : 1.0f));
        case LightSampler::Kind::Triangle: return e.emitted * (kPi * e.area * (e.twoSided ? 2.0f : 1.0f));
    }
    return glm::vec3(0.0f);
}

glm::vec3 uniformSphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// nanoflann's view of the photon array.
struct PhotonCloud {
    const std::vector<Photon>* photons;
    size_t kdtree_get_point_count() const { return photons->size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return (*photons)[i].position[static_cast<int>(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
        return false;
    }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PhotonCloud>, PhotonCloud, 3, uint32_t>;

}  // namespace

// ---------------------------------------------------------------------------------------------
// The map

struct PhotonMap::Tree {
    PhotonCloud cloud;
    KdTree index;
    explicit Tree(const std::vector<Photon>* photons)
        : cloud{photons}, index(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
};

PhotonMap::PhotonMap(std::vector<Photon> photons) : m_photons(std::move(photons)) {
    m_tree = std::make_unique<Tree>(&m_photons);
}
PhotonMap::~PhotonMap() = default;
// The tree points at m_photons, whose heap buffer moves with the vector: the pointer must follow.
PhotonMap::PhotonMap(PhotonMap&& other) noexcept : m_photons(std::move(other.m_photons)), m_tree(std::move(other.m_tree)) {
    if (m_tree) m_tree->cloud.photons = &m_photons;
}
PhotonMap& PhotonMap::operator=(PhotonMap&& other) noexcept {
    m_photons = std::move(other.m_photons);
    m_tree = std::move(other.m_tree);
    if (m_tree) m_tree->cloud.photons = &m_photons;
    return *this;
}

size_t PhotonMap::memoryBytes() const noexcept {
    return m_photons.size() * sizeof(Photon) + (m_tree ? m_tree->index.usedMemory(m_tree->index) : 0);
}

void PhotonMap::gather(glm::vec3 x, glm::vec3 n, const PhotonGatherParams& params, PhotonGather& out,
                       std::vector<uint32_t>& indices, std::vector<float>& dist2) const {
    out.accepted.clear();
    out.radius = 0.0f;
    out.candidates = 0;
    const size_t total = m_photons.size();
    if (total == 0 || params.k < 2) return;
    const auto k = static_cast<size_t>(params.k);
    const float maxR2 = params.maxRadius > 0.0f ? params.maxRadius * params.maxRadius : std::numeric_limits<float>::infinity();
    const float query[3] = {x.x, x.y, x.z};
    size_t want = std::min(total, 2 * k);
    const size_t most = std::min(total, static_cast<size_t>(kMaxCandidateFactor) * k);
    for (;;) {
        indices.resize(want);
        dist2.resize(want);
        const size_t found = m_tree->index.knnSearch(query, static_cast<uint32_t>(want), indices.data(), dist2.data());
        out.accepted.clear();
        out.candidates = static_cast<uint32_t>(found);
        for (size_t i = 0; i < found; ++i) {
            if (dist2[i] > maxR2) {
                // Everything inside the cap has been seen: the estimate is over the cap's disc.
                out.radius = params.maxRadius;
                return;
            }
            const Photon& p = m_photons[indices[i]];
            if (params.rejectOffPlane) {
                const float d = std::sqrt(dist2[i]);
                const float offPlane = std::abs(glm::dot(p.position - x, n));
                if (glm::dot(p.normal, n) < kNormalCos || glm::dot(p.incoming, n) <= 0.0f ||
                    offPlane > kPlaneSlope * d + kPlaneSlack)
                    continue;
            }
            if (out.accepted.size() + 1 == k) {
                // The k-th accepted photon sets the radius and is not summed: (k-1)/(pi r_k^2) is the
                // unbiased nearest-neighbour density (Poisson points), k/(pi r_k^2) is k/(k-1) too high.
                out.radius = std::sqrt(dist2[i]);
                return;
            }
            out.accepted.push_back(indices[i]);
        }
        if (found < want || want >= most) {
            // Every photon within the last candidate's distance has been examined.
            if (found == total && params.maxRadius > 0.0f) {
                out.radius = params.maxRadius;  // the whole map lies inside the cap
            } else if (found > 0) {
                // The last candidate sets the radius and, like the k-th, is not summed.
                out.radius = std::sqrt(dist2[found - 1]);
                if (!out.accepted.empty() && out.accepted.back() == indices[found - 1]) out.accepted.pop_back();
            }
            return;
        }
        want = std::min(most, 2 * want);
    }
}

glm::vec3 PhotonMap::irradiance(glm::vec3 x, glm::vec3 n, const PhotonGatherParams& params) const {
    PhotonGather g;
    std::vector<uint32_t> indices;
    std::vector<float> dist2;
    gather(x, n, params, g, indices, dist2);
    if (!(g.radius > 0.0f)) return glm::vec3(0.0f);
    glm::dvec3 sum(0.0);
    for (uint32_t i : g.accepted) sum += glm::dvec3(m_photons[i].power);
    return glm::vec3(sum / (static_cast<double>(kPi) * g.radius * g.radius));
}

// ---------------------------------------------------------------------------------------------
// The mapper

struct PhotonMapper::Impl {
    const Scene* scene = nullptr;
    PhotonMapSettings settings;
    float time = 0.0f;
    EmbreeScene embree;
    LightSampler lights;
    CameraRays camera;
    std::vector<Shading> shading;
    glm::vec3 sceneCentre{0.0f};
    float sceneRadius = 0.0f;
    int maxStoreReflections = 0;  // photons are stored after at most this many reflections
    int minStoreReflections = 0;
    double buildSeconds = 0.0;

    Impl(const Scene& s, const PhotonMapSettings& st, EmbreeScene e)
        : scene(&s),
          settings(st),
          time(s.timeOfFrame(st.frame)),
          embree(std::move(e)),
          lights(s, embree),
          camera(s.camera.at(time), st.width, st.height) {
        glm::vec3 lo, hi;
        s.bounds(time, lo, hi);
        sceneCentre = 0.5f * (lo + hi);
        sceneRadius = 0.5f * glm::length(hi - lo);  // as LightSampler's weight of directional lights
        maxStoreReflections = st.bounces == PhotonMapSettings::kUnbounded ? kMaxUnboundedReflections - 1 : st.bounces;
        minStoreReflections = st.indirectOnly ? 1 : 0;
        shading = PathTracer::gatherShading(s, embree, lights, time);
    }

    struct Hit {
        uint32_t geomId, primId;
        float u, v, t;
    };
    bool intersect(glm::vec3 origin, glm::vec3 direction, float tMax, Hit& hit) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh;
        setRay(rh.ray, origin, direction, 0.0f, tMax);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(embree.handle(), &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
        hit = {rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar};
        return true;
    }

    // Emits photon `index` and follows it, appending what it stores to `out`.
    void tracePhoton(uint64_t index, double powerDivisor, std::vector<Photon>& out, uint64_t& rays) const {
        Rng rng(settings.seed ^ kPhotonStream, index, 0);
        if (lights.empty()) return;  // every light is dark at this instant (hasDarkTexturedLight)
        const LightSampler::Entry& e = lights.choose(rng.next());
        if (!(e.pmf > 0.0f)) return;
        glm::vec3 power = glm::vec3(glm::dvec3(entryFlux(e, sceneRadius)) / (static_cast<double>(e.pmf) * powerDivisor));
        glm::vec3 origin, direction;
        float u1 = rng.next(), u2 = rng.next();
        const float u3 = rng.next(), u4 = rng.next();
        switch (e.kind) {
            case LightSampler::Kind::Point:
                origin = e.position;
                direction = uniformSphere(u1, u2);
                break;
            case LightSampler::Kind::Spot: {
                // cos(alpha) distributed as cos^n on [c0, 1]: every photon carries the same power.
                const float c0 = std::max(0.0f, e.cosCutoff);
                const float n1 = e.exponent + 1.0f;
                const float c0n = std::pow(c0, n1);
                const float cosA = std::min(1.0f, std::pow(c0n + u1 * (1.0f - c0n), 1.0f / n1));
                const float sinA = std::sqrt(std::max(0.0f, 1.0f - cosA * cosA));
                const float phi = 2.0f * kPi * u2;
                origin = e.position;
                direction = Frame(e.normal).toWorld({sinA * std::cos(phi), sinA * std::sin(phi), cosA});
                if (!(cosA > e.cosCutoff)) return;  // the reference's strict cutoff test
                break;
            }
            case LightSampler::Kind::Directional: {
                // A disc of the bounding sphere's radius, perpendicular to the light, outside the sphere.
                const Frame f(e.normal);
                const float r = sceneRadius * std::sqrt(u1);
                const float phi = 2.0f * kPi * u2;
                origin = sceneCentre - 2.0f * sceneRadius * e.normal + r * std::cos(phi) * f.t + r * std::sin(phi) * f.b;
                direction = e.normal;
                break;
            }
            case LightSampler::Kind::Area:
            case LightSampler::Kind::Triangle: {
                glm::vec3 y;
                if (e.kind == LightSampler::Kind::Area) {
                    // A textured rectangle: the point follows the texels' emitted luminance, and the
                    // photon carries flux (texel radiance) / (its density): power *= texel / pdf.
                    if (e.texture) {
                        const EmitterTexture::Sample ts = e.texture->sample(u1, u2);
                        u1 = ts.uv.x;
                        u2 = ts.uv.y;
                        power *= e.texture->texel(ts.texel) / e.texture->pdf(ts.texel);
                    }
                    y = e.position + u1 * e.edge1 + u2 * e.edge2;
                } else {
                    const glm::vec2 b = uniformTriangle(u1, u2);
                    y = e.position + b.x * e.edge1 + b.y * e.edge2;
                    // An emission texture: uniform points by area, each carrying its texel's radiance.
                    if (e.emissionTexture) power *= lookupBilinearRepeat(*e.emissionTexture, e.uv0 + b.x * e.uv1 + b.y * e.uv2);
                }
                glm::vec3 n = e.normal;
                if (e.twoSided && rng.next() < 0.5f) n = -n;
                origin = offsetRayOrigin(y, n);
                direction = Frame(n).toWorld(cosineHemisphere(u3, u4));
                break;
            }
        }

        for (int reflections = 0;; ++reflections) {
            Hit hit;
            ++rays;
            if (!intersect(origin, direction, std::numeric_limits<float>::infinity(), hit)) return;
            const Shading& sh = shading[hit.geomId];
            const SurfacePoint sp = embree.surface(hit.geomId, hit.primId, hit.u, hit.v);
            const bool front = glm::dot(direction, sp.geometricNormal) < 0.0f;
            // Area lights and the backs of one-sided surfaces absorb (docs/reference.md).
            if (sh.absorber || !(front || sh.twoSided)) return;
            const glm::vec3 ng = front ? sp.geometricNormal : -sp.geometricNormal;
            if (reflections >= minStoreReflections) out.push_back({sp.position, power, -direction, ng});
            if (reflections >= maxStoreReflections) return;

            glm::vec3 ns = front ? sp.shadingNormal : -sp.shadingNormal;
            if (glm::dot(ns, direction) >= 0.0f) ns = ng;
            const Frame frame(ns);
            const glm::vec3 texel = sh.texture ? lookupBilinearRepeat(*sh.texture, sp.uv) : glm::vec3(1.0f);
            glm::vec3 weight, wi;
            if (sh.lambertian || settings.diffuseOnly) {
                wi = frame.toWorld(cosineHemisphere(rng));
                weight = sh.diffuseAlbedo * texel;
            } else {
                const Bsdf bsdf(*sh.material, sh.material->baseColor * texel, false);
                const float uLobe = rng.next(), v1 = rng.next(), v2 = rng.next();
                Bsdf::Sample bs;
                if (!bsdf.sample(frame.toLocal(-direction), uLobe, v1, v2, bs)) return;
                wi = frame.toWorld(bs.wi);
                weight = bs.weight;
            }
            if (glm::dot(wi, ng) <= 0.0f) return;
            // Russian roulette on the bounce's reflectance: survivors keep their brightest channel.
            const float survive = std::min(1.0f, maxComponent(weight));
            if (!(rng.next() < survive)) return;
            power *= weight / survive;
            origin = offsetRayOrigin(sp.position, ng);
            direction = wi;
        }
    }

    // One pixel sample's radiance.
    glm::vec3 shadePixelSample(const PhotonMap& map, int px, int py, uint32_t sample, PhotonGather& g,
                               std::vector<uint32_t>& indices, std::vector<float>& dist2, uint64_t& rays,
                               double& radiusSum, uint64_t& gathers, uint64_t& shortGathers) const {
        const uint64_t pixel = static_cast<uint64_t>(py) * static_cast<uint64_t>(settings.width) + static_cast<uint64_t>(px);
        Rng rng(settings.seed ^ kGatherStream, pixel, sample);
        const float jx = rng.next(), jy = rng.next();
        const CameraRay ray = camera.generate(static_cast<float>(px) + jx, static_cast<float>(py) + jy);
        glm::vec3 origin = ray.origin;
        float tMax = ray.tMax;
        for (int crossings = 0; crossings <= kMaxCulledCrossings; ++crossings) {
            Hit hit;
            ++rays;
            if (!intersect(origin, ray.direction, tMax, hit)) return glm::vec3(0.0f);
            const Shading& sh = shading[hit.geomId];
            const SurfacePoint sp = embree.surface(hit.geomId, hit.primId, hit.u, hit.v);
            const bool front = glm::dot(ray.direction, sp.geometricNormal) < 0.0f;
            if (!front && !sh.twoSided) {
                // The rasteriser culls back faces: the camera sees through them.
                tMax -= hit.t;
                origin = offsetRayOrigin(sp.position, sp.geometricNormal);
                continue;
            }
            glm::vec3 radiance(0.0f);
            if (sh.emissive && !settings.indirectOnly) radiance += PathTracer::emittedAt(sh, hit.primId, hit.u, hit.v, sp.uv);  // k = 0
            if (sh.absorber) return radiance;
            const glm::vec3 ng = front ? sp.geometricNormal : -sp.geometricNormal;
            map.gather(sp.position, ng, PhotonGatherParams{settings.k, settings.maxRadius, true}, g, indices, dist2);
            ++gathers;
            radiusSum += g.radius;
            if (g.accepted.size() + 1 < static_cast<size_t>(settings.k)) ++shortGathers;
            if (!(g.radius > 0.0f)) return radiance;
            const glm::vec3 texel = sh.texture ? lookupBilinearRepeat(*sh.texture, sp.uv) : glm::vec3(1.0f);
            const auto photons = map.photons();
            glm::vec3 sum(0.0f);
            if (sh.lambertian) {
                glm::dvec3 flux(0.0);
                for (uint32_t i : g.accepted) flux += glm::dvec3(photons[i].power);
                sum = sh.diffuseAlbedo * texel * kInvPi * glm::vec3(flux);
            } else {
                glm::vec3 ns = front ? sp.shadingNormal : -sp.shadingNormal;
                if (glm::dot(ns, ray.direction) >= 0.0f) ns = ng;
                const Frame frame(ns);
                const Bsdf bsdf(*sh.material, sh.material->baseColor * texel, false);
                const glm::vec3 wo = frame.toLocal(-ray.direction);
                for (uint32_t i : g.accepted) sum += bsdf.eval(wo, frame.toLocal(photons[i].incoming)) * photons[i].power;
            }
            return radiance + sum / (kPi * g.radius * g.radius);
        }
        return glm::vec3(0.0f);
    }
};

Expected<PhotonMapper> PhotonMapper::create(const Scene& scene, const PhotonMapSettings& settings) {
    if (settings.width <= 0 || settings.height <= 0)
        return makeError("image size {}x{}: width and height must be positive", settings.width, settings.height);
    if (settings.photons == 0) return makeError("photons 0: at least one photon is needed");
    if (settings.photons > (uint64_t{1} << 32))
        return makeError("photons {}: at most 2^32 (the kd-tree's indices are 32-bit)", settings.photons);
    if (settings.k < 2) return makeError("k {}: the estimate needs at least 2 nearest photons", settings.k);
    if (settings.samplesPerPixel == 0) return makeError("spp 0: at least one camera ray per pixel is needed");
    if (settings.bounces < PhotonMapSettings::kUnbounded || settings.bounces >= kMaxUnboundedReflections)
        return makeError("bounces {}: must be between 0 and {} (or unbounded)", settings.bounces, kMaxUnboundedReflections - 1);
    if (!(settings.maxRadius >= 0.0f) || !std::isfinite(settings.maxRadius))
        return makeError("max radius {}: must be a finite number of metres >= 0 (0 = none)", settings.maxRadius);
    if (settings.threads < 0) return makeError("threads {}: must be 0 (all) or more", settings.threads);
    if (!(settings.timeLimitSeconds >= 0.0) || !std::isfinite(settings.timeLimitSeconds))
        return makeError("time limit {}: must be a finite number of seconds >= 0", settings.timeLimitSeconds);
    BOUNCE_TRY_VOID(checkTracedTextures(scene));
    EmbreeSceneOptions options;
    options.time = scene.timeOfFrame(settings.frame);
    options.filter = GeometryFilter::All;
    options.includeAreaLights = true;  // opaque emitters that absorb photons, as in the path tracer
    const Clock::time_point start = Clock::now();
    tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
    Expected<EmbreeScene> embree = makeError("unreachable");
    arena.execute([&] { embree = EmbreeScene::build(scene, options); });
    if (!embree) return embree.error();
    auto impl = std::make_unique<Impl>(scene, settings, std::move(embree).value());
    if (impl->lights.empty() && !impl->lights.hasDarkTexturedLight())
        return makeError("scene '{}': no light source (no light with non-zero power and no object with an emissive "
                         "material)",
                         scene.name);
    impl->buildSeconds = secondsSince(start);
    return PhotonMapper(std::move(impl));
}

PhotonMapper::PhotonMapper(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
PhotonMapper::~PhotonMapper() = default;
PhotonMapper::PhotonMapper(PhotonMapper&&) noexcept = default;
PhotonMapper& PhotonMapper::operator=(PhotonMapper&&) noexcept = default;
const PhotonMapSettings& PhotonMapper::settings() const noexcept { return m_impl->settings; }

std::vector<Photon> PhotonMapper::tracePhotons(uint64_t first, uint64_t count, double powerDivisor, uint64_t* rays) const {
    const uint64_t chunks = (count + kPhotonsPerChunk - 1) / kPhotonsPerChunk;
    std::vector<std::vector<Photon>> perChunk(chunks);
    std::vector<uint64_t> chunkRays(chunks, 0);
    tbb::task_arena arena(m_impl->settings.threads > 0 ? m_impl->settings.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<uint64_t>(0, chunks, 1), [&](const tbb::blocked_range<uint64_t>& r) {
            for (uint64_t c = r.begin(); c != r.end(); ++c) {
                const uint64_t begin = first + c * kPhotonsPerChunk;
                const uint64_t end = std::min(first + count, begin + kPhotonsPerChunk);
                std::vector<Photon>& out = perChunk[c];
                out.reserve(static_cast<size_t>(2 * (end - begin)));
                for (uint64_t i = begin; i < end; ++i) m_impl->tracePhoton(i, powerDivisor, out, chunkRays[c]);
            }
        });
    });
    size_t total = 0;
    for (const auto& v : perChunk) total += v.size();
    std::vector<Photon> photons;
    photons.reserve(total);
    for (const auto& v : perChunk) photons.insert(photons.end(), v.begin(), v.end());
    if (rays) {
        for (uint64_t r : chunkRays) *rays += r;
    }
    return photons;
}

Image PhotonMapper::renderImage(const PhotonMap& map, PhotonMapResult* stats) const {
    const PhotonMapSettings& s = m_impl->settings;
    Image image(s.width, s.height);
    std::atomic<uint64_t> rays{0}, gathers{0}, shortGathers{0}, invalid{0};
    std::atomic<double> radiusSum{0.0};
    tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, s.height, 1), [&](const tbb::blocked_range<int>& r) {
            PhotonGather g;
            std::vector<uint32_t> indices;
            std::vector<float> dist2;
            uint64_t localRays = 0, localGathers = 0, localShort = 0, localInvalid = 0;
            double localRadius = 0.0;
            for (int y = r.begin(); y != r.end(); ++y) {
                for (int x = 0; x < s.width; ++x) {
                    glm::dvec3 sum(0.0);
                    for (uint32_t sample = 0; sample < s.samplesPerPixel; ++sample) {
                        const glm::vec3 L = m_impl->shadePixelSample(map, x, y, sample, g, indices, dist2, localRays,
                                                                     localRadius, localGathers, localShort);
                        if (std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z)) {
                            sum += glm::dvec3(L);
                        } else {
                            ++localInvalid;
                        }
                    }
                    image.at(x, y) = glm::vec3(sum / static_cast<double>(s.samplesPerPixel));
                }
            }
            rays += localRays;
            gathers += localGathers;
            shortGathers += localShort;
            invalid += localInvalid;
            double expected = radiusSum.load();
            while (!radiusSum.compare_exchange_weak(expected, expected + localRadius)) {
            }
        });
    });
    if (stats) {
        stats->cameraRays = rays;
        stats->gathers = gathers;
        stats->shortGathers = shortGathers;
        stats->invalidSamples = invalid;
        stats->meanGatherRadius = gathers > 0 ? radiusSum.load() / static_cast<double>(gathers.load()) : 0.0;
    }
    return image;
}

PhotonMapResult PhotonMapper::render(const PhotonMapProgressCallback& progress) const {
    const PhotonMapSettings& s = m_impl->settings;
    PhotonMapResult result;
    result.buildSeconds = m_impl->buildSeconds;
    const Clock::time_point start = Clock::now();
    // Photons are traced with power Phi/pmf and divided by the number emitted once that is known
    // (it is less than asked when the time limit stops tracing).
    std::vector<Photon> photons;
    uint64_t emitted = 0;
    while (emitted < s.photons) {
        if (emitted > 0 && s.timeLimitSeconds > 0.0 && secondsSince(start) >= s.timeLimitSeconds) {
            result.stoppedByTimeLimit = true;
            break;
        }
        const uint64_t count = std::min(PhotonMapSettings::kPhotonsPerPass, s.photons - emitted);
        std::vector<Photon> pass = tracePhotons(emitted, count, 1.0, &result.photonRays);
        photons.insert(photons.end(), pass.begin(), pass.end());
        emitted += count;
        if (progress) progress({PhotonMapProgress::Phase::Tracing, emitted, s.photons, secondsSince(start)});
    }
    const float scale = static_cast<float>(1.0 / static_cast<double>(emitted));
    for (Photon& p : photons) p.power *= scale;
    result.photonsEmitted = emitted;
    result.photonsStored = photons.size();
    result.traceSeconds = secondsSince(start);

    const Clock::time_point treeStart = Clock::now();
    const PhotonMap map(std::move(photons));
    result.treeSeconds = secondsSince(treeStart);
    result.mapBytes = map.memoryBytes();

    const Clock::time_point gatherStart = Clock::now();
    result.radiance = renderImage(map, &result);
    result.gatherSeconds = secondsSince(gatherStart);
    if (progress)
        progress({PhotonMapProgress::Phase::Gathering, static_cast<uint64_t>(s.height), static_cast<uint64_t>(s.height),
                  secondsSince(start)});
    return result;
}

}  // namespace bounce
