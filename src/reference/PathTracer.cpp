#include "reference/PathTracer.h"

#include "core/ImageIo.h"
#include "core/Log.h"
#include "reference/Bsdf.h"
#include "reference/Sampling.h"
#include "reference/TextureLookup.h"

#include <tbb/blocked_range2d.h>
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

// Each pass renders at least this many paths, so that small test images (8 x 8 at 4096 spp) are not
// dominated by per-pass scheduling; a 512^2 image still advances one sample per pixel per pass.
constexpr uint64_t kMinPathsPerPass = 65536;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

RTCRayHit makeRayHit(glm::vec3 origin, glm::vec3 direction, float tMax) {
    RTCRayHit rh;
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.tnear = 0.0f;
    rh.ray.dir_x = direction.x;
    rh.ray.dir_y = direction.y;
    rh.ray.dir_z = direction.z;
    rh.ray.time = 0.0f;
    rh.ray.tfar = tMax;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

RTCRay makeShadowRay(glm::vec3 origin, glm::vec3 direction, float tMax) {
    RTCRay r;
    r.org_x = origin.x;
    r.org_y = origin.y;
    r.org_z = origin.z;
    r.tnear = 0.0f;
    r.dir_x = direction.x;
    r.dir_y = direction.y;
    r.dir_z = direction.z;
    r.time = 0.0f;
    r.tfar = tMax;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    return r;
}

}  // namespace

struct PathTracer::Counters {
    uint64_t rays = 0;
    uint64_t shadowRays = 0;
    uint64_t invalidSamples = 0;
};

// Per-pixel sums over samples, in double so that 10^5 samples add up without losing the small ones.
struct PathTracer::Accumulator {
    int width = 0;
    std::vector<glm::dvec3> radiance;
    std::vector<double> lum;
    std::vector<double> lum2;
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
    : m_scene(&scene),
      m_settings(settings),
      m_time(scene.timeOfFrame(settings.frame)),
      m_embree(std::move(embree)),
      m_lights(scene, m_embree),
      m_camera(scene.camera.at(m_time), settings.width, settings.height),
      m_maxReflections(settings.bounces == PathTracerSettings::kUnbounded ? kMaxUnboundedReflections : settings.bounces + 1) {
    m_shading.resize(m_embree.geometries().size());
    for (size_t i = 0; i < m_shading.size(); ++i) {
        const SceneGeometry& g = m_embree.geometries()[i];
        Shading& s = m_shading[i];
        if (g.kind == SceneGeometry::Kind::AreaLight) {
            s.emitted = scene.lights[g.lightIndex].radiance;
            s.absorber = true;
        } else {
            s.material = &scene.materials[g.materialIndex];
            if (s.material->baseColorTexture >= 0)
                s.texture = &scene.textures[static_cast<size_t>(s.material->baseColorTexture)].image;
            s.emitted = s.material->emission;
            s.twoSided = s.material->twoSided;
        }
        s.emissive = maxComponent(s.emitted) > 0.0f;
    }
}

glm::vec3 PathTracer::tracePath(Rng& rng, CameraRay cameraRay, Counters& counters) const {
    RTCScene scene = m_embree.handle();
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const bool indirectOnly = m_settings.indirectOnly;
    const bool diffuseOnly = m_settings.diffuseOnly;

    glm::vec3 radiance(0.0f);
    glm::vec3 throughput(1.0f);
    int reflections = 0;     // scattering events so far on this path
    float bsdfPdf = 0.0f;    // solid-angle pdf of the BSDF sample that chose the current ray
    int culledCrossings = 0;
    glm::vec3 origin = cameraRay.origin, direction = cameraRay.direction;
    float tMax = cameraRay.tMax;

    for (;;) {
        RTCRayHit rh = makeRayHit(origin, direction, tMax);
        rtcIntersect1(scene, &context, &rh);
        ++counters.rays;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;

        const uint32_t geomId = rh.hit.geomID, primId = rh.hit.primID;
        const Shading& sh = m_shading[geomId];
        const SurfacePoint sp = m_embree.surface(geomId, primId, rh.hit.u, rh.hit.v);
        const float cosIn = glm::dot(direction, sp.geometricNormal);
        const bool front = cosIn < 0.0f;

        if (!front && !sh.twoSided && reflections == 0) {
            // The rasteriser culls back faces of one-sided surfaces: the camera sees through them.
            if (++culledCrossings > kMaxCulledCrossings) break;
            origin = offsetRayOrigin(sp.position, sp.geometricNormal);
            tMax -= rh.ray.tfar;
            continue;
        }

        if (sh.emissive && (front || sh.twoSided) && (!indirectOnly || reflections >= 2)) {
            float weight = 1.0f;
            if (reflections > 0) {
                const float lightPdf = m_lights.pdfEmitterHit(geomId, primId, rh.ray.tfar, std::abs(cosIn));
                weight = powerHeuristic(bsdfPdf, lightPdf);
            }
            radiance += throughput * sh.emitted * weight;
        }
        if (sh.absorber || !(front || sh.twoSided)) break;
        if (reflections >= m_maxReflections) break;
        const int vertex = reflections + 1;  // this is the path's vertex-th reflection

        const glm::vec3 ng = front ? sp.geometricNormal : -sp.geometricNormal;
        glm::vec3 ns = front ? sp.shadingNormal : -sp.shadingNormal;
        // An interpolated normal can turn away from the viewer at silhouettes; fall back to the face.
        if (glm::dot(ns, direction) >= 0.0f) ns = ng;
        const Frame frame(ns);
        const glm::vec3 wo = frame.toLocal(-direction);
        glm::vec3 baseColor = sh.material->baseColor;
        if (sh.texture) baseColor *= lookupBilinearRepeat(*sh.texture, sp.uv);
        const Bsdf bsdf(*sh.material, baseColor, diffuseOnly && vertex >= 2);
        const glm::vec3 position = offsetRayOrigin(sp.position, ng);

        // Next-event estimation: one light source, one shadow ray. Under --indirect-only the first
        // reflection's direct light is not wanted, so no ray is spent on it.
        const float uSelect = rng.next(), uLight1 = rng.next(), uLight2 = rng.next();
        if (!indirectOnly || vertex >= 2) {
            LightSample ls;
            if (m_lights.sample(sp.position, uSelect, uLight1, uLight2, ls) && glm::dot(ls.wi, ng) > 0.0f) {
                const glm::vec3 wi = frame.toLocal(ls.wi);
                const glm::vec3 f = bsdf.eval(wo, wi);
                if (maxComponent(f) > 0.0f) {
                    const bool infinite = !std::isfinite(ls.distance);
                    RTCRay shadow = infinite ? makeShadowRay(position, ls.wi, std::numeric_limits<float>::infinity())
                                             : makeShadowRay(position, ls.lightPoint - position, 1.0f);
                    rtcOccluded1(scene, &context, &shadow);
                    ++counters.rays;
                    ++counters.shadowRays;
                    if (shadow.tfar >= 0.0f) {
                        const float weight = ls.pdf > 0.0f ? powerHeuristic(ls.pdf, bsdf.pdf(wo, wi)) : 1.0f;
                        radiance += throughput * f * (wi.z * weight) * ls.contribution;
                    }
                }
            }
        }

        const float uLobe = rng.next(), u1 = rng.next(), u2 = rng.next();
        Bsdf::Sample bs;
        if (!bsdf.sample(wo, uLobe, u1, u2, bs)) break;
        const glm::vec3 wi = frame.toWorld(bs.wi);
        // Directions below the geometric surface would leak through it.
        if (glm::dot(wi, ng) <= 0.0f) break;
        throughput *= bs.weight;
        bsdfPdf = bs.pdf;
        reflections = vertex;
        if (reflections >= kRouletteStartReflections) {
            const float survive = std::min(1.0f, maxComponent(throughput));
            if (!(rng.next() < survive)) break;
            throughput /= survive;
        }
        origin = position;
        direction = wi;
        tMax = std::numeric_limits<float>::infinity();
    }
    return radiance;
}

void PathTracer::renderTile(int x0, int y0, int x1, int y1, uint32_t s0, uint32_t s1, Accumulator& acc,
                            Counters& counters) const {
    const int width = m_settings.width;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            const size_t pixel = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
            glm::dvec3 sum = acc.radiance[pixel];
            double lum = acc.lum[pixel], lum2 = acc.lum2[pixel];
            for (uint32_t s = s0; s < s1; ++s) {
                Rng rng(m_settings.seed, pixel, s);
                const float jx = rng.next(), jy = rng.next();
                const CameraRay ray = m_camera.generate(static_cast<float>(x) + jx, static_cast<float>(y) + jy);
                glm::vec3 L = tracePath(rng, ray, counters);
                if (!finite(L)) {
                    ++counters.invalidSamples;
                    L = glm::vec3(0.0f);
                }
                const double y1v = luminance(L);
                sum += glm::dvec3(L);
                lum += y1v;
                lum2 += y1v * y1v;
            }
            acc.radiance[pixel] = sum;
            acc.lum[pixel] = lum;
            acc.lum2[pixel] = lum2;
        }
    }
}

PathTracerResult PathTracer::render(const ProgressCallback& progress) const {
    const int width = m_settings.width, height = m_settings.height;
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    Accumulator acc;
    acc.width = width;
    acc.radiance.assign(pixels, glm::dvec3(0.0));
    acc.lum.assign(pixels, 0.0);
    acc.lum2.assign(pixels, 0.0);

    const uint32_t target = m_settings.samplesPerPixel;
    const auto perPass = static_cast<uint32_t>(
        std::clamp<uint64_t>((kMinPathsPerPass + pixels - 1) / pixels, 1, target));
    const int tilesX = (width + kTileSize - 1) / kTileSize, tilesY = (height + kTileSize - 1) / kTileSize;

    std::atomic<uint64_t> rays{0}, shadowRays{0}, invalid{0};
    tbb::task_arena arena(m_settings.threads > 0 ? m_settings.threads : tbb::task_arena::automatic);
    PathTracerResult result;
    const Clock::time_point start = Clock::now();
    uint32_t done = 0;
    double lastPassSeconds = 0.0;
    while (done < target) {
        const double elapsed = secondsSince(start);
        // Start another pass only if it is expected to end within the budget (the first always runs).
        if (m_settings.timeLimitSeconds > 0.0 && done > 0 && elapsed + lastPassSeconds > m_settings.timeLimitSeconds) {
            result.stoppedByTimeLimit = true;
            break;
        }
        const uint32_t s0 = done, s1 = std::min(target, done + perPass);
        const Clock::time_point passStart = Clock::now();
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range2d<int>(0, tilesY, 1, 0, tilesX, 1),
                              [&](const tbb::blocked_range2d<int>& r) {
                                  Counters local;
                                  for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
                                      for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx)
                                          renderTile(tx * kTileSize, ty * kTileSize,
                                                     std::min(width, (tx + 1) * kTileSize),
                                                     std::min(height, (ty + 1) * kTileSize), s0, s1, acc, local);
                                  rays += local.rays;
                                  shadowRays += local.shadowRays;
                                  invalid += local.invalidSamples;
                              });
        });
        lastPassSeconds = secondsSince(passStart);
        done = s1;
        if (progress) progress(RenderProgress{done, target, secondsSince(start)});
    }
    result.renderSeconds = secondsSince(start);
    result.buildSeconds = m_buildSeconds;
    result.samplesPerPixel = done;
    result.paths = static_cast<uint64_t>(pixels) * done;
    result.rays = rays.load();
    result.shadowRays = shadowRays.load();
    result.invalidSamples = invalid.load();
    if (result.invalidSamples > 0)
        spdlog::warn("reference: {} non-finite samples were dropped", result.invalidSamples);

    result.radiance = Image(width, height);
    const double n = static_cast<double>(done);
    double relSum = 0.0, varOfMeanSum = 0.0, meanSum = 0.0;
    uint64_t measured = 0;
    for (size_t i = 0; i < pixels; ++i) {
        result.radiance.data()[i] = glm::vec3(acc.radiance[i] / n);
        const double mean = acc.lum[i] / n;
        // Unbiased sample variance of the per-sample luminance; needs two samples.
        const double variance = done > 1 ? std::max(0.0, (acc.lum2[i] - n * mean * mean) / (n - 1.0)) : 0.0;
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
