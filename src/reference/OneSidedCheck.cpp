#include "reference/OneSidedCheck.h"

#include "reference/CameraRays.h"
#include "reference/RayCaster.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace bounce {

namespace {

constexpr const char* kAdvice = "reverse its winding or set \"twoSided\": true on its material";

// The light is strictly in front of the plane through `p` with unit normal `n`: by more than a
// millionth of the scene's size, so a surface in the light's own plane (a ceiling around a panel)
// counts as facing away.
bool inFront(const Light& l, glm::vec3 p, glm::vec3 n, float epsilon) {
    switch (l.type) {
        case LightType::Directional: return glm::dot(n, -l.direction) > 1e-6f;
        case LightType::Area:
            for (float u : {-0.5f, 0.5f})
                for (float v : {-0.5f, 0.5f})
                    if (glm::dot(n, l.position + u * l.edgeU + v * l.edgeV - p) > epsilon) return true;
            return false;
        default: return glm::dot(n, l.position - p) > epsilon;
    }
}

}  // namespace

std::vector<std::string> checkOneSidedSurfaces(const Scene& scene, glm::ivec2 size, uint32_t frame,
                                               const OneSidedCheckOptions& options) {
    std::vector<std::string> messages;
    const auto oneSided = [&](const Object& o) {
        const Material& m = scene.materials[o.material];
        return !m.twoSided && glm::dot(m.emission, m.emission) == 0.0f;
    };
    if (std::none_of(scene.objects.begin(), scene.objects.end(), oneSided)) return messages;
    const float t = scene.timeOfFrame(frame);
    const std::string& file = scene.source.empty() ? scene.name : scene.source;

    // Seen from behind: the first hit of a grid of camera rays.
    std::vector<size_t> backHits(scene.objects.size(), 0);
    size_t rays = 0;
    if (auto caster = RayCaster::create(scene, t, GeometryFilter::All); caster.ok()) {
        const int w = std::max(1, options.raysAcross);
        const int h = std::max(1, static_cast<int>(std::lround(w * static_cast<double>(size.y) / std::max(1, size.x))));
        const CameraRays camera(scene.camera.at(t), w, h);
        std::vector<CastRay> batch;
        batch.reserve(static_cast<size_t>(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const CameraRay r = camera.generate(x + 0.5f, y + 0.5f);
                batch.push_back({r.origin, r.direction, 0.0f, r.tMax});
            }
        std::vector<std::optional<RayHit>> hits(batch.size());
        caster->closestHits(batch, hits);
        rays = batch.size();
        for (const auto& hit : hits)
            if (hit && !hit->frontFacing) ++backHits[hit->objectIndex];
    }
    glm::vec3 lo, hi;
    scene.bounds(t, lo, hi);
    const float epsilon = 1e-6f * std::max(1e-3f, glm::length(hi - lo));
    std::vector<Light> lights;
    for (const Light& l : scene.lights) lights.push_back(l.at(t));

    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Object& o = scene.objects[i];
        if (!oneSided(o)) continue;
        const double share = rays > 0 ? static_cast<double>(backHits[i]) / static_cast<double>(rays) : 0.0;
        if (share >= options.backFacingImageShare)
            messages.push_back(fmt::format("{}: object '{}' is one-sided and seen from behind over {:.0f}% of the image at "
                                           "frame {}: renderers show what lies behind it; {}",
                                           file, o.name, 100.0 * share, frame, kAdvice));
        if (lights.empty()) continue;
        const Mesh& mesh = scene.meshes[o.mesh];
        const glm::mat4 world = o.worldFromObject(t);
        bool lit = false;
        for (size_t k = 0; k + 2 < mesh.indices.size() && !lit; k += 3) {
            const glm::vec3 a = glm::vec3(world * glm::vec4(mesh.positions[mesh.indices[k]], 1.0f));
            const glm::vec3 b = glm::vec3(world * glm::vec4(mesh.positions[mesh.indices[k + 1]], 1.0f));
            const glm::vec3 c = glm::vec3(world * glm::vec4(mesh.positions[mesh.indices[k + 2]], 1.0f));
            const glm::vec3 cr = glm::cross(b - a, c - a);
            const float len = glm::length(cr);
            if (!(len > 0.0f)) continue;
            const glm::vec3 n = cr / len, centre = (a + b + c) / 3.0f;
            for (const Light& l : lights) lit |= inFront(l, centre, n, epsilon);
        }
        if (!lit)
            messages.push_back(fmt::format("{}: object '{}' is one-sided and every light is behind it or in its plane at "
                                           "frame {}: it receives no direct light; {}",
                                           file, o.name, frame, kAdvice));
    }
    return messages;
}

}  // namespace bounce
