#include "reference/PathTracer.h"

#include "core/ImageIo.h"
#include "core/Log.h"
#include "reference/Bsdf.h"
#include "scene/AreaTexture.h"
#include "reference/LambertKernel.h"
#include "reference/Sampling.h"
#include "reference/TextureLookup.h"

#include <glm/gtc/constants.hpp>

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
#include <cstring>
#include <memory>

namespace bounce {

namespace {

// PathTracerSettings::firstReflectionCones: a direction from the cone mixture (cone k with probability
// W_k / sum W, uniform within it) in the vct tracer's frame about the shading normal n, and its pdf
// (sum over the cones holding it of (W_k / sum W) / Omega_k, per steradian).
glm::vec3 sampleQuadratureCones(const std::vector<PathTracerSettings::QuadratureCone>& cones, glm::vec3 n, Rng& rng,
                                float& pdf) {
    float total = 0.0f;
    for (const auto& c : cones) total += c.weight;
    float pick = rng.next() * total;
    size_t k = 0;
    while (k + 1 < cones.size() && pick >= cones[k].weight) pick -= cones[k++].weight;
    const glm::vec3 helper = std::abs(n.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 tx = glm::normalize(glm::cross(helper, n)), tz = glm::cross(tx, n);
    const auto toWorld = [&](glm::vec3 d) { return glm::normalize(tx * d.x + n * d.y + tz * d.z); };
    // Uniform in cone k: cos theta uniform on [cos alpha, 1] about its axis.
    const glm::vec3 axis = toWorld(cones[k].direction);
    const float cosAlpha = std::cos(cones[k].halfAngle);
    const float cosTheta = 1.0f - rng.next() * (1.0f - cosAlpha);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * glm::pi<float>() * rng.next();
    const Frame around(axis);
    const glm::vec3 wi = around.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
    pdf = 0.0f;
    for (const auto& c : cones) {
        const float solidAngle = 2.0f * glm::pi<float>() * (1.0f - std::cos(c.halfAngle));
        if (glm::dot(wi, toWorld(c.direction)) >= std::cos(c.halfAngle) && solidAngle > 0.0f)
            pdf += c.weight / total / solidAngle;
    }
    return wi;
}

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

// A tile's paths run 16 at a time, as the lanes of one Embree packet (rtcIntersect16, rtcOccluded16)
// and of the vectorised kernel.
constexpr int kLanesOfPacket = lambert::kLanes;
static_assert(static_cast<int>(LightSampler::Kind::Point) == lambert::kPointLight &&
              static_cast<int>(LightSampler::Kind::Spot) == lambert::kSpotLight &&
              static_cast<int>(LightSampler::Kind::Directional) == lambert::kDirectionalLight &&
              static_cast<int>(LightSampler::Kind::Area) == lambert::kAreaLight &&
              static_cast<int>(LightSampler::Kind::Triangle) == lambert::kTriangleLight);
static_assert(kLanesOfPacket == 16, "the Embree packet calls are the 16-wide ones");

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

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
    glm::dvec3 radiance2{0.0};  // per channel sum of squares: the variance image (noise floors, docs/metrics.md)
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
    BOUNCE_TRY_VOID(checkTracedTextures(scene));
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
    // A textured light that is black at this frame leaves the list empty, yet the scene has a light: the
    // image is then black (tests/unit/ReferenceAreaTextureTest.cpp), not an error.
    if (tracer.m_lights.empty() && !tracer.m_lights.hasDarkTexturedLight())
        return makeError("scene '{}': no light source (no light with non-zero power and no object with an emissive "
                         "material)",
                         scene.name);
    tracer.m_buildSeconds = secondsSince(start);
    return tracer;
}

std::vector<PathTracer::Shading> PathTracer::gatherShading(const Scene& scene, const EmbreeScene& embree,
                                                          const LightSampler& lights, float time) {
    std::vector<Shading> shading(embree.geometries().size());
    for (size_t i = 0; i < shading.size(); ++i) {
        const SceneGeometry& g = embree.geometries()[i];
        Shading& s = shading[i];
        if (g.kind == SceneGeometry::Kind::AreaLight) {
            const Light light = scene.lights[g.lightIndex].at(time);
            s.emitted = light.radiance;
            s.emitterTexture = lights.texture(static_cast<uint32_t>(i));
            s.twoSided = light.twoSided;
            s.absorber = true;
        } else {
            const Material& m = scene.materials[g.materialIndex];
            s.material = &m;
            if (m.baseColorTexture >= 0) s.texture = &scene.textures[static_cast<size_t>(m.baseColorTexture)].image;
            if (m.emissionTexture >= 0) s.emissionTexture = &scene.textures[static_cast<size_t>(m.emissionTexture)].image;
            s.emitted = m.emission;
            s.twoSided = m.twoSided;
            s.diffuseAlbedo = m.baseColor * (1.0f - m.metallic);
            s.lambertian = m.specularF0 == 0.0f && m.metallic == 0.0f;
            if (m.metallicRoughnessTexture >= 0 && !g.uvs.empty())
                s.metallicRoughnessTexture = &scene.textures[static_cast<size_t>(m.metallicRoughnessTexture)].image;
            s.normalMapped = g.normalTexture != nullptr;
        }
        s.emissive = maxComponent(s.emitted) > 0.0f;
    }
    return shading;
}

PathTracer::PathTracer(const Scene& scene, const PathTracerSettings& settings, EmbreeScene embree)
    : m_settings(settings),
      m_time(scene.timeOfFrame(settings.frame)),
      m_embree(std::move(embree)),
      m_lights(scene, m_embree),
      m_camera(scene.camera.at(m_time), settings.width, settings.height),
      m_maxReflections(settings.bounces == PathTracerSettings::kUnbounded ? kMaxUnboundedReflections
                                                                          : settings.bounces + 1) {
    m_shading = gatherShading(scene, m_embree, m_lights, m_time);
    // What the kernel needs of each geometry, in one place (it reads the triangles themselves from
    // Embree's copy, as surface() does: a per-triangle table was 10 % slower on atrium's 100K
    // triangles, from cache misses).
    m_kernelGeometries.resize(m_shading.size());
    for (size_t gi = 0; gi < m_shading.size(); ++gi) {
        const SceneGeometry& g = m_embree.geometries()[gi];
        const Shading& sh = m_shading[gi];
        KernelGeometry& k = m_kernelGeometries[gi];
        k.triangles = g.triangles.data();
        k.positions = g.positions.data();
        k.faceNormals = g.faceNormals.data();
        k.normals = g.normals.empty() ? nullptr : g.normals.data();
        k.albedo = sh.diffuseAlbedo;
        k.emitted = sh.emitted;
        if (sh.emissive) {
            k.emitter = m_lights.emitter(static_cast<uint32_t>(gi), 0);
            k.emitterPerTriangle = k.emitter && k.emitter->kind == LightSampler::Kind::Triangle;
        }
        // Textured emitters vary over their rectangle: their hits go through scatter().
        // So do normal-mapped and metallic-roughness-textured materials (surface() and the texel).
        const bool plain = sh.texture == nullptr && !sh.normalMapped && sh.metallicRoughnessTexture == nullptr;
        k.shades = plain && sh.emitterTexture == nullptr && sh.emissionTexture == nullptr &&
                   (sh.lambertian || sh.absorber);
        k.shadesDiffuseOnly = plain && m_settings.diffuseOnly;
        k.emissive = sh.emissive;
        k.twoSided = sh.twoSided;
        k.absorber = sh.absorber;
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
            const float lightPdf = m_lights.pdfEmitterHit(hit.geomId, hit.primId, hit.u, hit.v, hit.t, std::abs(cosIn));
            weight = powerHeuristic(path.bsdfPdf, lightPdf);
        }
        path.radiance += path.throughput * emittedAt(sh, hit.primId, hit.u, hit.v, sp.uv) * weight;
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
    glm::vec3 albedo = sh.diffuseAlbedo * texel;
    const glm::vec3 wo = frame.toLocal(-path.direction);
    const Material* material = sh.material;
    Material textured;  // the factors times the metallic-roughness texel (glTF: G roughness, B metallic)
    if (sh.metallicRoughnessTexture) {
        const glm::vec3 mr = lookupBilinearRepeat(*sh.metallicRoughnessTexture, sp.uv);
        textured = *sh.material;
        textured.roughness *= mr.g;
        textured.metallic *= mr.b;
        material = &textured;
        albedo = textured.baseColor * (1.0f - textured.metallic) * texel;
    }
    const Bsdf bsdf = lambert ? Bsdf() : Bsdf(*material, material->baseColor * texel, false);

    // Next-event estimation: one light source, one shadow ray (traced by the caller). Under
    // --indirect-only the first reflection's direct light is not wanted, so no ray is spent on it.
    const float uSelect = rng.next(), uLight1 = rng.next(), uLight2 = rng.next();
    if ((!indirectOnly || vertex >= 2) && !m_lights.empty()) {
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
    if (lambert && vertex == 1 && !m_settings.firstReflectionCones.empty()) {
        wi = sampleQuadratureCones(m_settings.firstReflectionCones, ns, rng, path.bsdfPdf);
        path.throughput *= albedo;  // the quadrature's weight: (albedo / pi) sum W_k 1_k / Omega_k over its pdf
    } else if (lambert) {
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

// The lanes' state in and out of a PathState, for scatter().
PathTracer::PathState PathTracer::laneState(const lambert::Lanes& L, int i) {
    PathState path;
    path.rng = Rng::fromState(L.rng[i]);
    path.radiance = L.radiance.at(i);
    path.throughput = L.throughput.at(i);
    path.origin = L.origin.at(i);
    path.direction = L.direction.at(i);
    path.tMax = L.tMax[i];
    path.reflections = L.reflections[i];
    path.bsdfPdf = L.bsdfPdf[i];
    path.culledCrossings = L.culledCrossings[i];
    return path;
}

void PathTracer::setLaneState(lambert::Lanes& L, int i, const PathState& path) {
    L.rng[i] = path.rng.state();
    L.radiance.set(i, path.radiance);
    L.throughput.set(i, path.throughput);
    L.origin.set(i, path.origin);
    L.direction.set(i, path.direction);
    L.tMax[i] = path.tMax;
    L.reflections[i] = path.reflections;
    L.bsdfPdf[i] = path.bsdfPdf;
    L.culledCrossings[i] = path.culledCrossings;
}

bool PathTracer::loadKernelLane(lambert::Lanes& L, int i) const {
    const KernelGeometry& k = m_kernelGeometries[L.geomId[i]];
    const uint32_t primId = L.primId[i];
    const int reflections = L.reflections[i];
    if (!(k.shades || (k.shadesDiffuseOnly && reflections + 1 >= 2))) return false;
    // The cone quadrature's first reflection is drawn by scatter() (the kernel samples the cosine lobe).
    if (reflections == 0 && !m_settings.firstReflectionCones.empty()) return false;
    const glm::vec3 ng = k.faceNormals[primId];
    // A camera ray crossing a culled back face is traced on by scatter().
    if (reflections == 0 && !k.twoSided && !(glm::dot(L.direction.at(i), ng) < 0.0f)) return false;
    const glm::uvec3 tri = k.triangles[primId];
    L.in[i] = 1;
    L.p0.set(i, k.positions[tri.x]);
    L.p1.set(i, k.positions[tri.y]);
    L.p2.set(i, k.positions[tri.z]);
    L.faceNormal.set(i, ng);
    L.smooth[i] = k.normals != nullptr;
    if (k.normals) {
        L.n0.set(i, k.normals[tri.x]);
        L.n1.set(i, k.normals[tri.y]);
        L.n2.set(i, k.normals[tri.z]);
    }
    L.albedo.set(i, k.albedo);
    L.emitted.set(i, k.emitted);
    const LightSampler::Entry* emitter = k.emitterPerTriangle ? k.emitter + primId : k.emitter;
    L.emitterPmf[i] = emitter ? emitter->pmf : 0.0f;
    L.emitterArea[i] = emitter ? emitter->area : 0.0f;
    L.emissive[i] = k.emissive;
    L.twoSided[i] = k.twoSided;
    L.absorber[i] = k.absorber;
    return true;
}

void PathTracer::shadeLanes(lambert::Lanes& L, const int* active) const {
    int kernelLanes = 0;
    for (int i = 0; i < kPacketSize; ++i) {
        L.in[i] = 0;
        L.shadowActive[i] = 0;
        L.stop[i] = 1;
        if (!active[i] || L.geomId[i] == RTC_INVALID_GEOMETRY_ID) continue;
        if (m_settings.vectorized && loadKernelLane(L, i)) {
            ++kernelLanes;
            continue;
        }
        PathState path = laneState(L, i);
        ShadowRay shadow;
        const HitRecord hit{L.geomId[i], L.primId[i], L.u[i], L.v[i], L.t[i]};
        L.stop[i] = scatter(path, hit, shadow) == Step::Stop;
        setLaneState(L, i, path);
        L.shadowActive[i] = shadow.active;
        if (!shadow.active) continue;
        L.shadowOrigin.set(i, shadow.origin);
        L.shadowDirection.set(i, shadow.direction);
        L.shadowTMax[i] = shadow.tMax;
        L.shadowContribution.set(i, shadow.contribution);
    }
    if (kernelLanes == 0) return;
    lambert::hit(L, m_maxReflections, m_settings.indirectOnly);
    // Only while every light is dark (LightSampler::hasDarkTexturedLight): no light to sample.
    static const LightSampler::Entry kNoLight{LightSampler::Kind::Area};
    for (int i = 0; i < kPacketSize; ++i) {
        if (!L.in[i] || L.stop[i]) continue;
        if (m_lights.empty()) L.wantLight[i] = 0;
        const LightSampler::Entry& e = m_lights.empty() ? kNoLight : m_lights.choose(L.uSelect[i]);
        // A textured rectangle: the kernel samples (u1, u2) uniformly, so hand it the texel-distributed
        // point's numbers, with that texel's radiance and pmf (what LightSampler::sample uses).
        glm::vec3 emitted;
        float pmf;
        LightSampler::textureSample(e, L.uLight1[i], L.uLight2[i], emitted, pmf);
        L.lightCorner.set(i, e.position);
        L.lightEdge1.set(i, e.edge1);
        L.lightEdge2.set(i, e.edge2);
        L.lightNormal.set(i, e.normal);
        L.lightEmitted.set(i, emitted);
        L.lightArea[i] = e.area;
        L.lightPmf[i] = pmf;
        L.lightCosCutoff[i] = e.cosCutoff;
        L.lightExponent[i] = e.exponent;
        L.lightKind[i] = static_cast<int32_t>(e.kind);
        L.lightTwoSided[i] = e.twoSided;
    }
    lambert::reflect(L, kRouletteStartReflections);
}

namespace {

template <class T>
void copyLanes(T* to, const T (&from)[kLanesOfPacket]) {
    std::memcpy(to, from, sizeof from);
}

}  // namespace

void PathTracer::renderTile(int x0, int y0, int x1, int y1, uint32_t s0, uint32_t s1, PixelSums* sums,
                            Counters& counters) const {
    const FlushDenormals flushDenormals;
    const auto width = static_cast<size_t>(m_settings.width);
    RTCIntersectContext incoherent, coherent;
    rtcInitIntersectContext(&incoherent);
    rtcInitIntersectContext(&coherent);
    coherent.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int rayValid[kPacketSize];  // Embree requires the masks to be 64-byte aligned
    alignas(64) int shadowValid[kPacketSize];
    alignas(64) RTCRayHit16 packet;
    alignas(64) RTCRay16 shadowPacket;
    std::array<size_t, kPacketSize> pixels;
    auto lanesStorage = std::make_unique<lambert::Lanes>();  // 9 KB: off the stack, zeroed once
    lambert::Lanes& L = *lanesStorage;
    // The fields of the packets that never change.
    for (int lane = 0; lane < kPacketSize; ++lane) {
        packet.ray.tnear[lane] = 0.0f;
        packet.ray.time[lane] = 0.0f;
        packet.ray.mask[lane] = 0xffffffffu;
        packet.ray.id[lane] = 0;
        packet.ray.flags[lane] = 0;
        shadowPacket.tnear[lane] = 0.0f;
        shadowPacket.time[lane] = 0.0f;
        shadowPacket.mask[lane] = 0xffffffffu;
        shadowPacket.id[lane] = 0;
        shadowPacket.flags[lane] = 0;
    }

    // The tile's paths, sample by sample and row by row within a sample, are a queue that 16 lanes
    // work through: each step sends every lane's ray to Embree as one packet and shades the lanes
    // together, and a lane whose path ends takes the next path of the queue at once, so the packet
    // stays full until the tile's last paths. A pixel's samples finish in an order fixed by the
    // tile alone, so the sums are bit-identical for any thread count.
    // The queue's head: sample `headSample` of pixel (headX, headY).
    uint32_t headSample = s0;
    int headX = x0, headY = y0;
    const auto startPath = [&](int lane) {
        if (headSample == s1) return false;
        pixels[lane] = static_cast<size_t>(headY) * width + static_cast<size_t>(headX);
        Rng rng(m_settings.seed, pixels[lane], headSample);
        const float jx = rng.next(), jy = rng.next();
        const CameraRay r = m_camera.generate(static_cast<float>(headX) + jx, static_cast<float>(headY) + jy);
        PathState path;
        path.rng = rng;
        path.origin = r.origin;
        path.direction = r.direction;
        path.tMax = r.tMax;
        setLaneState(L, lane, path);
        if (++headX == x1) {
            headX = x0;
            if (++headY == y1) {
                headY = y0;
                ++headSample;
            }
        }
        return true;
    };
    int live = 0;
    for (int lane = 0; lane < kPacketSize; ++lane) {
        const bool started = startPath(lane);
        rayValid[lane] = started ? -1 : 0;
        live += started ? 1 : 0;
    }
    // The tile's first camera rays, and the shadow rays of their first reflections, start together
    // and head the same way: Embree traces such packets faster when told. After that the lanes'
    // paths are out of step.
    for (bool first = true; live > 0; first = false) {
        RTCIntersectContext* context = first ? &coherent : &incoherent;
        copyLanes(packet.ray.org_x, L.origin.x);
        copyLanes(packet.ray.org_y, L.origin.y);
        copyLanes(packet.ray.org_z, L.origin.z);
        copyLanes(packet.ray.dir_x, L.direction.x);
        copyLanes(packet.ray.dir_y, L.direction.y);
        copyLanes(packet.ray.dir_z, L.direction.z);
        copyLanes(packet.ray.tfar, L.tMax);
        for (int lane = 0; lane < kPacketSize; ++lane) {
            packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(rayValid, m_embree.handle(), context, &packet);
        copyLanes(L.geomId, packet.hit.geomID);
        copyLanes(L.primId, packet.hit.primID);
        copyLanes(L.u, packet.hit.u);
        copyLanes(L.v, packet.hit.v);
        copyLanes(L.t, packet.ray.tfar);
        counters.rays += static_cast<uint64_t>(live);

        shadeLanes(L, rayValid);

        int shadowLanes = 0;
        for (int lane = 0; lane < kPacketSize; ++lane) {
            shadowValid[lane] = L.shadowActive[lane] ? -1 : 0;
            shadowLanes += L.shadowActive[lane];
        }
        if (shadowLanes > 0) {
            copyLanes(shadowPacket.org_x, L.shadowOrigin.x);
            copyLanes(shadowPacket.org_y, L.shadowOrigin.y);
            copyLanes(shadowPacket.org_z, L.shadowOrigin.z);
            copyLanes(shadowPacket.dir_x, L.shadowDirection.x);
            copyLanes(shadowPacket.dir_y, L.shadowDirection.y);
            copyLanes(shadowPacket.dir_z, L.shadowDirection.z);
            copyLanes(shadowPacket.tfar, L.shadowTMax);
            rtcOccluded16(shadowValid, m_embree.handle(), context, &shadowPacket);
            counters.rays += static_cast<uint64_t>(shadowLanes);
            counters.shadowRays += static_cast<uint64_t>(shadowLanes);
            for (int lane = 0; lane < kPacketSize; ++lane)
                if (shadowValid[lane] && shadowPacket.tfar[lane] >= 0.0f)
                    L.radiance.set(lane, L.radiance.at(lane) + L.shadowContribution.at(lane));
        }

        for (int lane = 0; lane < kPacketSize; ++lane) {
            if (!rayValid[lane] || !L.stop[lane]) continue;
            glm::vec3 radiance = L.radiance.at(lane);
            if (!finite(radiance)) {
                ++counters.invalidSamples;
                radiance = glm::vec3(0.0f);
            }
            PixelSums& p = sums[pixels[lane]];
            const double y = luminance(radiance);
            p.radiance += glm::dvec3(radiance);
            p.radiance2 += glm::dvec3(radiance) * glm::dvec3(radiance);
            p.lum += y;
            p.lum2 += y * y;
            if (!startPath(lane)) {
                rayValid[lane] = 0;
                --live;
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
    result.variance = Image(width, height);
    const double n = static_cast<double>(done);
    double relSum = 0.0, varOfMeanSum = 0.0, meanSum = 0.0;
    uint64_t measured = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const PixelSums& p = sums[i];
        result.radiance.data()[i] = glm::vec3(p.radiance / n);
        if (done > 1) {
            // Per channel, the unbiased sample variance over n, i.e. the variance of the pixel's mean.
            const glm::dvec3 m = p.radiance / n;
            result.variance.data()[i] = glm::vec3(glm::max(glm::dvec3(0.0), (p.radiance2 - n * m * m) / (n - 1.0)) / n);
        }
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
