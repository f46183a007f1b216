#include "reference/PathTracer.h"

#include "core/ImageIo.h"
#include "core/Log.h"
#include "reference/Bsdf.h"
#include "reference/Sampling.h"
#include "reference/TextureLookup.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Russian roulette starts once a path has reflected this many times: direct light and the first
// indirect bounce are always sampled in full, which keeps the low-order light (most of the image in
// typical scenes) free of roulette noise.
constexpr int kRouletteStartReflections = 2;

// Unbounded paths still stop after this many reflections, so that an albedo of 1 (where roulette
// never fires) cannot loop forever. The light lost is rho^1024 of the total: 3e-5 at rho = 0.99.
constexpr int kMaxUnboundedReflections = 1024;

// A camera ray that enters a one-sided surface from behind passes through it, as the GPU's
// back-face culling lets it; this bounds how many such surfaces one camera ray may cross.
constexpr int kMaxCulledCrossings = 64;

// Tiles are the unit of parallel work: 16 x 16 pixels keeps one tile's accumulators in L1 and gives
// 1024 tiles for a 512^2 image, plenty to balance two to a few dozen threads.
constexpr int kTileSize = 16;

// Each pass renders at least this many paths: enough that per-pass costs (scheduling, and fetching
// every pixel's sums from memory) vanish, few enough that a 512^2 image reports progress and checks
// the time limit every 4 samples per pixel (about half a second).
constexpr uint64_t kMinPathsPerPass = 1u << 20;

// Camera rays go to Embree as packets of 4 x 4 pixels (rtcIntersect16): neighbouring primary rays
// traverse the same BVH nodes, which makes them about twice as cheap as single rays.
constexpr int kPacketSide = 4;
constexpr int kPacketSize = kPacketSide * kPacketSide;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

RTCRayHit makeRayHit(glm::vec3 origin, glm::vec3 direction, float tMax) {
    RTCRayHit rh;
    setRay(rh.ray, origin, direction, 0.0f, tMax);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

template <class Packet>
void setPacketRay(Packet& ray, int lane, glm::vec3 origin, glm::vec3 direction, float tMax) {
    ray.org_x[lane] = origin.x;
    ray.org_y[lane] = origin.y;
    ray.org_z[lane] = origin.z;
    ray.dir_x[lane] = direction.x;
    ray.dir_y[lane] = direction.y;
    ray.dir_z[lane] = direction.z;
    ray.tnear[lane] = 0.0f;
    ray.tfar[lane] = tMax;
    ray.time[lane] = 0.0f;
    ray.mask[lane] = 0xffffffffu;
    ray.id[lane] = 0;
    ray.flags[lane] = 0;
}

RTCRay makeShadowRay(glm::vec3 origin, glm::vec3 direction, float tMax) {
    RTCRay r;
    setRay(r, origin, direction, 0.0f, tMax);
    return r;
}

}  // namespace

// Embree asks for denormals to be flushed to zero on every thread that traces: without it, rays
// nearly parallel to an axis drive box tests through slow denormal arithmetic (Embree's own start-up
// warning). Scoped per tile, since TBB worker threads are shared with the rest of the program; every
// tile runs in the same mode, so images stay independent of the thread count.
class FlushDenormals {
public:
#if defined(__SSE__) || defined(__x86_64__)
    FlushDenormals() noexcept : m_saved(_mm_getcsr()) { _mm_setcsr(m_saved | kFlushToZero | kDenormalsAreZero); }
    ~FlushDenormals() { _mm_setcsr(m_saved); }
    FlushDenormals(const FlushDenormals&) = delete;
    FlushDenormals& operator=(const FlushDenormals&) = delete;

private:
    static constexpr unsigned kFlushToZero = 0x8000;       // MXCSR bit 15 (Intel SDM vol. 1, 10.2.3)
    static constexpr unsigned kDenormalsAreZero = 0x0040;  // MXCSR bit 6
    unsigned m_saved;
#endif
};

struct PathTracer::Counters {
    uint64_t rays = 0;
    uint64_t shadowRays = 0;
    uint64_t invalidSamples = 0;
};

// One pixel's sums over samples, in double so that 10^5 samples add up without losing the small
// ones; together in one struct so that a pixel's sums share a cache line.
struct PathTracer::PixelSums {
    glm::dvec3 radiance{0.0};
    double lum = 0.0;
    double lum2 = 0.0;
};

Expected<PathTracer> PathTracer::create(const Scene& scene, const PathTracerSettings& settings) {
    if (settings.width <= 0 || settings.height <= 0)
        return makeError("image size {}x{}: width and height must be positive", settings.width, settings.height);
    if (settings.samplesPerPixel == 0) return makeError("spp 0: at least one sample per pixel is needed");
    if (settings.bounces < PathTracerSettings::kUnbounded || settings.bounces >= kMaxUnboundedReflections)
        return makeError("bounces {}: must be between 0 and {} (or unbounded)", settings.bounces,
                         kMaxUnboundedReflections - 1);
    if (settings.threads < 0) return makeError("threads {}: must be 0 (all) or more", settings.threads);
    if (!(settings.timeLimitSeconds >= 0.0) || !std::isfinite(settings.timeLimitSeconds))
        return makeError("time limit {}: must be a finite number of seconds >= 0", settings.timeLimitSeconds);
    for (const Material& m : scene.materials) {
        if (m.baseColorTexture < 0) continue;
        if (static_cast<size_t>(m.baseColorTexture) >= scene.textures.size())
            return makeError("material '{}': texture index {} out of range ({} textures)", m.name, m.baseColorTexture,
                             scene.textures.size());
        const TextureImage& t = scene.textures[static_cast<size_t>(m.baseColorTexture)];
        if (t.image.empty()) return makeError("texture '{}' (material '{}'): empty image", t.name, m.name);
        BOUNCE_TRY_VOID(checkFinite(t.image, "texture '" + t.name + "'"));
    }

    const float time = scene.timeOfFrame(settings.frame);
    EmbreeSceneOptions options;
    options.time = time;
    options.filter = GeometryFilter::All;
    options.includeAreaLights = true;
    const Clock::time_point start = Clock::now();
    // Embree builds with TBB: inside the arena the build respects the thread limit too.
    tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
    Expected<EmbreeScene> embree = makeError("unreachable");
    arena.execute([&] { embree = EmbreeScene::build(scene, options); });
    if (!embree) return embree.error();
    PathTracer tracer(scene, settings, std::move(embree).value());
    if (tracer.m_lights.empty())
        return makeError("scene '{}': no light source (no light with non-zero power and no object with an emissive "
                         "material)",
                         scene.name);
    tracer.m_buildSeconds = secondsSince(start);
    return tracer;
}

PathTracer::PathTracer(const Scene& scene, const PathTracerSettings& settings, EmbreeScene embree)
    : m_settings(settings),
      m_time(scene.timeOfFrame(settings.frame)),
      m_embree(std::move(embree)),
      m_lights(scene, m_embree),
      m_camera(scene.camera.at(m_time), settings.width, settings.height),
      m_maxReflections(settings.bounces == PathTracerSettings::kUnbounded ? kMaxUnboundedReflections
                                                                          : settings.bounces + 1) {
    m_shading.resize(m_embree.geometries().size());
    for (size_t i = 0; i < m_shading.size(); ++i) {
        const SceneGeometry& g = m_embree.geometries()[i];
        Shading& s = m_shading[i];
        if (g.kind == SceneGeometry::Kind::AreaLight) {
            s.emitted = scene.lights[g.lightIndex].radiance;
            s.absorber = true;
        } else {
            const Material& m = scene.materials[g.materialIndex];
            s.material = &m;
            if (m.baseColorTexture >= 0) s.texture = &scene.textures[static_cast<size_t>(m.baseColorTexture)].image;
            s.emitted = m.emission;
            s.twoSided = m.twoSided;
            s.diffuseAlbedo = m.baseColor * (1.0f - m.metallic);
            s.lambertian = m.specularF0 == 0.0f && m.metallic == 0.0f;
        }
        s.emissive = maxComponent(s.emitted) > 0.0f;
    }
}

PathTracer::Step PathTracer::scatter(PathState& path, const HitRecord& hit, ShadowRay& shadow) const {
    shadow.active = false;
    const bool indirectOnly = m_settings.indirectOnly;
    const Shading& sh = m_shading[hit.geomId];
    const SurfacePoint sp = m_embree.surface(hit.geomId, hit.primId, hit.u, hit.v);
    const float cosIn = glm::dot(path.direction, sp.geometricNormal);
    const bool front = cosIn < 0.0f;
    Rng& rng = path.rng;

    if (!front && !sh.twoSided && path.reflections == 0) {
        // The rasteriser culls back faces of one-sided surfaces: the camera sees through them.
        if (++path.culledCrossings > kMaxCulledCrossings) return Step::Stop;
        path.tMax -= hit.t;
        path.origin = offsetRayOrigin(sp.position, sp.geometricNormal);
        return Step::Retrace;
    }

    if (sh.emissive && (front || sh.twoSided) && (!indirectOnly || path.reflections >= 2)) {
        float weight = 1.0f;
        if (path.reflections > 0) {
            const float lightPdf = m_lights.pdfEmitterHit(hit.geomId, hit.primId, hit.t, std::abs(cosIn));
            weight = powerHeuristic(path.bsdfPdf, lightPdf);
        }
        path.radiance += path.throughput * sh.emitted * weight;
    }
    if (sh.absorber || !(front || sh.twoSided)) return Step::Stop;
    if (path.reflections >= m_maxReflections) return Step::Stop;
    const int vertex = path.reflections + 1;  // this is the path's vertex-th reflection

    const glm::vec3 ng = front ? sp.geometricNormal : -sp.geometricNormal;
    glm::vec3 ns = front ? sp.shadingNormal : -sp.shadingNormal;
    // An interpolated normal can turn away from the viewer at silhouettes; fall back to the face.
    if (glm::dot(ns, path.direction) >= 0.0f) ns = ng;
    const Frame frame(ns);
    const glm::vec3 texel = sh.texture ? lookupBilinearRepeat(*sh.texture, sp.uv) : glm::vec3(1.0f);
    const glm::vec3 position = offsetRayOrigin(sp.position, ng);
    // Pure Lambert (the built-in scenes, and every vertex after the first under --diffuse-only)
    // takes a short path without the general BRDF.
    const bool lambert = sh.lambertian || (m_settings.diffuseOnly && vertex >= 2);
    const glm::vec3 albedo = sh.diffuseAlbedo * texel;
    const glm::vec3 wo = frame.toLocal(-path.direction);
    const Bsdf bsdf = lambert ? Bsdf() : Bsdf(*sh.material, sh.material->baseColor * texel, false);

    // Next-event estimation: one light source, one shadow ray (traced by the caller). Under
    // --indirect-only the first reflection's direct light is not wanted, so no ray is spent on it.
    const float uSelect = rng.next(), uLight1 = rng.next(), uLight2 = rng.next();
    if (!indirectOnly || vertex >= 2) {
        LightSample ls;
        if (m_lights.sample(sp.position, uSelect, uLight1, uLight2, ls) && glm::dot(ls.wi, ng) > 0.0f) {
            const float cosS = glm::dot(ls.wi, ns);
            glm::vec3 f(0.0f);
            float pdf = 0.0f;
            if (lambert) {
                if (cosS > 0.0f) {
                    f = albedo * kInvPi;
                    pdf = cosS * kInvPi;
                }
            } else {
                const glm::vec3 wi = frame.toLocal(ls.wi);
                f = bsdf.eval(wo, wi);
                if (maxComponent(f) > 0.0f) pdf = bsdf.pdf(wo, wi);
            }
            if (maxComponent(f) > 0.0f) {
                const float weight = ls.pdf > 0.0f ? powerHeuristic(ls.pdf, pdf) : 1.0f;
                shadow.active = true;
                shadow.origin = position;
                if (std::isfinite(ls.distance)) {
                    shadow.direction = ls.lightPoint - position;
                    shadow.tMax = 1.0f;
                } else {
                    shadow.direction = ls.wi;
                    shadow.tMax = std::numeric_limits<float>::infinity();
                }
                shadow.contribution = path.throughput * f * (cosS * weight) * ls.contribution;
            }
        }
    }

    glm::vec3 wi;
    if (lambert) {
        const glm::vec3 local = cosineHemisphere(rng);
        wi = frame.toWorld(local);
        path.throughput *= albedo;  // (albedo / pi) cos / (cos / pi)
        path.bsdfPdf = local.z * kInvPi;
    } else {
        const float uLobe = rng.next(), u1 = rng.next(), u2 = rng.next();
        Bsdf::Sample bs;
        if (!bsdf.sample(wo, uLobe, u1, u2, bs)) return Step::Stop;
        wi = frame.toWorld(bs.wi);
        path.throughput *= bs.weight;
        path.bsdfPdf = bs.pdf;
    }
    // Directions below the geometric surface would leak through it.
    if (glm::dot(wi, ng) <= 0.0f) return Step::Stop;
    path.reflections = vertex;
    if (path.reflections >= kRouletteStartReflections) {
        const float survive = std::min(1.0f, maxComponent(path.throughput));
        if (!(rng.next() < survive)) return Step::Stop;
        path.throughput /= survive;
    }
    path.origin = position;
    path.direction = wi;
    path.tMax = std::numeric_limits<float>::infinity();
    return Step::Continue;
}

PathTracer::HitRecord PathTracer::intersect(const PathState& path, Counters& counters) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = makeRayHit(path.origin, path.direction, path.tMax);
    rtcIntersect1(m_embree.handle(), &context, &rh);
    ++counters.rays;
    return {rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar};
}

bool PathTracer::visible(const ShadowRay& shadow, Counters& counters) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeShadowRay(shadow.origin, shadow.direction, shadow.tMax);
    rtcOccluded1(m_embree.handle(), &context, &ray);
    ++counters.rays;
    ++counters.shadowRays;
    return ray.tfar >= 0.0f;
}

void PathTracer::finishPath(PathState& path, HitRecord hit, Counters& counters) const {
    while (hit.geomId != RTC_INVALID_GEOMETRY_ID) {
        ShadowRay shadow;
        const Step step = scatter(path, hit, shadow);
        if (shadow.active && visible(shadow, counters)) path.radiance += shadow.contribution;
        if (step == Step::Stop) return;
        hit = intersect(path, counters);
    }
}

void PathTracer::renderTile(int x0, int y0, int x1, int y1, uint32_t s0, uint32_t s1, PixelSums* sums,
                            Counters& counters) const {
    const FlushDenormals flushDenormals;
    const auto width = static_cast<size_t>(m_settings.width);
    RTCIntersectContext coherent;
    rtcInitIntersectContext(&coherent);
    coherent.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[kPacketSize];  // Embree requires the masks to be 64-byte aligned
    alignas(64) int shadowValid[kPacketSize];
    alignas(64) RTCRayHit16 packet;
    alignas(64) RTCRay16 shadowPacket;
    std::array<PathState, kPacketSize> paths;
    std::array<ShadowRay, kPacketSize> shadows;
    std::array<Step, kPacketSize> steps;
    std::array<size_t, kPacketSize> pixels;

    for (int by = y0; by < y1; by += kPacketSide) {
        for (int bx = x0; bx < x1; bx += kPacketSide) {
            int lanes = 0;
            for (int lane = 0; lane < kPacketSize; ++lane) {
                const int x = bx + lane % kPacketSide, y = by + lane / kPacketSide;
                const bool inside = x < x1 && y < y1;
                valid[lane] = inside ? -1 : 0;
                pixels[lane] = inside ? static_cast<size_t>(y) * width + static_cast<size_t>(x) : 0;
                lanes += inside ? 1 : 0;
            }
            for (uint32_t s = s0; s < s1; ++s) {
                // Camera rays of the 4 x 4 block as one coherent packet.
                for (int lane = 0; lane < kPacketSize; ++lane) {
                    if (!valid[lane]) continue;
                    PathState& path = paths[lane];
                    path = PathState{};
                    path.rng = Rng(m_settings.seed, pixels[lane], s);
                    const float jx = path.rng.next(), jy = path.rng.next();
                    const int x = bx + lane % kPacketSide, y = by + lane / kPacketSide;
                    const CameraRay r = m_camera.generate(static_cast<float>(x) + jx, static_cast<float>(y) + jy);
                    path.origin = r.origin;
                    path.direction = r.direction;
                    path.tMax = r.tMax;
                    setPacketRay(packet.ray, lane, r.origin, r.direction, r.tMax);
                    packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
                    packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
                }
                rtcIntersect16(valid, m_embree.handle(), &coherent, &packet);
                counters.rays += static_cast<uint64_t>(lanes);

                // The first reflection of every lane, whose shadow rays all start near each other
                // and head for the same lights: traced as one coherent packet, about twice as fast
                // as single rays. Later reflections are incoherent and go one ray at a time.
                int shadowLanes = 0;
                for (int lane = 0; lane < kPacketSize; ++lane) {
                    shadowValid[lane] = 0;
                    steps[lane] = Step::Stop;
                    if (!valid[lane]) continue;
                    PathState& path = paths[lane];
                    HitRecord hit{packet.hit.geomID[lane], packet.hit.primID[lane], packet.hit.u[lane],
                                  packet.hit.v[lane], packet.ray.tfar[lane]};
                    ShadowRay& shadow = shadows[lane];
                    shadow.active = false;
                    while (hit.geomId != RTC_INVALID_GEOMETRY_ID) {
                        steps[lane] = scatter(path, hit, shadow);
                        if (steps[lane] != Step::Retrace) break;
                        hit = intersect(path, counters);
                    }
                    if (hit.geomId == RTC_INVALID_GEOMETRY_ID) steps[lane] = Step::Stop;
                    if (!shadow.active) continue;
                    shadowValid[lane] = -1;
                    ++shadowLanes;
                    setPacketRay(shadowPacket, lane, shadow.origin, shadow.direction, shadow.tMax);
                }
                if (shadowLanes > 0) {
                    rtcOccluded16(shadowValid, m_embree.handle(), &coherent, &shadowPacket);
                    counters.rays += static_cast<uint64_t>(shadowLanes);
                    counters.shadowRays += static_cast<uint64_t>(shadowLanes);
                }

                for (int lane = 0; lane < kPacketSize; ++lane) {
                    if (!valid[lane]) continue;
                    PathState& path = paths[lane];
                    if (shadowValid[lane] && shadowPacket.tfar[lane] >= 0.0f) path.radiance += shadows[lane].contribution;
                    if (steps[lane] == Step::Continue) finishPath(path, intersect(path, counters), counters);
                    glm::vec3 L = path.radiance;
                    if (!finite(L)) {
                        ++counters.invalidSamples;
                        L = glm::vec3(0.0f);
                    }
                    // Samples reach each pixel in increasing s whatever the thread: the sums are
                    // bit-identical for any thread count.
                    PixelSums& p = sums[pixels[lane]];
                    const double y = luminance(L);
                    p.radiance += glm::dvec3(L);
                    p.lum += y;
                    p.lum2 += y * y;
                }
            }
        }
    }
}

PathTracerResult PathTracer::render(const ProgressCallback& progress) const {
    const int width = m_settings.width, height = m_settings.height;
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    std::vector<PixelSums> sums(pixels);

    const uint32_t target = m_settings.samplesPerPixel;
    const auto perPass = static_cast<uint32_t>(
        std::clamp<uint64_t>((kMinPathsPerPass + pixels - 1) / pixels, 1, target));
    const int tilesX = (width + kTileSize - 1) / kTileSize, tilesY = (height + kTileSize - 1) / kTileSize;

    tbb::task_arena arena(m_settings.threads > 0 ? m_settings.threads : tbb::task_arena::automatic);
    PathTracerResult result;
    const bool limited = m_settings.timeLimitSeconds > 0.0;
    const Clock::time_point start = Clock::now();
    const Clock::time_point deadline =
        start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(m_settings.timeLimitSeconds));
    // With a time limit, a pass that cannot finish in time is abandoned and its partial sums
    // replaced by this copy, so the image holds complete passes only.
    std::vector<PixelSums> before;
    uint32_t done = 0;
    while (done < target) {
        const uint32_t s0 = done, s1 = std::min(target, done + perPass);
        // The first pass always completes, so there is an image however small the budget.
        const bool cancellable = limited && done > 0;
        if (cancellable) before = sums;
        std::atomic<bool> cancelled{false};
        std::atomic<uint64_t> rays{0}, shadowRays{0}, invalid{0};
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range2d<int>(0, tilesY, 1, 0, tilesX, 1),
                              [&](const tbb::blocked_range2d<int>& r) {
                                  Counters local;
                                  for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
                                      for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx) {
                                          if (cancellable && (cancelled.load(std::memory_order_relaxed) ||
                                                              Clock::now() > deadline)) {
                                              cancelled = true;
                                              return;
                                          }
                                          renderTile(tx * kTileSize, ty * kTileSize,
                                                     std::min(width, (tx + 1) * kTileSize),
                                                     std::min(height, (ty + 1) * kTileSize), s0, s1, sums.data(),
                                                     local);
                                      }
                                  rays += local.rays;
                                  shadowRays += local.shadowRays;
                                  invalid += local.invalidSamples;
                              });
        });
        if (cancelled || (cancellable && Clock::now() > deadline)) {
            sums.swap(before);
            result.stoppedByTimeLimit = true;
            break;
        }
        done = s1;
        result.rays += rays;
        result.shadowRays += shadowRays;
        result.invalidSamples += invalid;
        if (progress) progress(RenderProgress{done, target, secondsSince(start)});
        if (limited && done < target && Clock::now() >= deadline) {
            result.stoppedByTimeLimit = true;
            break;
        }
    }
    result.renderSeconds = secondsSince(start);
    result.buildSeconds = m_buildSeconds;
    result.samplesPerPixel = done;
    result.paths = static_cast<uint64_t>(pixels) * done;
    if (result.invalidSamples > 0)
        spdlog::warn("reference: {} non-finite samples were dropped", result.invalidSamples);

    result.radiance = Image(width, height);
    const double n = static_cast<double>(done);
    double relSum = 0.0, varOfMeanSum = 0.0, meanSum = 0.0;
    uint64_t measured = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const PixelSums& p = sums[i];
        result.radiance.data()[i] = glm::vec3(p.radiance / n);
        const double mean = p.lum / n;
        // Unbiased sample variance of the per-sample luminance; needs two samples.
        const double variance = done > 1 ? std::max(0.0, (p.lum2 - n * mean * mean) / (n - 1.0)) : 0.0;
        const double varOfMean = variance / n;
        meanSum += mean;
        varOfMeanSum += varOfMean;
        if (mean > 0.0) {
            relSum += std::sqrt(varOfMean) / mean;
            ++measured;
        }
    }
    result.noise.pixelsMeasured = measured;
    result.noise.meanPixelRelativeError = measured > 0 ? relSum / static_cast<double>(measured) : 0.0;
    // The image mean is (1/P) sum of pixel means; its variance is (1/P^2) sum of their variances.
    result.noise.imageRelativeError = meanSum > 0.0 ? std::sqrt(varOfMeanSum) / meanSum : 0.0;
    return result;
}

}  // namespace bounce
