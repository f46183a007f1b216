#include "techniques/photon_splat/PhotonInjection.h"

#include "core/Image.h"
#include "reference/Rng.h"
#include "reference/Sampling.h"
#include "reference/TextureLookup.h"
#include "scene/AreaTexture.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace bounce::photonsplat {

namespace {

constexpr float kPi = glm::pi<float>();

glm::vec3 uniformSphere(float u1, float u2) {
    const float z = 1.0f - 2.0f * u1;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// The rectangle, across a directional light's direction d, that holds the scene's box [lo, hi] as
// the light sees it: offsets (t, b) from the box centre along Frame(d)'s t and b axes.
struct SunRectangle {
    glm::vec2 min{0.0f}, max{0.0f};
    float area() const { return (max.x - min.x) * (max.y - min.y); }
};
SunRectangle sunRectangle(glm::vec3 d, glm::vec3 lo, glm::vec3 hi) {
    const Frame f(d);
    const glm::vec3 centre = 0.5f * (lo + hi);
    SunRectangle r{glm::vec2(std::numeric_limits<float>::infinity()), glm::vec2(-std::numeric_limits<float>::infinity())};
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 c((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
        const glm::vec2 q(glm::dot(c - centre, f.t), glm::dot(c - centre, f.b));
        r.min = glm::min(r.min, q);
        r.max = glm::max(r.max, q);
    }
    return r;
}

// Flux a light sends into the scene (W per channel). Directional lights: the irradiance through the
// rectangle that holds the scene's box as the light sees it. A textured area light: times its
// texture's mean now.
glm::vec3 emittedFlux(const Scene& scene, const Light& l, glm::vec3 lo, glm::vec3 hi, float time) {
    if (l.type == LightType::Directional) return l.irradiance * sunRectangle(glm::normalize(l.direction), lo, hi).area();
    if (l.type == LightType::Area) return l.flux() * areaTextureMean(scene, l, time);
    return l.flux();
}

struct Emission {
    glm::vec3 origin, direction, power;
};

// The texel of a textured area light at (u, v) (nearest, as the reference reads it: column from u,
// row 0 at v = 1; EmitterTexture::texelAt).
glm::vec3 areaTexel(const Image& image, float u, float v) {
    const int c = std::clamp(static_cast<int>(u * static_cast<float>(image.width())), 0, image.width() - 1);
    const int r = std::clamp(static_cast<int>((1.0f - v) * static_cast<float>(image.height())), 0, image.height() - 1);
    return image.at(c, r);
}

// One emitted photon of light l with random numbers from `rng`; the photon carries the light's flux
// `flux` divided by the n photons it shoots (an estimate whose sum over the n is the flux).
Emission emit(const Light& l, Rng& rng, glm::vec3 lo, glm::vec3 hi, glm::vec3 flux, uint32_t n, const Image* texture) {
    const float u[4] = {rng.next(), rng.next(), rng.next(), rng.next()};
    Emission e{l.position, glm::vec3(0.0f, -1.0f, 0.0f), flux / static_cast<float>(n)};
    switch (l.type) {
        case LightType::Point: e.direction = uniformSphere(u[0], u[1]); break;
        case LightType::Spot: {
            // Uniform in the cone's solid angle, power weighted by cos^n (the sum estimates Light::flux()).
            const float cutoff = std::min(l.cutoffAngle, kPi / 2.0f);
            const float cosC = std::cos(cutoff);
            const float cosA = 1.0f - u[0] * (1.0f - cosC);
            const float sinA = std::sqrt(std::max(0.0f, 1.0f - cosA * cosA));
            const float phi = 2.0f * kPi * u[1];
            const Frame f(glm::normalize(l.direction));
            e.direction = f.toWorld({sinA * std::cos(phi), sinA * std::sin(phi), cosA});
            // Uniform over the cone's solid angle: each photon carries I(alpha) * solid / n, whose sum
            // estimates Light::flux() (the cos^n integral).
            const float solid = 2.0f * kPi * (1.0f - cosC);
            e.power = l.intensity * std::pow(cosA, l.falloffExponent) * solid / static_cast<float>(n);
            break;
        }
        case LightType::Directional: {
            // Uniform over the rectangle that holds the scene's box, starting outside the box.
            const glm::vec3 d = glm::normalize(l.direction);
            const Frame f(d);
            const SunRectangle r = sunRectangle(d, lo, hi);
            const glm::vec2 q = glm::mix(r.min, r.max, glm::vec2(u[0], u[1]));
            e.origin = 0.5f * (lo + hi) - d * glm::length(hi - lo) + q.x * f.t + q.y * f.b;
            e.direction = d;
            break;
        }
        case LightType::Area: {
            // Uniform point, cosine direction about the emitting side: power pi L A / n per side (times
            // the texel there for a textured light: uniform points weighted by the texture estimate
            // pi A mean(L texel), the flux emittedFlux() splits photons by). A two-sided light picks a
            // side at random; its back shows the texture mirrored in u (Scene.h).
            const bool back = l.twoSided && rng.next() < 0.5f;
            e.origin = l.position + (u[0] - 0.5f) * l.edgeU + (u[1] - 0.5f) * l.edgeV;
            const Frame f(back ? -l.areaNormal() : l.areaNormal());
            e.direction = f.toWorld(cosineHemisphere(u[2], u[3]));
            const glm::vec3 base = l.radiance * (kPi * l.area() * (l.twoSided ? 2.0f : 1.0f)) / static_cast<float>(n);
            e.power = texture ? base * areaTexel(*texture, back ? 1.0f - u[0] : u[0], u[1]) : base;
            break;
        }
    }
    return e;
}

// The triangles of an object whose material emits (Material::emission, W/(m^2 sr)), in world space at
// one time, with the cumulative areas that pick one uniformly by area.
struct EmissiveObject {
    const Object* object = nullptr;
    const Material* material = nullptr;
    std::vector<glm::vec3> corners;  // 3 per triangle, world space
    std::vector<glm::vec2> uvs;      // 3 per triangle (zero without mesh uvs)
    std::vector<double> cdf;         // cumulative world areas, m^2
    glm::vec3 flux{0.0f};            // estimate used to split photons: sides pi A Le times the texture's mean
};

std::vector<EmissiveObject> emissiveObjects(const Scene& scene, float time) {
    std::vector<EmissiveObject> out;
    for (const Object& o : scene.objects) {
        const Material& m = scene.materials[o.material];
        if (!(maxComponent(m.emission) > 0.0f)) continue;
        const Mesh& mesh = scene.meshes[o.mesh];
        const glm::mat4 world = o.worldFromObject(time);
        EmissiveObject e;
        e.object = &o;
        e.material = &m;
        double area = 0.0;
        for (size_t t = 0; t < mesh.triangleCount(); ++t)
            for (int k = 0; k < 3; ++k) {
                const uint32_t i = mesh.indices[3 * t + static_cast<size_t>(k)];
                e.corners.push_back(glm::vec3(world * glm::vec4(mesh.positions[i], 1.0f)));
                e.uvs.push_back(i < mesh.uvs.size() ? mesh.uvs[i] : glm::vec2(0.0f));
                if (k == 2) {
                    const size_t c = e.corners.size() - 3;
                    area += 0.5 * glm::length(glm::cross(e.corners[c + 1] - e.corners[c], e.corners[c + 2] - e.corners[c]));
                    e.cdf.push_back(area);
                }
            }
        if (!(area > 0.0)) continue;
        const glm::vec3 mean = m.emissionTexture >= 0 ? imageMean(scene.textures[static_cast<size_t>(m.emissionTexture)].image) : glm::vec3(1.0f);
        e.flux = m.emission * mean * static_cast<float>(kPi * area * (m.twoSided ? 2.0 : 1.0));
        out.push_back(std::move(e));
    }
    return out;
}

// One photon of an emissive object: a triangle by area, a uniform point on it, a cosine direction
// about its front (a random side when two-sided); power sides pi A Le texel(uv) / n (A the object's
// area), so the n photons' sum estimates the object's flux.
Emission emitFromObject(const Scene& scene, const EmissiveObject& e, Rng& rng, uint32_t n) {
    const double total = e.cdf.back();
    const double pick = static_cast<double>(rng.next()) * total;
    const size_t t = std::min<size_t>(static_cast<size_t>(std::upper_bound(e.cdf.begin(), e.cdf.end(), pick) - e.cdf.begin()), e.cdf.size() - 1);
    const glm::vec2 b = uniformTriangle(rng.next(), rng.next());
    const glm::vec3 a = e.corners[3 * t], p1 = e.corners[3 * t + 1], p2 = e.corners[3 * t + 2];
    glm::vec3 normal = glm::normalize(glm::cross(p1 - a, p2 - a));
    const bool twoSided = e.material->twoSided;
    if (twoSided && rng.next() < 0.5f) normal = -normal;
    Emission out;
    out.origin = a + b.x * (p1 - a) + b.y * (p2 - a);
    const Frame f(normal);
    out.direction = f.toWorld(cosineHemisphere(rng.next(), rng.next()));
    out.origin = offsetRayOrigin(out.origin, normal);
    glm::vec3 le = e.material->emission;
    if (e.material->emissionTexture >= 0) {
        const glm::vec2 uv = e.uvs[3 * t] + b.x * (e.uvs[3 * t + 1] - e.uvs[3 * t]) + b.y * (e.uvs[3 * t + 2] - e.uvs[3 * t]);
        le *= lookupBilinearRepeat(scene.textures[static_cast<size_t>(e.material->emissionTexture)].image, uv);
    }
    out.power = le * static_cast<float>(kPi * total * (twoSided ? 2.0 : 1.0)) / static_cast<float>(n);
    return out;
}

glm::vec3 albedoAt(const Scene& scene, const RayHit& hit) {
    const Material& m = scene.materials[hit.materialIndex];
    glm::vec3 a = m.baseColor;
    if (m.baseColorTexture >= 0) a *= lookupBilinearRepeat(scene.textures[static_cast<size_t>(m.baseColorTexture)].image, hit.uv);
    return a * (1.0f - m.metallic);
}

}  // namespace

void injectPhotons(const Scene& scene, float time, const RayCaster& caster, const InjectionSettings& settings, std::vector<Photon>& out) {
    out.clear();
    glm::vec3 lo, hi;
    scene.bounds(time, lo, hi);
    // Emitters at time t (the lights, then the objects whose material emits), photons split over them
    // by flux (luminance).
    std::vector<Light> lights;
    for (const Light& l : scene.lights) lights.push_back(l.at(time));
    const std::vector<EmissiveObject> objects = emissiveObjects(scene, time);
    std::vector<Image> scratch(lights.size());
    std::vector<const Image*> textures;
    std::vector<float> weight;
    for (size_t li = 0; li < lights.size(); ++li) {
        textures.push_back(lights[li].type == LightType::Area ? areaTextureAt(scene, lights[li], time, scratch[li]) : nullptr);
        weight.push_back(std::max(luminance(emittedFlux(scene, lights[li], lo, hi, time)), 0.0f));
    }
    for (const EmissiveObject& e : objects) weight.push_back(std::max(luminance(e.flux), 0.0f));
    const float total = std::accumulate(weight.begin(), weight.end(), 0.0f);
    if (!(total > 0.0f) || settings.photons == 0) return;
    for (size_t ei = 0; ei < weight.size(); ++ei) {
        const uint32_t n = static_cast<uint32_t>(std::lround(settings.photons * weight[ei] / total));
        if (n == 0) continue;
        for (uint32_t i = 0; i < n; ++i) {
            Rng rng(settings.seed, ei, i);
            const Emission e = ei < lights.size()
                                   ? emit(lights[ei], rng, lo, hi, emittedFlux(scene, lights[ei], lo, hi, time), n, textures[ei])
                                   : emitFromObject(scene, objects[ei - lights.size()], rng, n);
            glm::vec3 origin = e.origin, dir = e.direction, power = e.power;
            if (!(maxComponent(power) > 0.0f)) continue;  // a black texel
            for (uint32_t b = 0; b < settings.bounces; ++b) {
                const std::optional<RayHit> hit = caster.closestHit(origin, dir);
                if (!hit) break;
                const Material& m = scene.materials[hit->materialIndex];
                // Light reaches a one-sided surface's back only to be absorbed (docs/scene.md).
                if (!hit->frontFacing && !m.twoSided) break;
                const glm::vec3 shading = hit->frontFacing ? hit->shadingNormal : -hit->shadingNormal;
                const glm::vec3 ng = hit->frontFacing ? hit->geometricNormal : -hit->geometricNormal;
                power *= albedoAt(scene, *hit);
                if (maxComponent(power) <= 0.0f) break;
                const Frame f(shading);
                glm::vec3 next = f.toWorld(cosineHemisphere(rng.next(), rng.next()));
                if (glm::dot(next, ng) <= 0.0f) next = glm::reflect(next, ng);  // shading normal past the face
                out.push_back(Photon{hit->position, power, next, ng});
                origin = offsetRayOrigin(hit->position, ng);
                dir = next;
            }
        }
    }
}

std::vector<Photon> stratify(const std::vector<Photon>& photons, glm::vec3 lo, glm::vec3 hi, int gridSize, int threshold,
                             uint64_t seed, StratifyStats* stats) {
    const int g = std::max(gridSize, 2) & ~1;  // whole 2x2x2 blocks
    const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-6f));
    std::vector<Photon> out;
    // The grid: one entry per photon inside it, sorted so that each 2x2x2 block's photons are
    // contiguous, and within a block each cell's (the thesis indexes its array by grid cell; bounce
    // sorts, so the grid takes memory per photon, not per cell).
    struct Entry {
        uint64_t key;  // block index * 8 + cell within the block
        uint32_t photon;
    };
    std::vector<Entry> grid;
    grid.reserve(photons.size());
    const uint64_t blocksPerSide = static_cast<uint64_t>(g / 2);
    for (uint32_t i = 0; i < photons.size(); ++i) {
        const glm::vec3 p = photons[i].position;
        if (!glm::all(glm::greaterThanEqual(p, lo)) || !glm::all(glm::lessThanEqual(p, hi))) {
            out.push_back(photons[i]);  // outside the grid: kept (the thesis ignores or cascades them)
            continue;
        }
        // The grid is closed: a photon on its upper faces (a ceiling on the scene's bounds) is in the last cell.
        const glm::ivec3 c = glm::min(glm::ivec3(glm::floor((p - lo) / extent * static_cast<float>(g))), glm::ivec3(g - 1));
        const glm::uvec3 b(c / 2), k(c % 2);
        const uint64_t block = b.x + blocksPerSide * (b.y + blocksPerSide * static_cast<uint64_t>(b.z));
        grid.push_back({block * 8 + (k.x + 2 * k.y + 4 * k.z), i});
    }
    std::sort(grid.begin(), grid.end(), [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.photon < b.photon; });
    size_t merged = 0;
    auto combine = [&](size_t first, size_t last, uint64_t key) {
        Rng rng(seed, key, last - first);
        const size_t pick = first + std::min(last - first - 1, static_cast<size_t>(rng.next() * static_cast<float>(last - first)));
        Photon p = photons[grid[pick].photon];
        p.power = glm::vec3(0.0f);
        for (size_t e = first; e < last; ++e) p.power += photons[grid[e].photon].power;
        out.push_back(p);
    };
    for (size_t first = 0; first < grid.size();) {
        const uint64_t block = grid[first].key / 8;
        size_t last = first;
        int count[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        while (last < grid.size() && grid[last].key / 8 == block) ++count[grid[last++].key % 8];
        // §4.2: "If one of those cells contains less photons than the threshold parameter, the colors
        // of all 8 cells are combined": an empty cell holds 0 photons, so it counts.
        const bool sparse = std::any_of(count, count + 8, [&](int n) { return n < threshold; });
        if (sparse) {
            combine(first, last, block * 8);
            ++merged;
        } else {
            for (size_t cell = first; cell < last;) {
                size_t end = cell;
                while (end < last && grid[end].key == grid[cell].key) ++end;
                combine(cell, end, grid[cell].key + 1);
                cell = end;
            }
        }
        first = last;
    }
    if (stats) {
        stats->inputPhotons = photons.size();
        stats->outputPhotons = out.size();
        stats->mergedBlocks = merged;
        stats->gridBytes = grid.capacity() * sizeof(Entry);
    }
    return out;
}

void bundleAxes(glm::vec3 w, glm::vec3& right, glm::vec3& up) {
    const glm::vec3 helper = std::abs(w.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    right = glm::normalize(glm::cross(helper, w));
    up = glm::cross(w, right);
}

void placeBundles(const std::vector<Photon>& photons, const RayCaster& caster, const BundleSettings& settings, std::vector<Bundle>& out,
                  BundleScratch& scratch) {
    std::vector<CastRay>& rays = scratch.rays;
    rays.resize(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) {
        rays[i].origin = offsetRayOrigin(photons[i].position, photons[i].normal);
        rays[i].direction = photons[i].direction;
        rays[i].tMax = settings.maxDistance;
    }
    std::vector<std::optional<RayHit>>& hits = scratch.hits;
    hits.assign(photons.size(), std::nullopt);
    caster.closestHits(rays, hits);
    out.clear();
    const bool keepEscaped = glm::all(glm::lessThanEqual(settings.lo, settings.hi));
    for (size_t i = 0; i < photons.size(); ++i) {
        Bundle b;
        b.direction = photons[i].direction;
        bundleAxes(b.direction, b.right, b.up);
        b.power = photons[i].power;
        b.photon = static_cast<uint32_t>(i);
        if (hits[i]) {
            b.hitDistance = hits[i]->t;
            b.hitNormal = hits[i]->frontFacing ? hits[i]->geometricNormal : -hits[i]->geometricNormal;
        } else {
            if (!keepEscaped) continue;
            // Where the ray leaves the box (slab test; the photon lies inside it).
            float exit = std::numeric_limits<float>::infinity();
            for (int k = 0; k < 3; ++k)
                if (b.direction[k] != 0.0f)
                    exit = std::min(exit, ((b.direction[k] > 0.0f ? settings.hi[k] : settings.lo[k]) - photons[i].position[k]) / b.direction[k]);
            if (!(exit > 0.0f) || !std::isfinite(exit)) continue;
            b.hitDistance = exit;
            b.hitNormal = -b.direction;
            b.escaped = true;
        }
        const float back = b.escaped ? b.hitDistance : std::min(settings.stepBack, b.hitDistance);  // C never behind P
        b.origin = photons[i].position + (b.hitDistance - back) * b.direction;
        out.push_back(b);
    }
}

}  // namespace bounce::photonsplat
