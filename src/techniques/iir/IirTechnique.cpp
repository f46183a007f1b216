// Incremental instant radiosity — Laine, Saransaari, Kontkanen, Lehtinen, Aila, "Incremental Instant
// Radiosity for Real-Time Indirect Illumination", EGSR 2007.
//
// Per frame, in the paper's order (§3):
//   1-4 (CPU) VplDistribution: validity of the carried-over VPLs by a shadow ray against the static
//       scene and the spot-cone test; deletion by the shortest-Delaunay-edge rule until recalcMin
//       slots are free; insertion at the largest empty circle, one ray each, up to recalcMax; cell
//       areas as intensities. Rays come from an Embree RayCaster over the static geometry, built once
//       (bounce's static geometry never changes).
//   3b  "sm-rendering": a paraboloid shadow map (256², 16-bit depth) per NEW VPL, one layer of a 2D
//       array indexed by the VPL's slot, static geometry only (techniques/paraboloid/ParaboloidMaps.h).
//   5   the camera G-buffer (shared Pipeline pass).
//   6   "split": positions and normals into an n×m atlas of interleaved sub-images (§5.1).
//   7   "accum": per atlas pixel, irradiance from the VPLs of its tile, with paraboloid shadow
//       lookups and the per-VPL irradiance clamp (no receiver albedo). VPLs are dealt to tiles in
//       creation order (§7) and keep their tile while they live (TileAssignment), so replacing a few
//       VPLs does not shift the interleaving pattern of the others.
//   8   "combine": the inverse of the split.
//   9   "filter": the geometry-aware filter (Fig. 5's thresholds; by default over a (2n-1)×(2m-1) tent
//       instead of the n×m box, which left stair-steps of period n: docs), then the receiver's albedo/π.
//
// Equations. A VPL i at a diffuse hit of albedo ρ_i receiving flux Φ_i is a cosine emitter of
// intensity I_i(θ) = ρ_i Φ_i cosθ / π. A receiver x with normal n_x gets
//   E(x) = Σ_i min(I_i(0) cosθ_i cosθ_x / d_i², I_i(0) / d_c²) · V_i(x),
// (d_c: clampDistance × scene diagonal) and reflects L = ρ_x (1 − metallic) E / π. Φ_i = Φ · A_i / π
// (disc) or Φ · A_i / 4π (sphere), A_i the Voronoi cell area — the flux of the light's directions in
// the cell; with paperNormalisation the paper's Φ · A_i / Σ_VPL A_j.
//
// Deviations (docs/techniques/iir.md gives each its reason):
// - rays that escape keep a Miss sample carrying their cell's flux.
// - the first frame fills the budget (the paper does not say how it starts).
// - paraboloid depth is the exact ray-plane distance per fragment, not interpolated from vertices.
// - area and directional primary lights become point emitters.
// - VPL management overlaps only the GPU work already queued this frame (no one-frame delay).
// - G-buffer atlases are 32-bit float.
// - the filter's kernel is a tent over (2n-1)×(2m-1) taps by default (filter=box: the paper's n×m box).
#include "techniques/iir/IirTechnique.h"

#include "scene/AreaTexture.h"

#include "core/Check.h"
#include "core/Log.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace bounce {

namespace {

// A directional light becomes a spot this many scene diagonals away, aimed at the scene's centre, whose
// cone just covers the scene's bounding sphere: its rays are parallel to within radius/distance
// (0.5/100 rad) and its irradiance varies by (1 ± 0.01)² across the scene.
constexpr float kDirectionalDistanceInDiagonals = 100.0f;
// Rays leave the light and VPLs sit this fraction of the scene diagonal off their surface, so that a
// light on a ceiling (area light) or a VPL on a wall does not hit its own surface (float rounding of
// positions is ~1e-7 relative).
constexpr float kSurfaceOffsetInDiagonals = 1e-3f;
// Paraboloid depth range, in scene diagonals: no two static points are farther apart than the
// diagonal; 1 % more keeps the farthest surfaces off the clamped end of the 16-bit range.
constexpr float kShadowFarInDiagonals = 1.01f;

struct VplGpu {
    glm::vec4 position;   // xyz: world, w: shadow-map layer
    glm::vec4 normal;     // xyz: unit normal (paraboloid +z)
    glm::vec4 tangent;    // xyz: paraboloid +x
    glm::vec4 intensity;  // rgb: I_i(0) = ρ_i Φ_i / π, W/sr
};
static_assert(sizeof(VplGpu) == 64);

glm::vec3 anyTangent(glm::vec3 n) {
    const glm::vec3 helper = std::abs(n.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    return glm::normalize(glm::cross(helper, n));
}

double millisecondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void IirTechnique::visitSettings(SettingsVisitor& v) {
    v.field("maxLights", m_maxLights, "maxLights: VPL slots (paper: 256; 1024 tested)", 1, 2048);
    v.field("recalcMin", m_recalcMin, "recalcMin: slots freed per frame (paper: 4)", 0, 2048);
    v.field("recalcMax", m_recalcMax, "recalcMax: new VPLs per frame at most (paper: 8)", 1, 2048);
    v.field("incremental", m_incremental,
            "false: the paper's comparison method, all VPLs and shadow maps regenerated every frame");
    v.field("shadowMapSize", m_shadowMapSize, "paraboloid shadow map size per side, texels (paper: 256)", 16, 2048);
    v.field("tilesX", m_tilesX, "interleaved-sampling tiles n across (paper: 4)", 1, 16);
    v.field("tilesY", m_tilesY, "interleaved-sampling tiles m down (paper: 4)", 1, 16);
    v.field("filter", m_filterKernel,
            "geometry-aware filter kernel: tent = (2n-1) x (2m-1) taps weighted (n-|x|)(m-|y|), each VPL subset "
            "interpolated linearly (no stair-steps; docs); box = the paper's n x m box (Fig. 5)",
            kFilters);
    v.field("normalThreshold", m_normalThreshold, "filter beta: minimum normal dot product (paper: 0.8)", -1.0f, 1.0f);
    v.field("positionThreshold", m_positionThreshold,
            "filter alpha: maximum position distance, fraction of the scene diagonal (paper: scene-dependent, none given)",
            0.0f, 10.0f);
    v.field("clampDistance", m_clampDistance,
            "per-VPL irradiance clamp I(0)/d_c^2, d_c as a fraction of the scene diagonal (paper: a clamp, no value)",
            0.0f, 1.0f);
    v.field("shadowBias", m_shadowBias, "paraboloid shadow bias, fraction of the scene diagonal", 0.0f, 0.1f);
    v.field("paperNormalisation", m_paperNormalisation,
            "true: VPL flux = cell area / sum of VPL cell areas (the paper, escaping flux given to VPLs); "
            "false: cell area / domain area");
}

IirPrimaryLight IirTechnique::primaryLight(const Scene& scene, float time) {
    IirPrimaryLight p;
    if (scene.lights.empty()) return p;
    const Light light = scene.lights.front().at(time);
    p.emitter = light;
    glm::vec3 lo, hi;
    scene.bounds(0.0f, lo, hi);
    const float diagonal = std::max(glm::length(hi - lo), 1e-6f);
    switch (light.type) {
        case LightType::Point:
        case LightType::Spot:
            p.supported = true;
            break;
        case LightType::Area: {
            // A cosine spot at the centre (n = 1, cutoff 90°) with I0 = L·A, whose flux π·L·A equals the
            // rectangle's: the paper's "crude approximation" of §7 (rays from one point). A textured light
            // emits L times its texture's mean multiplier at this time (its pattern is lost with the rest
            // of the rectangle's extent; without the mean a mostly dark screen shot its peak radiance).
            p.emitter.type = LightType::Spot;
            p.emitter.direction = light.areaNormal();
            p.emitter.position = light.position + light.areaNormal() * (kSurfaceOffsetInDiagonals * diagonal);
            p.emitter.intensity = light.radiance * areaTextureMean(scene, scene.lights.front(), time) * light.area();
            p.emitter.falloffExponent = 1.0f;
            p.emitter.cutoffAngle = glm::half_pi<float>();
            p.supported = light.area() > 0.0f;
            break;
        }
        case LightType::Directional: {
            // A uniform (n = 0) spot far away whose cone covers the bounding sphere; I0 = E·D² gives
            // irradiance E at the scene's centre.
            const float distance = kDirectionalDistanceInDiagonals * diagonal;
            const glm::vec3 centre = 0.5f * (lo + hi);
            const glm::vec3 dir = glm::normalize(light.direction);
            p.emitter.type = LightType::Spot;
            p.emitter.direction = dir;
            p.emitter.position = centre - dir * distance;
            p.emitter.intensity = light.irradiance * distance * distance;
            p.emitter.falloffExponent = 0.0f;
            p.emitter.cutoffAngle = std::asin(std::min(0.5f * diagonal / distance, 1.0f));
            p.supported = true;
            break;
        }
    }
    p.flux = p.supported ? p.emitter.flux() : glm::vec3(0.0f);
    if (p.supported && light.type == LightType::Directional) {
        // Light::flux works in float, where 1 - cos(c) of a 0.005 rad cone keeps only ~2 digits:
        // 2*pi*(1 - cos c) = 4*pi*sin^2(c/2), in double.
        const double s = std::sin(0.5 * static_cast<double>(p.emitter.cutoffAngle));
        p.flux = glm::vec3(glm::dvec3(p.emitter.intensity) * (4.0 * glm::pi<double>() * s * s));
    }
    return p;
}

Expected<void> IirTechnique::setup(const SetupContext& ctx) {
    m_scene = &ctx.scene;
    glm::vec3 lo, hi;
    ctx.scene.bounds(0.0f, lo, hi);
    m_sceneDiagonal = std::max(glm::length(hi - lo), 1e-6f);

    BOUNCE_TRY(m_split, gl::Program::build({"iir.split", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                          {GL_FRAGMENT_SHADER, "techniques/iir/split.frag"}}}));
    BOUNCE_TRY(m_accumulate, gl::Program::build({"iir.accum", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                               {GL_FRAGMENT_SHADER, "techniques/iir/accumulate.frag"}}}));
    BOUNCE_TRY(m_combine, gl::Program::build({"iir.combine", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                              {GL_FRAGMENT_SHADER, "techniques/iir/combine.frag"}}}));
    BOUNCE_TRY(m_filter, gl::Program::build({"iir.filter", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                            {GL_FRAGMENT_SHADER, "techniques/iir/filter.frag"}}}));

    m_primary = primaryLight(ctx.scene, 0.0f);
    if (!m_primary.supported) {
        spdlog::warn("iir: scene '{}' has no light usable as a primary light; indirect light is 0", ctx.scene.name);
    } else {
        BOUNCE_TRY(const SamplingDomain domain, SamplingDomain::forLight(m_primary.emitter));
        VplDistributionParams params;
        params.maxLights = static_cast<uint32_t>(m_maxLights);
        if (m_incremental) {
            if (m_recalcMin > m_recalcMax || m_recalcMax > m_maxLights)
                return makeError("need recalcMin ({}) <= recalcMax ({}) <= maxLights ({})",
                                 m_recalcMin, m_recalcMax, m_maxLights);
            params.recalcMax = static_cast<uint32_t>(m_recalcMax);
            params.recalcMin = static_cast<uint32_t>(m_recalcMin);
        } else {
            // The comparison method: every slot freed and refilled every frame.
            params.recalcMin = params.recalcMax = params.maxLights;
        }
        if (auto valid = params.validate(); !valid) return makeError("{}", valid.error().message);
        m_distribution.emplace(domain, params);
        BOUNCE_TRY(m_rayCaster, RayCaster::create(ctx.scene, 0.0f, GeometryFilter::StaticOnly));
    }
    m_slots.assign(static_cast<size_t>(m_maxLights), SlotAttributes{});
    m_sampleFlux.assign(static_cast<size_t>(m_maxLights), glm::vec3(0.0f));
    m_tiles = TileAssignment(static_cast<uint32_t>(m_tilesX * m_tilesY), static_cast<size_t>(m_maxLights));
    // §4.6: "a heavily blurred version of the texture": its mean colour.
    m_textureMeans.clear();
    for (const TextureImage& t : ctx.scene.textures) {
        glm::dvec3 sum(0.0);
        for (const glm::vec3& p : t.image.pixels()) sum += glm::dvec3(p);
        m_textureMeans.push_back(t.image.empty() ? glm::vec3(1.0f) : glm::vec3(sum / double(t.image.pixelCount())));
    }

    // §6: 16-bit depth.
    BOUNCE_TRY(m_maps, paraboloid::ParaboloidMaps::create({"iir.paraboloid", "iir.paraboloidMaps", "iir.paraboloid.fbo"},
                                                          GL_DEPTH_COMPONENT16, m_shadowMapSize, m_maxLights));
    m_mapSamples = gl::Query::create("iir.mapSamples", GL_SAMPLES_PASSED);

    const int n = m_tilesX, m = m_tilesY;
    m_tileSize = {(ctx.size.x + n - 1) / n, (ctx.size.y + m - 1) / m};
    const glm::ivec2 atlas{m_tileSize.x * n, m_tileSize.y * m};
    auto target = [](std::string_view name, glm::ivec2 s) {
        gl::TextureDesc d;
        d.format = GL_RGBA32F;
        d.width = s.x;
        d.height = s.y;
        d.minFilter = d.magFilter = GL_NEAREST;
        return gl::Texture::create(name, d);
    };
    m_splitPosition = target("iir.split.position", atlas);
    m_splitNormal = target("iir.split.normal", atlas);
    m_tileIrradiance = target("iir.tileIrradiance", atlas);
    m_irradiance = target("iir.irradiance", ctx.size);
    m_splitFbo = gl::Framebuffer::create("iir.split.fbo");
    m_splitFbo.attach(GL_COLOR_ATTACHMENT0, m_splitPosition);
    m_splitFbo.attach(GL_COLOR_ATTACHMENT1, m_splitNormal);
    m_splitFbo.setDrawBuffers(2);
    BOUNCE_CHECK(m_splitFbo.complete(), "iir split framebuffer");
    m_accumulateFbo = gl::Framebuffer::create("iir.accum.fbo");
    m_accumulateFbo.attach(GL_COLOR_ATTACHMENT0, m_tileIrradiance);
    m_accumulateFbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_accumulateFbo.complete(), "iir accumulation framebuffer");
    m_combineFbo = gl::Framebuffer::create("iir.combine.fbo");
    m_combineFbo.attach(GL_COLOR_ATTACHMENT0, m_irradiance);
    m_combineFbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_combineFbo.complete(), "iir combine framebuffer");
    m_filterFbo = gl::Framebuffer::create("iir.filter.fbo");

    m_vplBuffer = gl::Buffer::create("iir.vpls", sizeof(VplGpu) * static_cast<size_t>(m_maxLights));
    const size_t tiles = static_cast<size_t>(n * m);
    m_tileBuffer = gl::Buffer::create("iir.tiles", sizeof(uint32_t) * (tiles + 1 + static_cast<size_t>(m_maxLights)));
    return {};
}

void IirTechnique::updateVpls(FrameContext& ctx, const LightPose& pose) {
    const auto t0 = std::chrono::steady_clock::now();
    VplDistribution& dist = *m_distribution;
    const RayCaster& rays = *m_rayCaster;
    const float offset = kSurfaceOffsetInDiagonals * m_sceneDiagonal;
    auto isValid = [&](SlotId, const VplSample& s) {
        if (s.kind == SampleKind::Vpl) return !rays.occluded(pose.position, s.positionWorld);
        return !rays.closestHit(pose.position, glm::vec3(s.directionWorld), offset).has_value();
    };
    auto castRay = [&](SlotId slot, const glm::dvec3& direction) -> std::optional<glm::vec3> {
        const glm::vec3 dir(direction);
        const std::optional<RayHit> hit = rays.closestHit(pose.position, dir, offset);
        if (!hit) return std::nullopt;
        SlotAttributes& a = m_slots[slot];
        a.normal = glm::dot(hit->shadingNormal, dir) > 0.0f ? -hit->shadingNormal : hit->shadingNormal;
        const Material& mat = m_scene->materials[hit->materialIndex];
        glm::vec3 albedo = mat.baseColor * (1.0f - mat.metallic);
        if (mat.baseColorTexture >= 0 && static_cast<size_t>(mat.baseColorTexture) < m_textureMeans.size())
            albedo *= m_textureMeans[static_cast<size_t>(mat.baseColorTexture)];
        a.albedo = albedo;
        return hit->position;
    };

    dist.removeInvalid(pose, isValid);
    const auto tValid = std::chrono::steady_clock::now();
    dist.deleteForBudget();
    std::vector<SlotId> created = dist.createSamples(castRay);
    // The first frame fills every slot (the paper does not say how the set starts; growing by
    // recalcMax per frame would leave the first maxLights/recalcMax frames dark).
    if (ctx.frame == 0 || dist.sampleCount() == created.size()) {
        while (dist.sampleCount() < dist.params().maxLights) {
            std::vector<SlotId> more = dist.createSamples(castRay);
            if (more.empty()) break;
            created.insert(created.end(), more.begin(), more.end());
        }
    }
    dist.computeWeights();
    const double ms = millisecondsSince(t0);

    const VplFrameStats& stats = dist.frameStats();
    std::vector<SlotId> newVpls;
    for (SlotId s : created)
        if (dist.sample(s).kind == SampleKind::Vpl) newVpls.push_back(s);
    ctx.counters["vplManagementMs"] = ms;
    ctx.counters["vplValidityMs"] = std::chrono::duration<double, std::milli>(tValid - t0).count();
    ctx.counters["vpls"] = dist.vplCount();
    ctx.counters["vplMisses"] = dist.sampleCount() - dist.vplCount();
    ctx.counters["vplsInvalidated"] = stats.invalidOutsideCone + stats.invalidRejected + stats.invalidCoincident;
    ctx.counters["vplsDeleted"] = stats.deleted;
    ctx.counters["vplSamplesCreated"] = static_cast<double>(created.size());
    ctx.counters["vplsCreated"] = static_cast<double>(newVpls.size());
    ctx.counters["vplDispersion"] = stats.dispersion;

    for (size_t i = 0; i < m_sampleFlux.size(); ++i) {
        const VplSample& s = dist.samples()[i];
        const double share = s.kind == SampleKind::Empty ? 0.0 : (m_paperNormalisation ? s.weight : s.fluxFraction);
        m_sampleFlux[i] = m_primary.flux * static_cast<float>(share);
    }
    renderShadowMaps(ctx, newVpls);
}

glm::vec3 IirTechnique::paraboloidTangent(glm::vec3 normal) { return anyTangent(normal); }

glm::vec3 IirTechnique::paraboloidOrigin(glm::vec3 position, glm::vec3 normal) const {
    return position + normal * (kSurfaceOffsetInDiagonals * m_sceneDiagonal);
}

float IirTechnique::paraboloidFar() const { return kShadowFarInDiagonals * m_sceneDiagonal; }

void IirTechnique::renderShadowMaps(FrameContext& ctx, const std::vector<SlotId>& slots) {
    auto scope = ctx.timers.scope("sm-rendering");
    m_mapsRenderedLastFrame = static_cast<uint32_t>(slots.size());
    ctx.counters["vplShadowMaps"] = static_cast<double>(slots.size());
    m_mapQueries = !slots.empty();
    if (slots.empty()) return;
    glBeginQuery(GL_SAMPLES_PASSED, m_mapSamples.id());
    const float offset = kSurfaceOffsetInDiagonals * m_sceneDiagonal;
    const float far = kShadowFarInDiagonals * m_sceneDiagonal;
    m_maps.begin(far);
    for (SlotId slot : slots) {
        const VplSample& s = m_distribution->sample(slot);
        const SlotAttributes& a = m_slots[slot];
        const glm::vec3 t = anyTangent(a.normal);
        m_maps.setFrame(paraboloid::vplFromWorld(t, glm::cross(a.normal, t), a.normal));
        m_maps.render(ctx.drawer, static_cast<int>(slot), s.positionWorld + a.normal * offset, render::DrawFilter::Static);
    }
    glEndQuery(GL_SAMPLES_PASSED);
    m_maps.end();
}

void IirTechnique::collectCounters(Counters& out) {
    if (!m_mapQueries) return;
    GLuint64 samples = 0;
    glGetQueryObjectui64v(m_mapSamples.id(), GL_QUERY_RESULT, &samples);
    out["vplMapSamples"] = static_cast<double>(samples);
}

void IirTechnique::derivedSettings(std::map<std::string, double>& out) const {
    out["sceneDiagonalMetres"] = m_sceneDiagonal;
    out["positionThresholdMetres"] = static_cast<double>(m_positionThreshold) * m_sceneDiagonal;
    out["clampDistanceMetres"] = static_cast<double>(m_clampDistance) * m_sceneDiagonal;
    out["shadowBiasMetres"] = static_cast<double>(m_shadowBias) * m_sceneDiagonal;
}

void IirTechnique::uploadVpls() {
    const VplDistribution& dist = *m_distribution;
    const float offset = kSurfaceOffsetInDiagonals * m_sceneDiagonal;
    // §7: VPLs go to tiles in the order they were generated, round robin, so tiles get equal counts;
    // a VPL keeps its tile while it lives (TileAssignment), so the interleaving pattern of the
    // surviving VPLs does not shift when others are replaced.
    m_tiles.update(dist.samples());
    std::vector<SlotId> order;
    for (size_t i = 0; i < dist.samples().size(); ++i)
        if (dist.samples()[i].kind == SampleKind::Vpl) order.push_back(static_cast<SlotId>(i));
    std::sort(order.begin(), order.end(),
              [&](SlotId a, SlotId b) { return dist.sample(a).serial < dist.sample(b).serial; });
    std::vector<VplGpu> vpls(order.size());
    for (size_t k = 0; k < order.size(); ++k) {
        const SlotId slot = order[k];
        const SlotAttributes& a = m_slots[slot];
        vpls[k].position = glm::vec4(dist.sample(slot).positionWorld + a.normal * offset, static_cast<float>(slot));
        vpls[k].normal = glm::vec4(a.normal, 0.0f);
        vpls[k].tangent = glm::vec4(anyTangent(a.normal), 0.0f);
        vpls[k].intensity = glm::vec4(a.albedo * m_sampleFlux[slot] / glm::pi<float>(), 0.0f);
    }
    const size_t tiles = static_cast<size_t>(m_tilesX * m_tilesY);
    std::vector<uint32_t> data(tiles + 1, 0);
    std::vector<std::vector<uint32_t>> lists(tiles);
    for (size_t k = 0; k < order.size(); ++k) {
        const int tile = m_tiles.tileOf(order[k]);
        BOUNCE_CHECK(tile >= 0 && static_cast<size_t>(tile) < tiles, "iir: VPL in slot {} has no tile", order[k]);
        lists[static_cast<size_t>(tile)].push_back(static_cast<uint32_t>(k));
    }
    for (size_t t = 0; t < tiles; ++t) {
        data[t] = static_cast<uint32_t>(data.size());
        data.insert(data.end(), lists[t].begin(), lists[t].end());
    }
    data[tiles] = static_cast<uint32_t>(data.size());
    if (!vpls.empty()) m_vplBuffer.upload(0, vpls.size() * sizeof(VplGpu), vpls.data());
    m_tileBuffer.upload(0, data.size() * sizeof(uint32_t), data.data());
}

void IirTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    m_mapQueries = false;
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (!m_primary.supported) {
        ctx.counters["iirUnsupportedLight"] = 1.0;
        glClearTexImage(indirect.id(), 0, GL_RGBA, GL_FLOAT, zero);
        return;
    }
    // §7 overlaps VPL management with GPU work. Flushing first starts the G-buffer and direct-light
    // passes already queued this frame, so they render while the CPU works on the VPLs below.
    glFlush();
    const IirPrimaryLight light = primaryLight(*m_scene, ctx.time);
    const LightPose pose{light.emitter.position, glm::normalize(light.emitter.direction)};
    updateVpls(ctx, pose);
    uploadVpls();

    const int n = m_tilesX, m = m_tilesY;
    const glm::ivec2 atlas{m_tileSize.x * n, m_tileSize.y * m};
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    gl::Context::current()->bindEmptyVertexArray();
    ctx.gbuffer.bind();
    auto setTiling = [&](gl::Program& p) {
        p.set("u_tiles", glm::ivec2(n, m));
        p.set("u_tileSize", m_tileSize);
        p.set("u_imageSize", ctx.size);
    };
    {
        auto s = ctx.timers.scope("split");
        m_splitFbo.bind();
        glViewport(0, 0, atlas.x, atlas.y);
        setTiling(m_split);
        m_split.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    {
        auto s = ctx.timers.scope("accum");
        m_accumulateFbo.bind();
        glViewport(0, 0, atlas.x, atlas.y);
        m_splitPosition.bind(BINDING_TEX_INPUT0);
        m_splitNormal.bind(BINDING_TEX_INPUT1);
        m_maps.maps().bind(BINDING_TEX_TECH0);
        m_vplBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
        m_tileBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
        setTiling(m_accumulate);
        const float clampDistance = m_clampDistance * m_sceneDiagonal;
        m_accumulate.set("u_maxGeometry", clampDistance > 0.0f ? 1.0f / (clampDistance * clampDistance) : 3.0e38f);
        m_accumulate.set("u_far", kShadowFarInDiagonals * m_sceneDiagonal);
        m_accumulate.set("u_depthBias", m_shadowBias / kShadowFarInDiagonals);
        m_accumulate.set("u_normalOffset", m_shadowBias * m_sceneDiagonal);
        m_accumulate.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    {
        auto s = ctx.timers.scope("combine");
        m_combineFbo.bind();
        glViewport(0, 0, ctx.size.x, ctx.size.y);
        m_tileIrradiance.bind(BINDING_TEX_INPUT0);
        setTiling(m_combine);
        m_combine.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    {
        auto s = ctx.timers.scope("filter");
        m_filterFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
        m_filterFbo.setDrawBuffers(1);
        BOUNCE_CHECK(m_filterFbo.complete(), "iir filter framebuffer");
        m_filterFbo.bind();
        glViewport(0, 0, ctx.size.x, ctx.size.y);
        m_irradiance.bind(BINDING_TEX_INPUT0);
        setTiling(m_filter);
        m_filter.set("u_alpha", m_positionThreshold * m_sceneDiagonal);
        m_filter.set("u_beta", m_normalThreshold);
        m_filter.set("u_tent", m_filterKernel == "box" ? 0 : 1);
        m_filter.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
}

}  // namespace bounce
