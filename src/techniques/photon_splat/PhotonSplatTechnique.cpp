// `photon-splat` — photon splatting with orthographic bundles (seed 004, a thesis: ch. 3-4) on a GPU
// pipeline. Passes per frame:
//  1. inject (CPU, §3.2): photons from the emitters, stored at their first diffuse hit with a cosine
//     direction (PhotonInjection); injection=rsm: the document's method B (shared RSM's VPLs).
//  2. stratify (CPU, optional, §3.2.1/§4.2): 2x2x2 blocks with a cell under the threshold merge.
//  3. bundles (CPU, §3.3, Fig. 4): a ray per photon to its hit, the step back, the volume
//     (BundleVolume), the clusters of the scene that meet it (ClusterSet).
//  4. depth-maps: one r x r tile of a depth atlas per bundle, one multi-draw per batch (depth.vert),
//     the same tiles rasterised in a compute pass (depthMaps=compute: depth_raster.comp), or traced on
//     the CPU, a ray per texel centre (depthMaps=rays, llvmpipe's default: DepthRays).
//  5. hit-ranges + splat (§3.3/§4.3): each volume's back faces; per pixel the tolerant depth test,
//     the filter weight, the Lambert splat, added with the weight in alpha (splat.vert/.frag).
//  6. resolve (§3.4/§4.4): the flux estimate, or the document's normalisation; debug views.
//  7. blur (§3.5): separable Gaussian.
// Deviations, one line each (docs/techniques/photon-splat.md has the measurements):
//  - default estimate=flux, calibrated; the document's normalized has no physical scale.
//  - b = d by default (bundle from its photon) and D past the scene's box; b < d tilts the near plane.
//  - no bundle ray starts behind its photon's surface; photons whose ray escapes keep their bundle.
//  - the depth test uses the receiver's plane at the texel centre; maps in an atlas, culled clusters;
//    on llvmpipe the maps are traced on the CPU (the same first surfaces).
//  - photons from emissive surfaces and textured area lights too; 16384 photons, blur 5 by default.
// References: seed 004 (shared/seeds), spec shared/specs/photon-splatting-orthographic-bundles.md.
#include "techniques/photon_splat/PhotonSplatTechnique.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/DispatchGrid.h"
#include "reference/Rng.h"
#include "reference/Sampling.h"
#include "techniques/photon_splat/DepthRays.h"
#include "techniques/photon_splat/splat_shared.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

namespace bounce {

namespace {

// Defaults tied to the scene's size, for settings given as 0 (the document leaves them to the artist).
constexpr float kAutoMapSizeFraction = 0.05f;  // bundle width 2h = a twentieth of the scene diagonal (bias/noise, measured: docs)
constexpr float kAutoToleranceTexels = 0.05f;  // depth tolerance past the receiver plane: 1/20 texel (float rounding, curvature)
constexpr float kEmitterOffsetFraction = 1e-4f;  // emitter plane offset: 1e-4 of the scene diagonal (0.1 mm per metre)
constexpr uint32_t kClusterTriangles = SPLAT_CLUSTER_TRIANGLES;  // triangles per culling cluster (splat_shared.h)
constexpr int kMaxAtlasTexels = 4096;          // depth atlas side limit, texels (64 MB of DEPTH32F)
constexpr int kBundlePointsWidth = 256;        // texels per row of the bundle-points debug texture
constexpr float kRangeMarginTexels = 4.0f;     // splat volume cut to the first hits' depths +- 4 texels (slopes to tan 76 degrees over a half texel diagonal... and then some)
constexpr int kDepthClipPlanes = 7;
constexpr float kOverlapHeatMax = 64.0f;       // the overlap view's red: bundles per pixel (the defaults reach ~25 mean, ~80 at most)            // depth.vert's clip distances: tile (4), near, far, emitter

template <size_t N>
int indexOf(const std::array<std::string_view, N>& list, std::string_view s) {
    for (size_t i = 0; i < N; ++i)
        if (list[i] == s) return static_cast<int>(i);
    return 0;
}

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void PhotonSplatTechnique::visitSettings(SettingsVisitor& v) {
    v.field("injection", m_injection, "rays: photons shot from the lights through the ray-casting service (the document's method A); rsm: the regular VPLs of a reflective shadow map (its method B for a GPU pipeline)", kInjections);
    v.field("rsmSize", m_rsmSize, "RSM resolution per side with injection=rsm (per cube face for point/area lights)", 8, 2048);
    v.field("vplGrid", m_vplGrid, "VPLs per side per RSM layer with injection=rsm (must divide rsmSize): vplGrid^2 photons per layer", 1, 256);
    v.field("photons", m_photonCount, "photons shot from the emitters per frame (document: 2,500-50,000; default 16384: within bounds on every built-in scene, docs)", 1, 1 << 20);
    v.field("bounces", m_bounces, "diffuse hits at which photons are stored (1: single bounce, as implemented in the document)", 1, 8);
    v.field("seed", m_seed, "random seed of the photon paths", 0, 1 << 30);
    v.field("reseed", m_reseed, "new photon paths every frame (seed + frame): converges over frames, flickers; off = the same paths every frame");
    v.field("stratify", m_stratify, "3D stratification of the photons (document 3.2.1 / 4.2)");
    v.field("gridSize", m_gridSize, "stratification cells per side (even; document Fig. 9: 16)", 2, 256);
    v.field("threshold", m_threshold, "a 2x2x2 block with a cell (an empty one too, as 4.2 words the rule) under this many photons is merged (document Fig. 3: 2)", 1, 1 << 20);
    v.field("mapSize", m_mapSize, "bundle width 2h, metres; 0 = a twentieth of the scene diagonal", 0.0f, 1.0e6f);
    v.field("mapDepth", m_mapDepth, "bundle depth D past its near plane, metres; 0 = past the scene's bounding box", 0.0f, 1.0e6f);
    v.field("stepBack", m_stepBack, "step back b from the photon ray's hit, metres (the near plane then lies parallel to the hit surface); 0 = the hit distance d: the bundle starts at its photon", 0.0f, 1.0e6f);
    v.field("depthMaps", m_depthMaps, "how the bundles' depth maps are made: raster (a multi-draw into the atlas's tiles, the document's), compute (the same maps rasterised in a compute pass) or rays (a ray per texel centre traced on the CPU: the same maps, the fastest on llvmpipe, the default there)", kDepthMaps,
            PerProfile<std::string_view>{"rays", "raster"});
    v.field("mapResolution", m_mapResolution, "texels per side of each bundle's depth map (document: 4 and 32 tested)", 4, 32);
    v.field("depthTolerance", m_depthTolerance, "tolerant depth test: a receiver whose plane lies up to this far behind the stored depth at the texel's centre is lit, metres; 0 = 1/20 texel", 0.0f, 1.0e6f);
    v.field("filter", m_filter, "splat weight over the cross-section: gaussian (sigma = h/2), tent, box (document Fig. 6)", kFilters);
    v.field("estimate", m_estimate, "flux: rho/pi sum Phi w_n cos V with a unit-integral kernel (bounce's calibrated estimator of one-bounce light, the default); normalized: sum(w S)/sum(w) times exposure (the document's, no physical scale)", kEstimates);
    v.field("exposure", m_exposure, "factor on the normalized indirect light (document 4.4)", 0.0f, 1.0e6f);
    v.field("ambient", m_ambient, "radiance (times albedo) of pixels no bundle reached, W/(m^2 sr) (document 3.4)", 0.0f, 1.0e6f);
    v.field("blur", m_blur, "separable Gaussian blur of the indirect light: 0 (off), 3, 5, 7 or 9 pixels (document 3.5; default 5: fills the pixels no bundle reached, docs)", 0, 9);
    v.field("debugView", m_debugView, "overlap: bundles per pixel (blue 0 to red 64); accumulation: before normalisation; grid: stratification cell of each pixel", kDebugViews);
}

Expected<void> PhotonSplatTechnique::setup(const SetupContext& ctx) {
    if (m_blur != 0 && (m_blur < 3 || m_blur % 2 == 0))
        return makeError("setting blur={}: the blur kernel is 0 (off) or 3, 5, 7 or 9 pixels", m_blur);
    if (m_injection == "rsm") {
        BOUNCE_TRY_VOID(nichols::RegularVpls::checkGrid(m_rsmSize, m_vplGrid, nichols::ReflectiveShadowMap::layersFor(ctx.scene)));
        BOUNCE_TRY(m_rsm, nichols::ReflectiveShadowMap::create());
        BOUNCE_TRY(m_vpls, nichols::RegularVpls::create());
    }
    if (m_gridSize % 2 != 0) return makeError("setting gridSize={} must be even (the grid is walked in 2x2x2 blocks)", m_gridSize);
    ctx.scene.bounds(0.0f, m_lo, m_hi);
    const float diagonal = std::max(glm::length(m_hi - m_lo), 1e-3f);
    const float size = m_mapSize > 0.0f ? m_mapSize : kAutoMapSizeFraction * diagonal;
    m_half = 0.5f * size;
    m_back = m_stepBack > 0.0f ? m_stepBack : std::numeric_limits<float>::infinity();  // 0: b = d, from the photon
    m_depth = m_mapDepth;  // 0: to where the rays leave the scene's box
    m_emitterOffset = kEmitterOffsetFraction * diagonal;
    const gl::GpuInfo& info = gl::Context::current()->info();
    const int r = m_mapResolution;
    // Bundles per frame at most: photons times stored bounces, or one per VPL of a cube RSM.
    const int capacity = std::max(1, m_injection == "rsm" ? 6 * m_vplGrid * m_vplGrid : m_photonCount * m_bounces);
    const bool computeMaps = m_depthMaps == "compute";  // only the chosen path's program is built
    if (computeMaps) {
        BOUNCE_TRY(m_rasterProgram, gl::Program::build({"photon-splat.depthRaster", {{GL_COMPUTE_SHADER, "techniques/photon_splat/depth_raster.comp"}}}));
    } else if (m_depthMaps == "raster") {
        BOUNCE_TRY(m_depthProgram, gl::Program::build({"photon-splat.depth", {{GL_VERTEX_SHADER, "techniques/photon_splat/depth.vert"},
                                                                             {GL_FRAGMENT_SHADER, "render/shadow_depth.frag"}}}));
    }
    BOUNCE_TRY(m_splat, gl::Program::build({"photon-splat.splat", {{GL_VERTEX_SHADER, "techniques/photon_splat/splat.vert"},
                                                                   {GL_FRAGMENT_SHADER, "techniques/photon_splat/splat.frag"}}}));
    BOUNCE_TRY(m_rangeProgram, gl::Program::build({"photon-splat.range", {{GL_COMPUTE_SHADER, "techniques/photon_splat/tile_range.comp"}}}));
    BOUNCE_TRY(m_resolve, gl::Program::build({"photon-splat.resolve", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                                       {GL_FRAGMENT_SHADER, "techniques/photon_splat/resolve.frag"}}}));
    BOUNCE_TRY(m_blurProgram, gl::Program::build({"photon-splat.blur", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                                        {GL_FRAGMENT_SHADER, "techniques/photon_splat/blur.frag"}}}));
    // The depth atlas: one r x r tile per bundle, as many tiles as a frame's bundles (up to the side
    // limit; more bundles take several batches).
    const int maxTiles = std::max(1, std::min(info.maxTextureSize, kMaxAtlasTexels) / r);
    m_tiles.x = std::min(maxTiles, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(capacity)))));
    m_tiles.y = std::min(maxTiles, (capacity + m_tiles.x - 1) / m_tiles.x);
    gl::TextureDesc maps;
    maps.format = m_depthMaps != "raster" ? GL_R32F : GL_DEPTH_COMPONENT32F;  // read as .r by the passes after either way
    maps.width = m_tiles.x * r;
    maps.height = m_tiles.y * r;
    maps.minFilter = maps.magFilter = GL_NEAREST;  // a depth test per texel, no filtering
    m_maps = gl::Texture::create("photon-splat.depthAtlas", maps);
    // A set-up again (another path) keeps nothing of the last one's path: the byte counters count what is.
    m_mapsUint = {};
    m_mapFbo = {};
    m_clusterIndices = {};
    m_depthVao = {};
    m_tracedAtlas.clear();
    m_tracedAtlas.shrink_to_fit();
    if (computeMaps) {
        m_mapsUint = gl::Texture::createView("photon-splat.depthAtlasUint", m_maps, GL_R32UI);
    } else if (m_depthMaps == "rays") {
        m_tracedAtlas.assign(static_cast<size_t>(maps.width) * static_cast<size_t>(maps.height), 1.0f);  // the largest, once (soak)
        const float one = 1.0f;
        glClearTexImage(m_maps.id(), 0, GL_RED, GL_FLOAT, &one);
        m_tracedRows = 0;
    } else {
        m_mapFbo = gl::Framebuffer::create("photon-splat.mapFbo");
        m_mapFbo.attach(GL_DEPTH_ATTACHMENT, m_maps);
        m_mapFbo.setDrawBuffers(0);
        BOUNCE_CHECK(m_mapFbo.complete(), "photon-splat depth atlas framebuffer");
    }
    // The scene's triangles in clusters, drawn per bundle by one multi-draw per batch (raster) or read
    // by the compute pass; traced maps need none.
    m_clusters = photonsplat::ClusterSet{};
    m_drawCapacity = 0;
    if (m_depthMaps != "rays") {
        m_clusters = photonsplat::ClusterSet::build(ctx.scene, kClusterTriangles);
        const std::vector<uint32_t>& indices = m_clusters.indices();
        m_clusterIndices = gl::Buffer::create("photon-splat.clusterIndices", std::max<size_t>(indices.size(), 1) * sizeof(uint32_t),
                                              indices.empty() ? nullptr : indices.data(), 0);
        m_depthVao = gl::VertexArray::create("photon-splat.depthVao");
        glVertexArrayElementBuffer(m_depthVao.id(), m_clusterIndices.id());
    }
    m_accum = gl::Texture::create2D("photon-splat.accumulation", ctx.size.x, ctx.size.y, GL_RGBA32F);
    m_stats = gl::Texture::create2D("photon-splat.overlap", ctx.size.x, ctx.size.y, GL_RGBA32F);
    m_blurTemp = gl::Texture::create2D("photon-splat.blur", ctx.size.x, ctx.size.y, GL_RGBA32F);
    m_accumFbo = gl::Framebuffer::create("photon-splat.accumFbo");
    m_accumFbo.attach(GL_COLOR_ATTACHMENT0, m_accum);
    m_accumFbo.attach(GL_COLOR_ATTACHMENT1, m_stats);
    m_accumFbo.setDrawBuffers(2);
    BOUNCE_CHECK(m_accumFbo.complete(), "photon-splat accumulation framebuffer");
    m_outFbo = gl::Framebuffer::create("photon-splat.outFbo");
    m_bundleBuffer = gl::Buffer::create("photon-splat.bundles", static_cast<size_t>(capacity) * sizeof(gpu::BundleGpu));
    m_ranges = gl::Buffer::create("photon-splat.hitRanges", static_cast<size_t>(capacity) * sizeof(glm::vec2));
    // The per-bundle CPU arrays at their largest from the start: the bundle count varies from frame to
    // frame (photons that reach no surface), and growing them later crept the soak's RSS past its bound.
    m_bundles.reserve(static_cast<size_t>(capacity));
    m_volumes.reserve(static_cast<size_t>(capacity));
    m_gpuBundles.reserve(static_cast<size_t>(capacity));
    gl::TextureDesc points;
    points.target = GL_TEXTURE_2D_ARRAY;
    points.format = GL_RGBA32F;
    points.width = std::min(capacity, kBundlePointsWidth);  // rows of 256: within any texture width limit
    points.height = (capacity + points.width - 1) / points.width;
    points.minFilter = points.magFilter = GL_NEAREST;
    m_bundlePoints = gl::Texture::create("photon-splat.bundlePoints", points);
    const std::vector<glm::vec4> empty(static_cast<size_t>(points.width) * static_cast<size_t>(points.height), glm::vec4(0.0f));
    glTextureSubImage3D(m_bundlePoints.id(), 0, 0, 0, 0, points.width, points.height, 1, GL_RGBA, GL_FLOAT, empty.data());
    m_pointsWritten = 0;
    m_caster.reset();
    m_casterTime = -1.0f;
    return {};
}

void PhotonSplatTechnique::updateGeometry(FrameContext& ctx) {
    // The ray-casting scene and the clusters' bounds at this frame's time; static scenes build them once.
    if (!m_caster || (ctx.sceneGpu.hasDynamicObjects() && m_casterTime != ctx.time)) {
        auto caster = RayCaster::create(ctx.scene, ctx.time, GeometryFilter::All);
        BOUNCE_CHECK(caster.ok(), "photon-splat: ray-casting scene");
        m_caster.emplace(std::move(*caster));
        m_casterTime = ctx.time;
    }
    if (m_depthMaps != "rays") m_clusters.update(ctx.scene, ctx.time);
}

std::vector<photonsplat::Photon> PhotonSplatTechnique::rsmPhotons(FrameContext& ctx, uint64_t seed) {
    std::vector<photonsplat::Photon> out;
    if (!m_rsm->render(ctx, m_rsmSize)) return out;  // no light
    m_vpls->extract(*m_rsm, m_vplGrid);
    const std::vector<nichols::VplRecord> records = m_vpls->download();
    for (size_t i = 0; i < records.size(); ++i) {
        const nichols::VplRecord& r = records[i];
        if (r.position.w < 0.5f || std::max(r.flux.r, std::max(r.flux.g, r.flux.b)) <= 0.0f) continue;
        // The RSM's flux is already the reflected flux (albedo x incident); the photon leaves in a
        // cosine-distributed direction about the VPL's normal, as a shot photon does.
        const glm::vec3 n = glm::normalize(glm::vec3(r.normal));
        Rng rng(seed, i, 0);
        const Frame f(n);
        out.push_back(photonsplat::Photon{glm::vec3(r.position), glm::vec3(r.flux), f.toWorld(cosineHemisphere(rng.next(), rng.next())), n});
    }
    return out;
}

void PhotonSplatTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    updateGeometry(ctx);
    {
        auto s = ctx.timers.scope("inject");  // CPU work: the timer shows the wall time it blocks
        const auto t0 = std::chrono::steady_clock::now();
        photonsplat::InjectionSettings inj;
        inj.photons = static_cast<uint32_t>(m_photonCount);
        inj.bounces = static_cast<uint32_t>(m_bounces);
        inj.seed = static_cast<uint64_t>(m_seed) + (m_reseed ? ctx.frame : 0u);
        if (m_fixedPhotons) m_photonList = *m_fixedPhotons;
        else if (m_injection == "rsm") m_photonList = rsmPhotons(ctx, inj.seed);
        else photonsplat::injectPhotons(ctx.scene, ctx.time, *m_caster, inj, m_photonList);
        ctx.counters["injectMs"] = msSince(t0);
        ctx.counters["photonsStored"] = static_cast<double>(m_photonList.size());
        // What the photons take where they are held: the list's allocation (48 B per Photon).
        ctx.counters["photonBytes"] = static_cast<double>(m_photonList.capacity() * sizeof(photonsplat::Photon));
        if (m_stratify) {
            const auto t1 = std::chrono::steady_clock::now();
            photonsplat::StratifyStats st;
            m_photonList = photonsplat::stratify(m_photonList, m_lo, m_hi, m_gridSize, m_threshold, inj.seed, &st);
            ctx.counters["stratifyMs"] = msSince(t1);
            ctx.counters["gridBytes"] = static_cast<double>(st.gridBytes);
            ctx.counters["mergedBlocks"] = static_cast<double>(st.mergedBlocks);
            ctx.counters["photonsStratified"] = static_cast<double>(st.outputPhotons);
        }
        const auto t2 = std::chrono::steady_clock::now();
        photonsplat::BundleSettings bs;
        bs.stepBack = m_back;
        ctx.scene.bounds(ctx.time, bs.lo, bs.hi);  // rays that hit nothing still get a bundle
        photonsplat::placeBundles(m_photonList, *m_caster, bs, m_bundles, m_bundleScratch);
        ctx.counters["bundleMs"] = msSince(t2);
        ctx.counters["bundles"] = static_cast<double>(m_bundles.size());
    }
    const int count = static_cast<int>(std::min<size_t>(m_bundles.size(), m_bundleBuffer.size() / sizeof(gpu::BundleGpu)));
    m_volumes.resize(static_cast<size_t>(count));
    photonsplat::VolumeSettings volumeSettings;
    volumeSettings.half = m_half;
    volumeSettings.stepBack = m_back;
    volumeSettings.length = m_depth;
    volumeSettings.emitterOffset = m_emitterOffset;
    if (m_depth <= 0.0f) ctx.scene.bounds(ctx.time, volumeSettings.lo, volumeSettings.hi);
    std::vector<gpu::BundleGpu>& gpuBundles = m_gpuBundles;  // kept across frames: no per-frame megabytes
    gpuBundles.resize(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        const photonsplat::Bundle& b = m_bundles[static_cast<size_t>(i)];
        const photonsplat::BundleVolume v = photonsplat::bundleVolume(m_photonList[b.photon], b, volumeSettings);
        m_volumes[static_cast<size_t>(i)] = v;
        const bool emitter = std::isfinite(v.emitterOffset);
        gpuBundles[static_cast<size_t>(i)] = gpu::BundleGpu{glm::vec4(v.origin, v.half), glm::vec4(v.direction, v.length),
                                                            glm::vec4(v.right, v.zNear), glm::vec4(v.up, v.zFar),
                                                            glm::vec4(v.nearNormal, v.nearOffset),
                                                            glm::vec4(v.emitterNormal, emitter ? v.emitterOffset : -1e30f), glm::vec4(b.power, 0.0f)};
    }
    if (count > 0) m_bundleBuffer.upload(0, gpuBundles.size() * sizeof(gpu::BundleGpu), gpuBundles.data());
    {
        // The debug view's points: this frame's hit points, and zeros over what an earlier, larger
        // frame wrote.
        const gl::TextureDesc& d = m_bundlePoints.desc();
        const int written = std::min(std::max(count, m_pointsWritten), d.width * d.height);
        const int rows = (written + d.width - 1) / d.width;
        std::vector<glm::vec4>& hits = m_pointScratch;
        hits.assign(static_cast<size_t>(rows) * static_cast<size_t>(d.width), glm::vec4(0.0f));
        for (int i = 0; i < count && i < static_cast<int>(hits.size()); ++i) {
            const photonsplat::Bundle& b = m_bundles[static_cast<size_t>(i)];
            hits[static_cast<size_t>(i)] = glm::vec4(m_photonList[b.photon].position + b.hitDistance * b.direction, 1.0f);
        }
        if (rows > 0) glTextureSubImage3D(m_bundlePoints.id(), 0, 0, 0, 0, d.width, rows, 1, GL_RGBA, GL_FLOAT, hits.data());
        m_pointsWritten = count;
    }

    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(m_accumFbo.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(m_accumFbo.id(), GL_COLOR, 1, zero);
    const float tolerance = depthTolerance();
    const int tiles = m_tiles.x * m_tiles.y;
    int batches = 0;
    double clusterDraws = 0.0, cullMs = 0.0, traceMs = 0.0, tracedRays = 0.0;
    std::vector<uint32_t>& kept = m_cull.kept;
    std::vector<glm::uvec2>& pairs = m_cull.pairs;  // (cluster, bundle)
    for (int first = 0; first < count; first += tiles, ++batches) {
        const int n = std::min(tiles, count - first);
        {
            auto s = ctx.timers.scope("depth-maps");
            const auto t0 = std::chrono::steady_clock::now();
            if (m_depthMaps == "rays") {
                tracedRays += static_cast<double>(traceMaps(first, n));
                traceMs += msSince(t0);
            } else {
                // Cull: per bundle, the clusters whose box meets its volume (CPU); then the pairs as
                // draws (raster) or as workgroups (compute).
                const bool compute = m_depthMaps == "compute";
                std::vector<glm::uvec4>& work = m_cull.rasterPairs;  // compute: the pairs as the workgroups read them
                pairs.clear();
                work.clear();
                for (int i = 0; i < n; ++i) {
                    kept.clear();
                    if (m_cullClusters) m_clusters.cull(m_volumes[static_cast<size_t>(first + i)], kept);
                    else for (uint32_t c = 0; c < m_clusters.clusters().size(); ++c) kept.push_back(c);
                    const auto bundle = static_cast<uint32_t>(first + i);
                    for (uint32_t c : kept) {
                        if (!compute) {
                            pairs.push_back({c, bundle});
                            continue;
                        }
                        const photonsplat::ClusterSet::Cluster& cl = m_clusters.clusters()[c];
                        work.push_back({bundle, cl.object, cl.firstIndex, cl.indexCount});
                    }
                }
                clusterDraws += static_cast<double>(compute ? work.size() : pairs.size());
                if (compute) {
                    cullMs += msSince(t0);
                    renderMapsInCompute(ctx, first, work);
                } else {
                    buildDraws(pairs);
                    cullMs += msSince(t0);
                    renderMapsByRaster(ctx, first);
                }
            }
        }
        const bool useRanges = m_estimate == "flux";
        if (useRanges) {
            // The depths of each bundle's first hits, for the splat's cut volume.
            auto s = ctx.timers.scope("hit-ranges");
            m_maps.bind(BINDING_TEX_TECH0);
            m_bundleBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
            m_ranges.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
            m_rangeProgram.set("u_first", first);
            m_rangeProgram.set("u_tiles", m_tiles);
            m_rangeProgram.set("u_resolution", m_mapResolution);
            m_rangeProgram.use();
            glDispatchCompute(static_cast<GLuint>(n), 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // splat.vert reads the ranges
        }
        {
            auto s = ctx.timers.scope("splat");
            m_accumFbo.bind();
            glViewport(0, 0, ctx.size.x, ctx.size.y);
            glEnable(GL_BLEND);
            glBlendEquation(GL_FUNC_ADD);
            glBlendFunc(GL_ONE, GL_ONE);
            glEnable(GL_CULL_FACE);  // the volume's back faces: each covered pixel once (splat.vert)
            glCullFace(GL_FRONT);
            ctx.gbuffer.bind();
            m_maps.bind(BINDING_TEX_TECH0);
            m_bundleBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
            m_splat.set("u_first", first);
            m_splat.set("u_tiles", m_tiles);
            m_splat.set("u_resolution", m_mapResolution);
            m_splat.set("u_filter", indexOf(kFilters, m_filter) == 0 ? SPLAT_FILTER_GAUSSIAN
                                    : indexOf(kFilters, m_filter) == 1 ? SPLAT_FILTER_TENT : SPLAT_FILTER_BOX);
            m_splat.set("u_estimate", m_estimate == "flux" ? SPLAT_ESTIMATE_FLUX : SPLAT_ESTIMATE_NORMALIZED);
            m_splat.set("u_tolerance", tolerance);
            m_splat.set("u_useRanges", useRanges);
            // A receiver may lie beyond its texel's hit depth by its slope over half a texel: the
            // margin covers slopes up to kRangeMarginTexels (tan 76 degrees), plus the tolerance.
            m_splat.set("u_rangeMargin", kRangeMarginTexels * 2.0f * m_half / static_cast<float>(m_mapResolution) + tolerance);
            m_ranges.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
            m_splat.use();
            gl::Context::current()->bindEmptyVertexArray();
            glDrawArraysInstanced(GL_TRIANGLES, 0, 36, n);
            glCullFace(GL_BACK);
            glDisable(GL_CULL_FACE);
            glDisable(GL_BLEND);
        }
    }
    ctx.counters["depthMapBatches"] = static_cast<double>(batches);
    ctx.counters["depthMapTexels"] = static_cast<double>(count) * m_mapResolution * m_mapResolution;
    if (m_depthMaps == "rays") {
        ctx.counters["traceMs"] = traceMs;
        ctx.counters["tracedRays"] = tracedRays;
    } else {
        ctx.counters["clusterDraws"] = clusterDraws;
        ctx.counters["cullMs"] = cullMs;
    }
    ctx.counters["bundleHalfSize"] = m_half;
    ctx.counters["bundleBufferBytes"] = static_cast<double>(m_bundleBuffer.size());
    ctx.counters["depthAtlasBytes"] = static_cast<double>(gl::textureStorageBytes(m_maps.desc()));
    ctx.counters["clusterBytes"] = static_cast<double>(m_clusters.bytes() + m_clusterIndices.size());
    {
        auto s = ctx.timers.scope("resolve");
        const gl::Texture& target = m_blur > 0 && m_debugView == "none" ? m_blurTemp : indirect;
        m_outFbo.attach(GL_COLOR_ATTACHMENT0, target);
        m_outFbo.setDrawBuffers(1);
        BOUNCE_CHECK(m_outFbo.complete(), "photon-splat output framebuffer");
        m_outFbo.bind();
        glViewport(0, 0, ctx.size.x, ctx.size.y);
        ctx.gbuffer.bind();
        m_accum.bind(BINDING_TEX_INPUT0);
        m_stats.bind(BINDING_TEX_INPUT1);
        m_resolve.set("u_estimate", m_estimate == "flux" ? SPLAT_ESTIMATE_FLUX : SPLAT_ESTIMATE_NORMALIZED);
        m_resolve.set("u_exposure", m_exposure);
        m_resolve.set("u_ambient", glm::vec3(m_ambient));
        m_resolve.set("u_view", indexOf(kDebugViews, m_debugView));
        m_resolve.set("u_heatMax", kOverlapHeatMax);
        m_resolve.set("u_gridLo", m_lo);
        m_resolve.set("u_gridHi", m_hi);
        m_resolve.set("u_gridSize", m_gridSize);
        m_resolve.use();
        gl::Context::current()->bindEmptyVertexArray();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    if (m_blur > 0 && m_debugView == "none") {
        auto s = ctx.timers.scope("blur");
        // Horizontal into m_accum (free now), vertical into the output.
        m_blurProgram.set("u_kernel", m_blur);
        const std::array<std::pair<const gl::Texture*, const gl::Texture*>, 2> passes = {{{&m_blurTemp, &m_accum}, {&m_accum, &indirect}}};
        for (size_t pass = 0; pass < passes.size(); ++pass) {
            m_outFbo.attach(GL_COLOR_ATTACHMENT0, *passes[pass].second);
            m_outFbo.bind();
            passes[pass].first->bind(BINDING_TEX_INPUT0);
            m_blurProgram.set("u_direction", pass == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1));
            m_blurProgram.use();
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    }
}

float PhotonSplatTechnique::depthTolerance() const {
    return m_depthTolerance > 0.0f ? m_depthTolerance : kAutoToleranceTexels * 2.0f * m_half / static_cast<float>(m_mapResolution);
}

void PhotonSplatTechnique::derivedSettings(std::map<std::string, double>& out) const {
    out["sceneDiagonalMetres"] = glm::length(m_hi - m_lo);
    out["mapSizeMetres"] = 2.0 * m_half;
    out["depthToleranceMetres"] = depthTolerance();
    if (m_stepBack > 0.0f) out["stepBackMetres"] = m_stepBack;
    if (m_mapDepth > 0.0f) out["mapDepthMetres"] = m_mapDepth;
}

void PhotonSplatTechnique::collectCounters(Counters& out) {
    if (!m_stats) return;
    std::vector<float>& counts = m_overlapScratch;
    counts.resize(static_cast<size_t>(m_stats.width()) * static_cast<size_t>(m_stats.height()));
    glGetTextureImage(m_stats.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(counts.size() * sizeof(float)), counts.data());
    double sum = 0.0, most = 0.0, pixels = 0.0;
    for (float c : counts)
        if (c > 0.0f) {
            sum += c;
            most = std::max(most, static_cast<double>(c));
            pixels += 1.0;
        }
    out["overlapMean"] = pixels > 0.0 ? sum / pixels : 0.0;
    out["overlapMax"] = most;
    out["overlapPixels"] = pixels;
}

std::string_view PhotonSplatTechnique::frameReadbackReason() const {
    // injection=rays traces on the CPU from the scene alone; injection=rsm (the document's method B)
    // reads the shared RSM's VPLs back as photons, because the bundles are built on the CPU (pass 3).
    if (m_injection == "rsm") return "injection=rsm: the RSM's VPLs are read back as photons for the CPU's bundle pass";
    return {};
}

// depthMaps=raster: one instanced indirect command per cluster, its instances the bundles that keep
// it (grouped by a counting sort, so that baseInstance + gl_InstanceID reads them).
void PhotonSplatTechnique::buildDraws(const std::vector<glm::uvec2>& pairs) {
    std::vector<uint32_t>& perCluster = m_cull.perCluster;
    std::vector<DrawCommand>& commands = m_cull.commands;
    std::vector<glm::uvec2>& drawData = m_cull.drawData;
    perCluster.assign(m_clusters.clusters().size() + 1, 0u);
    for (const glm::uvec2& pr : pairs) ++perCluster[pr.x + 1];
    std::partial_sum(perCluster.begin(), perCluster.end(), perCluster.begin());
    commands.clear();
    for (size_t c = 0; c + 1 < perCluster.size(); ++c)
        if (perCluster[c + 1] > perCluster[c]) {
            const photonsplat::ClusterSet::Cluster& cl = m_clusters.clusters()[c];
            commands.push_back({cl.indexCount, perCluster[c + 1] - perCluster[c], cl.firstIndex, 0, perCluster[c]});
        }
    drawData.resize(pairs.size());
    for (const glm::uvec2& pr : pairs) drawData[perCluster[pr.x]++] = {pr.y, m_clusters.clusters()[pr.x].object};
}

// depthMaps=raster: the batch's tiles by one multi-draw (depth.vert, render/shadow_depth.frag).
void PhotonSplatTechnique::renderMapsByRaster(FrameContext& ctx, int first) {
    const std::vector<DrawCommand>& commands = m_cull.commands;
    const std::vector<glm::uvec2>& drawData = m_cull.drawData;
    if (std::max(commands.size(), drawData.size()) > m_drawCapacity) {
        m_drawCapacity = std::max(std::max(commands.size(), drawData.size()), 2 * m_drawCapacity);
        m_drawCommands = gl::Buffer::create("photon-splat.drawCommands", m_drawCapacity * sizeof(DrawCommand));
        m_drawData = gl::Buffer::create("photon-splat.drawData", m_drawCapacity * sizeof(glm::uvec2));
        glVertexArrayVertexBuffer(m_depthVao.id(), 0, m_drawData.id(), 0, sizeof(glm::uvec2));
        glVertexArrayBindingDivisor(m_depthVao.id(), 0, 1);
        glEnableVertexArrayAttrib(m_depthVao.id(), 0);
        glVertexArrayAttribIFormat(m_depthVao.id(), 0, 2, GL_UNSIGNED_INT, 0);
        glVertexArrayAttribBinding(m_depthVao.id(), 0, 0);
    }
    if (!commands.empty()) {
        m_drawCommands.upload(0, commands.size() * sizeof(DrawCommand), commands.data());
        m_drawData.upload(0, drawData.size() * sizeof(glm::uvec2), drawData.data());
    }
    m_mapFbo.bind();
    glViewport(0, 0, m_maps.width(), m_maps.height());
    const float one = 1.0f;
    glDepthMask(GL_TRUE);  // the clear obeys the depth write mask an earlier pass may have left off
    glClearNamedFramebufferfv(m_mapFbo.id(), GL_DEPTH, 0, &one);
    if (commands.empty()) return;
    m_depthProgram.use();
    m_depthProgram.set("u_first", first);
    m_depthProgram.set("u_tiles", m_tiles);
    m_bundleBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    ctx.sceneGpu.vertices().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
    ctx.sceneGpu.objects().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_OBJECTS);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // back faces occlude too: the volume may start inside geometry (4.3)
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    for (int k = 0; k < kDepthClipPlanes; ++k) glEnable(GL_CLIP_DISTANCE0 + static_cast<GLenum>(k));
    m_depthVao.bind();
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_drawCommands.id());
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, static_cast<GLsizei>(commands.size()), 0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    for (int k = 0; k < kDepthClipPlanes; ++k) glDisable(GL_CLIP_DISTANCE0 + static_cast<GLenum>(k));
    glDisable(GL_DEPTH_TEST);
}

// depthMaps=compute: the same tiles by depth_raster.comp, a workgroup per (bundle, cluster) pair.
// depthMaps=rays: the n maps from bundle `first` traced on the CPU (DepthRays) into the atlas's rows,
// uploaded; rows an earlier batch wrote below them are cleared (no map, as the other paths clear).
size_t PhotonSplatTechnique::traceMaps(int first, int n) {
    const std::span<const photonsplat::BundleVolume> volumes(m_volumes.data() + first, static_cast<size_t>(n));
    const int rows = (n + m_tiles.x - 1) / m_tiles.x * m_mapResolution;
    const int width = m_tiles.x * m_mapResolution;
    const size_t rays = photonsplat::traceDepthMaps(*m_caster, volumes, m_mapResolution, m_tiles.x,
                                                    std::span(m_tracedAtlas.data(), static_cast<size_t>(rows) * static_cast<size_t>(width)));
    glTextureSubImage2D(m_maps.id(), 0, 0, 0, width, rows, GL_RED, GL_FLOAT, m_tracedAtlas.data());
    if (m_tracedRows > rows) {
        const float one = 1.0f;
        glClearTexSubImage(m_maps.id(), 0, 0, rows, 0, width, m_tracedRows - rows, 1, GL_RED, GL_FLOAT, &one);
    }
    m_tracedRows = rows;
    return rays;
}

void PhotonSplatTechnique::renderMapsInCompute(FrameContext& ctx, int first, const std::vector<glm::uvec4>& work) {
    const float one = 1.0f;
    // Shader image writes of the previous batch, then this clear (GL 4.5 7.13.2: a texture update).
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glClearTexImage(m_maps.id(), 0, GL_RED, GL_FLOAT, &one);
    if (work.empty()) return;
    if (work.size() > m_rasterCapacity) {
        m_rasterCapacity = std::max(work.size(), 2 * m_rasterCapacity);
        m_rasterPairs = gl::Buffer::create("photon-splat.rasterPairs", m_rasterCapacity * sizeof(glm::uvec4));
    }
    m_rasterPairs.upload(0, work.size() * sizeof(glm::uvec4), work.data());
    m_rasterProgram.use();
    m_rasterProgram.set("u_first", first);
    m_rasterProgram.set("u_tiles", m_tiles);
    m_rasterProgram.set("u_resolution", m_mapResolution);
    m_rasterProgram.set("u_pairCount", static_cast<GLuint>(work.size()));
    m_bundleBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    ctx.sceneGpu.vertices().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
    m_rasterPairs.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
    m_clusterIndices.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH3);
    ctx.sceneGpu.objects().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_OBJECTS);
    m_mapsUint.bindImage(BINDING_IMG0, GL_READ_WRITE);
    gl::dispatchGroupsLinear(work.size());  // a workgroup per pair, in rows within the device's limit
    // The tile ranges and the splat read the atlas through samplers.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace bounce
