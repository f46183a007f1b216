// `vct` — voxel cone tracing with hybrid voxelization and spherical-harmonics radiance
// (Rauwendaal 2013, PhD thesis, Oregon State University; the voxelizer of Rauwendaal & Bailey 2013).
//
// Every frame, with no precomputation (dynamic objects and lights need nothing else):
//  1. "voxelize": the scene is voxelized into a dense N^3 grid around the scene bounds (or a user
//     box) by one of three voxelizers sharing the exact triangle/voxel overlap test of section 4.1
//     (shaders/techniques/vct/overlap.glsl, 6- or 26-separating):
//       triangle  — triangle-parallel: one geometry-shader invocation per triangle loops over its
//                   voxels (4.1.1);
//       fragment  — fragment-parallel: the geometry shader swizzles to the dominant plane and dilates
//                   the triangle (Hertel), the fragment shader loops over the column's depth (4.1.2);
//       hybrid    — pass 1 voxelizes triangles whose projected area is at most `cutoff` voxels^2 in
//                   the geometry shader and appends the others to an index buffer; pass 2 draws those
//                   indirectly through the fragment-parallel stages (4.1.3).
//     Each voxel receives the direct light reflected by its surface (Eq. 7.1, radiometrically
//     L = rho / pi * E * V with the light set's shadow maps; inject.glsl), written as isotropic
//     RGBA8 through an r32ui view (imageAtomicMax or the running average of Fig. B.1) and, for
//     SH-F32, added to the DC coefficients with float atomics. Level 0 is isotropic in every format,
//     as in the thesis (directional initialisation darkened the hierarchy, 5.1.2/5.1.3). With
//     `binary` only a single-component occupancy volume is written (the Table 4.1 benchmark mode).
//     Active voxels of level 0 go to a list (mutex volume + atomic append, 5.4).
//  2. "post-voxelize": opacity 1 for written voxels (average mode), SH-F32 normalisation (sum /
//     count), SH-U8 transfer from the isotropic result; the anisotropic faces copy level 0.
//  3. "mipmap": level by level, the opacity-weighted isotropic mip (every format: its opacity is the
//     SH formats' alpha volume), then the format's own filter: directional anisotropic, or the SH
//     face projection of Eq. 5.9 with the division by pi the thesis omits. Sparse mode processes only
//     the active-voxel lists (compute jobs dispatched indirectly from the lists' counts); dense mode every voxel.
//  4. "diffuse-ao": six 60-degree cones per pixel (Eq. 6.8/6.9), generic (Fig. B.4) or specialised
//     (Fig. B.5) tracer; "specular": one cone about the mirror direction, aperture from roughness.
//  5. "shadow" (coneShadows on): the pixel's direct light, shadowed by one cone per light through the
//     volume (Eq. 6.3), replaces the shared shadow-mapped pass (the technique then owns the direct
//     light). Off by default: the shared pass is what every other technique uses.
//
// Deviations (docs/techniques/vct.md, one line each):
//  - HDR radiance: the 8-bit formats store it divided by an automatic range (RadianceRange.h); SH-U8 as
//    RGBA8_SNORM; SH clamped at 0, not [0, 1].
//  - every volume, SH included, stores colour premultiplied by opacity (the SH mip divides by 8).
//  - generic tracer (the default) with the tangent cap: no sample's footprint reaches below the
//    receiver's tangent plane (the receiver lit itself through the filter).
//  - aniso opacity blended as transmittance; iso/SH opacity corrected for the step length; cones end
//    where they leave the grid.
//  - no bindless: the 6 or 12 volumes on ordinary texture units; at most four lights injected; hybrid
//    pass 2 reads (vertex, object) pairs by vertex pulling (a mesh may be placed by several objects).
#include "techniques/vct/VctTechnique.h"

#include "core/Check.h"
#include "core/Log.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/SetupLimits.h"
#include "gpu/ShaderLimits.h"
#include "techniques/vct/ConeSet.h"
#include "techniques/vct/RadianceRange.h"
#include "techniques/vct/ShMath.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace bounce {

namespace {

// Surface samples of the automatic radiance range: enough that a spot's hot spot on a wall of the
// Cornell box falls within a few centimetres of one (engineering choice).
constexpr size_t kRangeSamples = 16384;
// Headroom over the brightest sample: the hot spot's true peak lies between samples.
constexpr float kRangeHeadroom = 1.25f;
// Active-voxel list capacity per level, in multiples of N_l^2: a surface occupies O(N^2) voxels; 32
// covers six thick walls and interior geometry several times over (engineering choice).
constexpr uint32_t kListCapacityPerSquare = 32;
// resolution's default per device profile (issue 29 #20): the thesis's 256^3 for its GI figures on a
// GPU (Rauwendaal 2013 ch. 6); 64^3 on llvmpipe, which voxelizes and traces on the CPU.
constexpr int kResolutionLlvmpipe = 64;
constexpr int kResolutionGpu = 256;
// vct.counters: [0..3] writes, pass-1 and pass-2 triangles, CAS drops; [4..7] pass 2's indirect
// command; [8] oversized triangles (volume.glsl's VctCounters).
constexpr int kCounters = 12;
// SH-U8 coefficient range relative to the radiance range: the DC coefficient of radiance L is
// L / Y00 = 3.545 L, band 1 is bounded by the same (|Y1| <= |Y00| sqrt(3)).
constexpr float kShU8RangeFactor = 3.6f;

int storageIndex(std::string_view s) {
    for (size_t i = 0; i < VctTechnique::kStorages.size(); ++i)
        if (VctTechnique::kStorages[i] == s) return static_cast<int>(i);
    return 0;
}

int debugIndex(std::string_view s) {
    for (size_t i = 0; i < VctTechnique::kDebugViews.size(); ++i)
        if (VctTechnique::kDebugViews[i] == s) return static_cast<int>(i);
    return 0;
}

// An active-voxel list's head (passes.glsl ListIn/ListOut): the append count, three free words, the
// capacity; the packed voxels follow.
struct ListHead {
    uint32_t count, unused0, unused1, unused2;
    uint32_t capacity, pad0, pad1, pad2;
};

}  // namespace

void VctTechnique::visitSettings(SettingsVisitor& v) {
    v.field("voxelizer", m_voxelizer, "hybrid: small triangles in the geometry shader, large ones by an indirect fragment-parallel pass (thesis 4.1.3); triangle: triangle-parallel (4.1.1); fragment: fragment-parallel (4.1.2)", kVoxelizers);
    v.field("resolution", m_resolution, "voxels per side N (power of two; thesis 128..512, 256 for its GI figures; 64 on llvmpipe, where 256 takes minutes a frame)", 16, 512,
            PerProfile<int>{kResolutionLlvmpipe, kResolutionGpu});
    v.field("separability", m_separability, "conservative: 26-separating overlap (Fig. 4.4); thin: 6-separating (Fig. 4.5, the Table 4.1 benchmark)", kSeparabilities);
    v.field("cutoff", m_cutoff, "hybrid classification: projected triangle area on its dominant plane, voxels^2, above which a triangle goes to pass 2 (thesis: 'a few', optimum 0.5..13.7 in Table 4.1)", 0.0f, 1.0e6f);
    v.field("storage", m_storage, "radiance storage: iso RGBA8 (5.1.1), aniso 6 x RGBA8 (5.1.2; the default, closest to the reference), sh-f32 12 x R32F with float atomics, sh-u8 3 x RGBA8 transferred from iso (5.1.3)", kStorages);
    v.field("atomic", m_atomic, "level-0 write conflicts: average = compare-and-swap running average (Fig. B.1), max = imageAtomicMax", kAtomics);
    v.field("casRetries", m_casRetries, "compare-and-swap retries of a level-0 write (atomic=average, and sh-f32 without float atomics) before it is dropped and counted in casDrops (Fig. B.1 bounds the loop; 255, the count's saturation)", 1, 4096);
    v.field("triangleInvocations", m_triangleInvocations, "voxelizer=triangle: geometry-shader invocations per triangle, each looping over every k-th row of its voxel box (bounce's; one invocation, the thesis's, loops over the whole box: about 10^6 iterations at N=512, past a GPU watchdog and llvmpipe's loop budget; GL guarantees 32)", 1, 32);
    v.field("sparseMip", m_sparseMip, "post-voxelization and mipmapping over active-voxel lists (thesis 5.4); off = every voxel (dense)");
    v.field("binary", m_binary, "occupancy only (single-component volume, Table 4.1 benchmark mode): no radiance, the indirect output is black unless a debug view shows the occupancy");
    v.field("tracer", m_tracer, "diffuse cones: the generic tracer (Fig. B.4, with the tangent cap; the default, closest to the reference) or the specialised 60-degree tracer at integer LODs (Fig. B.5, as printed)", kTracers);
    v.field("tangentCap", m_tangentCap, "generic tracer: a sample whose trilinear footprint would reach below the receiver's tangent plane takes the finest level that stays above it and steps by that level's texel (bounce's fix: receivers lit themselves through the filter); off = Fig. B.4 as printed");
    v.field("anisoBlend", m_anisoBlend, "aniso sampling (Fig. B.2's ambient cube): transmittance = opacity 1 - prod (1 - a_i)^(d_i^2), so a plane opaque along its normal stops oblique cones; linear = the printed sum d_i^2 a_i", kAnisoBlends);
    v.field("opacityCorrection", m_opacityCorrection, "iso/SH samples: opacity 1 - (1 - a)^s for a sample standing for s level-0 voxels of path (a is a mean over level-0 voxels); off = the thesis's raw mean opacity, under which a one-voxel wall at level k lets 1 - 2^-k of a cone through");
    v.field("startOffset", m_startOffset, "f of Eqs. 6.1-6.2, voxels: diffuse/AO origins move f along the normal, specular cones start at f|v|/(n.w) (thesis default 1.5)", 0.0f, 16.0f);
    v.field("maxStartOffset", m_maxStartOffset, "fMax of Eq. 6.2, voxels: cap of the specular start distance at grazing angles (not given by the thesis)", 0.0f, 64.0f);
    v.field("maxDistance", m_maxDistance, "cone length, metres; 0 = the grid's diagonal", 0.0f, 1.0e6f);
    v.field("aoDistance", m_aoDistance, "distance after which the AO accessibility is frozen (aoDist), metres; 0 = a quarter of the grid's side", 0.0f, 1.0e6f);
    v.field("specular", m_specular, "trace one specular cone about the mirror direction for surfaces with F0 > 0 (section 6.5)");
    v.field("coneShadows", m_coneShadows, "shadow the pixel's direct light with one cone per light through the voxel volume (Eq. 6.3, the thesis's results) instead of the shared shadow maps; vct then owns the direct light");
    v.field("shadowAperture", m_shadowAperture, "shadow cone aperture, degrees (thesis Fig. 6.6 shows 0, 2, 4, 6; 0 = a ray marched at LOD 0)", 0.0f, 60.0f);
    v.field("specularApertureScale", m_specularApertureScale, "specular cone aperture = 2 atan(scale * alpha), alpha = roughness^2 (the thesis gives no mapping)", 0.0f, 100.0f);
    v.field("radianceRange", m_radianceRange, "radiance mapped to 1.0 in the 8-bit formats, W/(m^2 sr); 0 = automatic per frame", 0.0f, 1.0e9f);
    v.field("debugView", m_debugView, "replace the indirect output: occupancy or radiance of the first voxel on each camera ray at debugLevel, ao (accessibility of the six cones), slice (radiance of z = debugSlice at debugLevel)", kDebugViews);
    v.field("debugLevel", m_debugLevel, "mip level of the occupancy, radiance and slice views", 0, 9);
    v.field("debugSlice", m_debugSlice, "z of the slice view, 0..1 across the grid", 0.0f, 1.0f);
    v.field("boxSide", m_boxSide, "side of a user voxel grid cube, metres; 0 = a cube around the scene's bounds at t = 0 with a one-voxel margin", 0.0f, 1.0e6f);
    v.field("boxCentreX", m_boxCentre.x, "centre of the user grid cube (with boxSide > 0), metres", -1.0e6f, 1.0e6f);
    v.field("boxCentreY", m_boxCentre.y, "centre of the user grid cube, metres", -1.0e6f, 1.0e6f);
    v.field("boxCentreZ", m_boxCentre.z, "centre of the user grid cube, metres", -1.0e6f, 1.0e6f);
    v.field("memoryBudgetMiB", m_memoryBudgetMiB, "largest total size of the voxel volumes, MiB (setup fails above it)", 1, 1 << 20);
}

int VctTechnique::storageId() const { return storageIndex(m_storage); }

double VctTechnique::radianceBytesPerVoxel(std::string_view storage) {
    switch (storageIndex(storage)) {
        case VCT_STORAGE_ISO: return 4.0;
        case VCT_STORAGE_ANISO: return 24.0;
        case VCT_STORAGE_SH_F32: return 48.0;
        case VCT_STORAGE_SH_U8: return 12.0;
    }
    return 0.0;
}

Expected<void> VctTechnique::buildPrograms() {
    const int storage = storageId();
    const std::string conservative = m_separability == "conservative" ? "1" : "0";
    std::vector<std::pair<std::string, std::string>> defines = {{"VCT_STORAGE", std::to_string(storage)},
                                                                {"VCT_CONSERVATIVE", conservative},
                                                                {"VCT_FLOAT_ATOMICS", m_floatAtomics ? "1" : "0"},
                                                                {"VCT_CAS_RETRIES", std::to_string(m_casRetries)}};
    auto with = [&](std::vector<std::pair<std::string, std::string>> extra) {
        auto d = defines;
        d.insert(d.end(), extra.begin(), extra.end());
        return d;
    };
    const std::string geomTri = "techniques/vct/voxelize_triangle.geom";
    if (m_voxelizer == "triangle") {
        BOUNCE_TRY(m_voxTriangle, gl::Program::build({"vct.voxelize.triangle", {{GL_VERTEX_SHADER, "techniques/vct/voxelize.vert"}, {GL_GEOMETRY_SHADER, geomTri}}, with({{"VCT_HYBRID", "0"}, {"VCT_INVOCATIONS", std::to_string(m_triangleInvocations)}})}));
    }
    if (m_voxelizer == "hybrid") {
        BOUNCE_TRY(m_voxHybrid, gl::Program::build({"vct.voxelize.hybrid1", {{GL_VERTEX_SHADER, "techniques/vct/voxelize.vert"}, {GL_GEOMETRY_SHADER, geomTri}}, with({{"VCT_HYBRID", "1"}})}));
        BOUNCE_TRY(m_voxLarge, gl::Program::build({"vct.voxelize.hybrid2", {{GL_VERTEX_SHADER, "techniques/vct/large.vert"}, {GL_GEOMETRY_SHADER, "techniques/vct/voxelize_fragment.geom"}, {GL_FRAGMENT_SHADER, "techniques/vct/voxelize_fragment.frag"}}, defines}));
    }
    if (m_voxelizer == "fragment") {
        BOUNCE_TRY(m_voxFragment, gl::Program::build({"vct.voxelize.fragment", {{GL_VERTEX_SHADER, "techniques/vct/voxelize.vert"}, {GL_GEOMETRY_SHADER, "techniques/vct/voxelize_fragment.geom"}, {GL_FRAGMENT_SHADER, "techniques/vct/voxelize_fragment.frag"}}, defines}));
    }
    if (m_binary) {
        if (m_coneShadows) return makeError("settings binary=true and coneShadows=true: a binary volume holds no opacity mip to trace shadows through");
        return {};
    }
    auto pass = [&](int id, bool sparse, gl::Program& out) -> Expected<void> {
        const std::string label = fmt::format("vct.pass{}.{}", id, sparse ? "sparse" : "dense");
        auto d = with({{"VCT_PASS", std::to_string(id)}, {"VCT_SPARSE", sparse ? "1" : "0"}});
        if (sparse) {
            BOUNCE_TRY(out, gl::Program::build({label, {{GL_COMPUTE_SHADER, "techniques/vct/pass_list.comp"}}, d}));
        } else {
            BOUNCE_TRY(out, gl::Program::build({label, {{GL_COMPUTE_SHADER, "techniques/vct/pass.comp"}}, d}));
        }
        return {};
    };
    BOUNCE_TRY_VOID(pass(1, false, m_postDense));
    BOUNCE_TRY_VOID(pass(2, false, m_mipIsoDense));
    if (m_sparseMip) {
        BOUNCE_TRY(m_listDispatch, gl::ListDispatch::create());
        BOUNCE_TRY_VOID(pass(1, true, m_postSparse));
        BOUNCE_TRY_VOID(pass(2, true, m_mipIsoSparse));
        BOUNCE_TRY_VOID(pass(5, true, m_clearSparse));
    }
    if (storage == VCT_STORAGE_ANISO || storage == VCT_STORAGE_SH_F32 || storage == VCT_STORAGE_SH_U8) {
        const int id = storage == VCT_STORAGE_ANISO ? 3 : 4;
        BOUNCE_TRY_VOID(pass(id, false, m_mipDense));
        if (m_sparseMip) BOUNCE_TRY_VOID(pass(id, true, m_mipSparse));
        if (id == 4) {
            for (int i = 0; i < 8; ++i) {
                const std::string name = fmt::format("u_shMip[{}]", i);
                m_mipDense.set(name, vct::shMipChildMatrix(i));
                if (m_sparseMip) m_mipSparse.set(name, vct::shMipChildMatrix(i));
            }
        }
    }
    auto traceDefines = [&](int part) { return with({{"VCT_PART", std::to_string(part)}}); };
    BOUNCE_TRY(m_traceDiffuse, gl::Program::build({"vct.trace.diffuse", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "techniques/vct/trace.frag"}}, traceDefines(1)}));
    BOUNCE_TRY(m_traceSpecular, gl::Program::build({"vct.trace.specular", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "techniques/vct/trace.frag"}}, traceDefines(2)}));
    if (m_coneShadows) {
        BOUNCE_TRY(m_emission, gl::Program::build({"vct.emission", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "render/emission.frag"}}}));
        BOUNCE_TRY(m_directCone, gl::Program::build({"vct.direct.cone", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "techniques/vct/direct_cone.frag"}}, defines}));
    }
    return {};
}

// The active list of level l (sizeof(ListHead) + capacity words; allocate() below).
static uint64_t activeListCapacity(int resolution, int level) {
    const uint64_t n = static_cast<uint64_t>(resolution >> level);
    return std::min<uint64_t>(n * n * n, kListCapacityPerSquare * n * n);
}

Expected<void> VctTechnique::checkBuffers(const gl::GpuInfo& info, int resolution, size_t triangles) {
    const size_t large = std::max<size_t>(triangles, 1) * 3 * 2 * sizeof(uint32_t);
    BOUNCE_TRY_VOID(gl::checkStorageBuffer(info, large, fmt::format("technique 'vct': the scene's {} triangles", triangles),
                                           "the large-triangle list (6 words a triangle)"));
    const size_t list = sizeof(ListHead) + activeListCapacity(resolution, 0) * sizeof(uint32_t);
    return gl::checkStorageBuffer(info, list, fmt::format("technique 'vct': setting resolution={}", resolution),
                                  fmt::format("the level-0 active list ({} voxels)", activeListCapacity(resolution, 0)));
}

Expected<void> VctTechnique::setup(const SetupContext& ctx) {
    const int N = m_resolution;
    if (N < 16 || (N & (N - 1)) != 0) return makeError("setting resolution={} must be a power of two between 16 and 512", N);
    const gl::GpuInfo& info = gl::Context::current()->info();
    if (N > info.max3dTextureSize)
        return makeError("setting resolution={} exceeds this GL's largest 3D texture ({} texels per side)", N, info.max3dTextureSize);
    if (m_cutoff < 0.5f || m_cutoff > 64.0f) {
        if (m_voxelizer == "hybrid")
            return makeError("setting cutoff={} is out of range: the hybrid voxelizer's cutoff is 0.5..64 voxels^2 (thesis optimum 0.5..13.7)", m_cutoff);
    }
    if (ctx.scene.lights.size() > VCT_MAX_LIGHTS)
        return makeError("technique vct injects at most {} lights at voxelization; scene '{}' has {}", VCT_MAX_LIGHTS, ctx.scene.name,
                         ctx.scene.lights.size());
    const int storage = storageId();
    // SH-F32 adds floats atomically: GL_NV_shader_atomic_float where the GL has it, else a compare-and-
    // swap loop through r32ui views of the same volumes (volume.glsl).
    m_floatAtomics = epoxy_has_gl_extension("GL_NV_shader_atomic_float");
    // Memory: every level of every volume (x 8/7), the level-0-only count volume, the mutexes.
    const double voxels0 = std::pow(static_cast<double>(N), 3.0);
    const double chain = 8.0 / 7.0;
    double bytes = 0.0;
    if (m_binary) bytes = voxels0;
    else {
        bytes = (4.0 + radianceBytesPerVoxel(m_storage)) * voxels0 * chain;  // iso/alpha + radiance
        if (storage == VCT_STORAGE_ISO) bytes = 4.0 * voxels0 * chain;
        if (storage == VCT_STORAGE_SH_F32) bytes += 4.0 * voxels0;  // write counts
    }
    if (m_sparseMip || !m_binary) bytes += 4.0 * voxels0 * chain;  // mutexes
    const double budget = static_cast<double>(m_memoryBudgetMiB) * 1024.0 * 1024.0;
    if (bytes > budget)
        return makeError("settings resolution={} storage={}: the voxel volumes need {:.0f} MiB, over memoryBudgetMiB={}", N, m_storage,
                         bytes / (1024.0 * 1024.0), m_memoryBudgetMiB);

    // The grid: a cube around the scene (or the user box) with a one-voxel margin on each side.
    glm::vec3 centre;
    float side;
    if (m_boxSide > 0.0f) {
        centre = m_boxCentre;
        side = m_boxSide;
    } else {
        glm::vec3 lo, hi;
        ctx.scene.bounds(0.0f, lo, hi);
        centre = 0.5f * (lo + hi);
        const float extent = std::max(hi.x - lo.x, std::max(hi.y - lo.y, hi.z - lo.z));
        if (!(extent > 0.0f)) return makeError("technique vct: scene '{}' has no extent to voxelize", ctx.scene.name);
        side = extent * static_cast<float>(N) / static_cast<float>(N - 2);
    }
    const float voxel = side / static_cast<float>(N);
    const glm::vec3 origin = centre - glm::vec3(0.5f * side);
    m_uniforms.voxelFromWorld = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / voxel)) * glm::translate(glm::mat4(1.0f), -origin);
    m_uniforms.worldFromVoxel = glm::inverse(m_uniforms.voxelFromWorld);
    m_levels = static_cast<int>(std::log2(N)) + 1;
    m_uniforms.grid = glm::vec4(static_cast<float>(N), 1.0f / static_cast<float>(N), voxel, static_cast<float>(m_levels));
    m_sceneGpu = &ctx.sceneGpu;

    BOUNCE_TRY_VOID(checkBuffers(info, N, ctx.sceneGpu.triangleCount(render::DrawFilter::All)));
    BOUNCE_TRY_VOID(buildPrograms());
    BOUNCE_TRY_VOID(allocate(ctx));

    m_rangeSamples = vct::rangeSamples(ctx.scene, kRangeSamples);
    return {};
}

Expected<void> VctTechnique::allocate(const SetupContext&) {
    const int N = m_resolution;
    const int storage = storageId();
    auto volume = [&](std::string_view name, GLenum format, int levels) {
        gl::TextureDesc d;
        d.target = GL_TEXTURE_3D;
        d.format = format;
        d.width = d.height = d.depth = N;
        d.levels = levels;
        // Integer volumes (mutexes, counts) take NEAREST: with other filters an integer texture is
        // incomplete (GL 4.5 §8.17) and image access to it invalid (§8.26).
        const bool integer = format == GL_R32UI || format == GL_R8UI;
        d.minFilter = levels > 1 && !integer ? GL_LINEAR_MIPMAP_LINEAR : (levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
        d.magFilter = levels > 1 && !integer ? GL_LINEAR : GL_NEAREST;
        // Clamp to edge (the TextureDesc default): a sample whose footprint crosses the grid's side
        // reads the boundary texels, where the scene's bounding walls lie (a zero border lets cones
        // through those walls at coarse levels: measured 12-22 % darker). Cones end where their near
        // edge leaves the grid (cone.glsl), so nothing is collected from beyond it.
        return gl::Texture::create(name, d);
    };
    m_iso = volume("vct.iso", GL_RGBA8, m_levels);
    m_mutex = volume("vct.mutex", GL_R32UI, m_levels);
    if (m_binary) m_binaryVolume = volume("vct.binary", GL_R8UI, 1);
    else m_binaryVolume = volume("vct.binary.unused", GL_R8UI, 1);
    m_volumes.clear();
    if (!m_binary) {
        if (storage == VCT_STORAGE_ANISO) {
            static constexpr const char* kFaces[6] = {"vct.aniso.+x", "vct.aniso.-x", "vct.aniso.+y", "vct.aniso.-y", "vct.aniso.+z", "vct.aniso.-z"};
            for (const char* f : kFaces) m_volumes.push_back(volume(f, GL_RGBA8, m_levels));
        } else if (storage == VCT_STORAGE_SH_F32) {
            for (int c = 0; c < 12; ++c) m_volumes.push_back(volume(fmt::format("vct.sh.{}{}", "rgb"[c / 4], c % 4), GL_R32F, m_levels));
            m_count = volume("vct.sh.count", GL_R32UI, 1);
            const float zero = 0.0f;
            for (int c = 0; c < 12; ++c)
                for (int l = 0; l < m_levels; ++l) glClearTexImage(m_volumes[c].id(), l, GL_RED, GL_FLOAT, &zero);
        } else if (storage == VCT_STORAGE_SH_U8) {
            for (int c = 0; c < 3; ++c) m_volumes.push_back(volume(fmt::format("vct.shu8.{}", "rgb"[c]), GL_RGBA8_SNORM, m_levels));
        }
    }
    m_ubo = gl::Buffer::create("vct.uniforms", sizeof(gpu::VctUniforms));
    m_counters = gl::Buffer::create("vct.counters", kCounters * sizeof(uint32_t));
    size_t triangles = m_sceneGpu->triangleCount(render::DrawFilter::All);
    m_largeCapacity = static_cast<uint32_t>(std::max<size_t>(triangles, 1));
    m_large = gl::Buffer::create("vct.largeTriangles", static_cast<size_t>(m_largeCapacity) * 3 * 2 * sizeof(uint32_t));
    m_lists.clear();
    for (int l = 0; l < m_levels; ++l) {
        ActiveList list;
        list.capacity = static_cast<uint32_t>(activeListCapacity(N, l));
        list.buffer = gl::Buffer::create(fmt::format("vct.activeList{}", l), sizeof(ListHead) + list.capacity * sizeof(uint32_t));
        list.args = gl::ListDispatch::createArgs(fmt::format("vct.activeList{}.dispatch", l));
        m_lists.push_back(std::move(list));
    }
    m_sparseActive = m_sparseMip;
    m_listsValid = false;
    m_dummy2D = gl::Texture::create2D("vct.shadowDummy2D", 1, 1, GL_DEPTH_COMPONENT32F);
    m_dummy2D.setCompareMode(true);
    gl::TextureDesc cube;
    cube.target = GL_TEXTURE_CUBE_MAP;
    cube.format = GL_R32F;
    m_dummyCube = gl::Texture::create("vct.shadowDummyCube", cube);
    const float one = 1.0f;
    glClearTexImage(m_dummy2D.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
    glClearTexImage(m_dummyCube.id(), 0, GL_RED, GL_FLOAT, &one);
    m_voxelFbo = gl::Framebuffer::create("vct.voxelizeFbo");
    glNamedFramebufferParameteri(m_voxelFbo.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, N);
    glNamedFramebufferParameteri(m_voxelFbo.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, N);
    m_traceFbo = gl::Framebuffer::create("vct.traceFbo");
    return {};
}

void VctTechnique::updateUniforms(FrameContext& ctx) {
    gpu::VctUniforms& u = m_uniforms;
    const float side = u.grid.z * u.grid.x;
    u.voxelize = glm::vec4(m_separability == "conservative" ? 1.0f : 0.0f, m_cutoff, static_cast<float>(storageId()),
                           m_atomic == "average" ? static_cast<float>(VCT_ATOMIC_AVERAGE) : static_cast<float>(VCT_ATOMIC_MAX));
    // Radiance range: the setting, or the brightest reflected radiance of the surface samples.
    float range = m_radianceRange;
    if (range <= 0.0f) {
        const float brightest = vct::brightestReflectedRadiance(m_rangeSamples, ctx.scene, ctx.sceneGpu.lights(), ctx.time);
        range = brightest > 0.0f ? brightest * kRangeHeadroom : 1.0f;
    }
    u.range = glm::vec4(range, range * kShU8RangeFactor, static_cast<float>(std::min<size_t>(ctx.lights.count(), VCT_MAX_LIGHTS)),
                        m_binary ? 1.0f : 0.0f);
    const float maxDist = coneLength(side);
    const float aoDist = aoLength(side);
    u.cone = glm::vec4(m_startOffset, std::max(m_maxStartOffset, m_startOffset), maxDist, aoDist);
    u.cone2 = glm::vec4(m_specular ? 1.0f : 0.0f, m_specularApertureScale, m_tracer == "specialised" ? 1.0f : 0.0f,
                        glm::radians(m_shadowAperture));
    u.debug = glm::vec4(static_cast<float>(debugIndex(m_debugView)), static_cast<float>(std::min(m_debugLevel, m_levels - 1)), m_debugSlice,
                        m_sparseActive ? 1.0f : 0.0f);
    // |v| of Eq. 6.2 for a cubic voxel: the diagonal for 26-separating voxelization, the side for
    // 6-separating (vct::voxelExtent, ConeSet.h), in voxels.
    const float extent = vct::voxelExtent(m_separability == "conservative" ? vct::Separability::Conservative26 : vct::Separability::Thin6,
                                          glm::vec3(1.0f));
    u.trace = glm::vec4(m_tangentCap ? 1.0f : 0.0f, m_opacityCorrection ? 1.0f : 0.0f, extent, m_anisoBlend == "transmittance" ? 1.0f : 0.0f);
    for (size_t i = 0; i < VCT_MAX_LIGHTS; ++i) u.lights[i] = i < ctx.lights.count() ? ctx.lights.light(i) : gpu::LightGpu{};
    m_ubo.upload(0, sizeof(u), &u);
}

void VctTechnique::clearVolumes() {
    const uint32_t zero = 0u;
    const float zeroF[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const int storage = storageId();
    if (m_binary) {
        glClearTexImage(m_binaryVolume.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    }
    if (m_sparseActive && m_listsValid) {
        clearListedVoxels();  // every level, level 0 included, through last frame's lists
    } else {
        glClearTexImage(m_iso.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, &zero);
        if (m_sparseActive) {
            for (int l = 0; l < m_levels; ++l) glClearTexImage(m_mutex.id(), l, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
            // Only active parents are written: every other voxel of the upper levels must read empty.
            for (int l = 1; l < m_levels; ++l) {
                glClearTexImage(m_iso.id(), l, GL_RGBA, GL_UNSIGNED_BYTE, &zero);
                for (gl::Texture& v : m_volumes) {
                    if (storage == VCT_STORAGE_SH_F32) glClearTexImage(v.id(), l, GL_RED, GL_FLOAT, zeroF);
                    else glClearTexImage(v.id(), l, GL_RGBA, GL_FLOAT, zeroF);
                }
            }
        }
        // The SH-U8 transfer and the SH-F32 sums write occupied voxels only.
        if (storage == VCT_STORAGE_SH_U8 && !m_binary)
            for (gl::Texture& v : m_volumes) glClearTexImage(v.id(), 0, GL_RGBA, GL_FLOAT, zeroF);
        if (storage == VCT_STORAGE_SH_F32 && !m_binary)
            for (int c = 0; c < 3; ++c) glClearTexImage(m_volumes[4 * c].id(), 0, GL_RED, GL_FLOAT, zeroF);
    }
    if (m_sparseActive) {
        for (ActiveList& list : m_lists) {
            const ListHead head{0u, 0u, 0u, 0u, list.capacity, 0u, 0u, 0u};
            list.buffer.upload(0, sizeof(head), &head);
        }
    }
    // The SH-F32 write counts (one level) are cleared densely in both paths.
    if (storage == VCT_STORAGE_SH_F32 && !m_binary) glClearTexImage(m_count.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    const uint32_t counters[kCounters] = {0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0};  // [4..7]: pass 2's DrawArraysIndirectCommand
    m_counters.upload(0, sizeof(counters), counters);
}

void VctTechnique::clearListedVoxels() {
    const int storage = storageId();
    const GLenum volumeFormat = storage == VCT_STORAGE_SH_F32 ? GL_R32F : storage == VCT_STORAGE_SH_U8 ? GL_RGBA8_SNORM : GL_RGBA8;
    constexpr int kVolumesPerPass = 6;  // IMG2..IMG7: with the iso and mutex images, the 8 units GL 4.5 guarantees
    for (int l = 0; l < m_levels; ++l) {
        m_listDispatch.writeArgs(m_lists[l].buffer, m_lists[l].args, m_lists[l].capacity);
        m_lists[l].buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
        m_lists[l].buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);  // declared, unused
        glBindImageTexture(BINDING_IMG0, m_iso.id(), l, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8);
        glBindImageTexture(BINDING_IMG1, m_mutex.id(), l, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
        const int volumes = static_cast<int>(m_volumes.size());
        for (int first = 0; first == 0 || first < volumes; first += kVolumesPerPass) {
            const int n = std::min(kVolumesPerPass, volumes - first);
            for (int k = 0; k < kVolumesPerPass; ++k) {
                // Unused units keep a valid image of the declared format bound.
                const gl::Texture& t = k < n ? m_volumes[static_cast<size_t>(first + k)] : (volumes > 0 ? m_volumes[0] : m_iso);
                glBindImageTexture(BINDING_IMG2 + k, t.id(), l, GL_TRUE, 0, GL_WRITE_ONLY, volumes > 0 ? volumeFormat : GL_RGBA8);
            }
            m_clearSparse.set("u_level", l);
            m_clearSparse.set("u_volumeCount", std::max(n, 0));
            m_clearSparse.use();
            gl::ListDispatch::dispatch(m_lists[l].args);
        }
    }
    // The zeros must land before voxelization's atomics and the list heads' reset (a buffer upload).
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
}

void VctTechnique::voxelize(FrameContext& ctx) {
    const int storage = storageId();
    m_ubo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
    glBindImageTexture(BINDING_IMG0, m_iso.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    if (storage == VCT_STORAGE_SH_F32 && !m_binary) {
        for (int c = 0; c < 3; ++c)
            glBindImageTexture(BINDING_IMG1 + c, m_volumes[4 * c].id(), 0, GL_TRUE, 0, GL_READ_WRITE, m_floatAtomics ? GL_R32F : GL_R32UI);
        glBindImageTexture(BINDING_IMG4, m_count.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    }
    glBindImageTexture(BINDING_IMG5, m_binaryVolume.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8UI);
    glBindImageTexture(BINDING_IMG6, m_mutex.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    m_lists[0].buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    m_counters.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
    for (size_t i = 0; i < VCT_MAX_LIGHTS; ++i) {
        if (i < ctx.lights.count()) ctx.lights.bindShadowMaps(i, BINDING_TEX_VCT_SHADOW2D0 + i, BINDING_TEX_VCT_SHADOWCUBE0 + i);
        else {
            m_dummy2D.bind(static_cast<GLuint>(BINDING_TEX_VCT_SHADOW2D0 + i));
            m_dummyCube.bind(static_cast<GLuint>(BINDING_TEX_VCT_SHADOWCUBE0 + i));
        }
    }
    // lighting.glsl's single-light samplers must see complete textures of their types too.
    m_dummy2D.bind(BINDING_TEX_SHADOW);
    m_dummyCube.bind(BINDING_TEX_SHADOW_CUBE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    m_voxelFbo.bind();
    render::View view;  // unused by the voxelizer's vertex stage (it reads u_vct), sets the viewport
    view.viewport = {m_resolution, m_resolution};
    view.clipFromView = m_uniforms.voxelFromWorld;
    if (m_voxelizer == "triangle" || m_voxelizer == "hybrid") {
        auto s = ctx.timers.scope("pass1");
        glEnable(GL_RASTERIZER_DISCARD);
        if (m_voxelizer == "hybrid") {
            m_large.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH3);
            m_voxHybrid.set("u_largeCapacity", m_largeCapacity);
            m_voxHybrid.set("u_loopBudget", static_cast<unsigned>(gl::shaderLoopIterationBudget()));
            m_voxHybrid.use();
        } else {
            m_voxTriangle.set("u_loopBudget", static_cast<unsigned>(gl::shaderLoopIterationBudget()));
            m_voxTriangle.use();
        }
        ctx.drawer.draw(view);
        glDisable(GL_RASTERIZER_DISCARD);
    }
    if (m_voxelizer == "hybrid") {
        auto s = ctx.timers.scope("pass2");
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        m_sceneGpu->vertices().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
        m_large.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH3);
        m_voxLarge.use();
        glViewport(0, 0, m_resolution, m_resolution);
        gl::Context::current()->bindEmptyVertexArray();
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_counters.id());
        glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(4 * sizeof(uint32_t)));
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    }
    if (m_voxelizer == "fragment") {
        m_voxFragment.use();
        ctx.drawer.draw(view);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void VctTechnique::runPass(gl::Program& dense, gl::Program& sparse, bool sparseMode, int level, int listIn, int listOut) {
    if (sparseMode) {
        // One invocation per entry of the input list (gpu/ListDispatch.h: its count never leaves the GPU).
        m_listDispatch.writeArgs(m_lists[listIn].buffer, m_lists[listIn].args, m_lists[listIn].capacity);
        m_lists[listIn].buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
        m_lists[listOut].buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
        sparse.set("u_level", level);
        sparse.use();
        gl::ListDispatch::dispatch(m_lists[listIn].args);
    } else {
        // Unused by the dense path but declared: keep valid buffers bound.
        m_lists[0].buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
        m_lists[0].buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
        dense.set("u_level", level);
        const int size = m_resolution >> level;
        dense.set("u_size", size);
        dense.use();
        gl::Program::dispatch(size, size, size, 4, 4, 4);
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void VctTechnique::postVoxelize(bool sparse) {
    const int storage = storageId();
    glBindImageTexture(BINDING_IMG0, m_iso.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    if (storage == VCT_STORAGE_SH_F32) {
        for (int c = 0; c < 3; ++c) glBindImageTexture(BINDING_IMG1 + c, m_volumes[4 * c].id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
        glBindImageTexture(BINDING_IMG4, m_count.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    } else if (storage == VCT_STORAGE_SH_U8) {
        for (int c = 0; c < 3; ++c) glBindImageTexture(BINDING_IMG1 + c, m_volumes[c].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8_SNORM);
    }
    runPass(m_postDense, m_postSparse, sparse, 0, 0, 0);
    if (storage == VCT_STORAGE_ANISO) {
        // Level 0 is isotropic: the same colour on all six faces (thesis 5.1.2).
        const int N = m_resolution;
        for (gl::Texture& face : m_volumes)
            glCopyImageSubData(m_iso.id(), GL_TEXTURE_3D, 0, 0, 0, 0, face.id(), GL_TEXTURE_3D, 0, 0, 0, 0, N, N, N);
    }
}

void VctTechnique::bindVolumes() const {
    m_iso.bind(BINDING_TEX_VCT_ALPHA);
    for (size_t i = 0; i < m_volumes.size(); ++i) m_volumes[i].bind(static_cast<GLuint>(BINDING_TEX_VCT_VOLUME0 + i));
}

void VctTechnique::mipmap(bool sparse) {
    const int storage = storageId();
    bindVolumes();
    for (int level = 1; level < m_levels; ++level) {
        glBindImageTexture(BINDING_IMG0, m_iso.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8);
        glBindImageTexture(BINDING_IMG7, m_mutex.id(), level, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
        runPass(m_mipIsoDense, m_mipIsoSparse, sparse, level, level - 1, level);
        if (storage == VCT_STORAGE_ANISO) {
            for (int f = 0; f < 6; ++f)
                glBindImageTexture(BINDING_IMG0 + f, m_volumes[f].id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8);
            runPass(m_mipDense, m_mipSparse, sparse, level, level, level);
        } else if (storage == VCT_STORAGE_SH_F32 || storage == VCT_STORAGE_SH_U8) {
            for (int c = 0; c < 3; ++c) {
                if (storage == VCT_STORAGE_SH_F32) {
                    for (int k = 0; k < 4; ++k)
                        glBindImageTexture(BINDING_IMG0 + k, m_volumes[4 * c + k].id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
                } else {
                    glBindImageTexture(BINDING_IMG0, m_volumes[c].id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8_SNORM);
                }
                m_mipDense.set("u_channel", c);
                if (sparse) m_mipSparse.set("u_channel", c);
                runPass(m_mipDense, m_mipSparse, sparse, level, level, level);
            }
        }
    }
}

void VctTechnique::beginFullScreen(FrameContext& ctx, const gl::Texture& target) {
    m_traceFbo.attach(GL_COLOR_ATTACHMENT0, target);
    m_traceFbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_traceFbo.complete(), "vct full-screen framebuffer");
    m_traceFbo.bind();
    glViewport(0, 0, ctx.size.x, ctx.size.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    ctx.gbuffer.bind();
    bindVolumes();
    m_ubo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
    gl::Context::current()->bindEmptyVertexArray();
}

void VctTechnique::trace(FrameContext& ctx, const gl::Texture& indirect) {
    beginFullScreen(ctx, indirect);
    {
        auto s = ctx.timers.scope("diffuse-ao");
        m_traceDiffuse.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    if (m_specular && m_debugView == "none") {
        auto s = ctx.timers.scope("specular");
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        m_traceSpecular.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_BLEND);
    }
}

void VctTechnique::coneShadowedDirect(FrameContext& ctx) {
    auto s = ctx.timers.scope("shadow");
    beginFullScreen(ctx, ctx.direct);
    m_emission.use();  // emitted radiance first (unblended), as render/DirectLighting
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    m_directCone.use();
    for (size_t i = 0; i < ctx.lights.count(); ++i) {
        ctx.lights.bind(i);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_BLEND);
}

void VctTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    updateUniforms(ctx);
    const bool sparse = m_sparseActive && !m_binary;
    {
        auto s = ctx.timers.scope("voxelize");
        clearVolumes();
        voxelize(ctx);
    }
    if (!m_binary) {
        {
            auto s = ctx.timers.scope("post-voxelize");
            postVoxelize(sparse);
        }
        {
            auto s = ctx.timers.scope("mipmap");
            mipmap(sparse);
        }
        if (m_coneShadows) coneShadowedDirect(ctx);
        trace(ctx, indirect);
    } else {
        m_traceFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
        m_traceFbo.setDrawBuffers(1);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(m_traceFbo.id(), GL_COLOR, 0, zero);
    }
    m_frameSparse = sparse;
    m_listsValid = false;  // until collectCounters has seen that no list overflowed
}

float VctTechnique::coneLength(float side) const { return m_maxDistance > 0.0f ? m_maxDistance : side * std::sqrt(3.0f); }

float VctTechnique::aoLength(float side) const { return m_aoDistance > 0.0f ? m_aoDistance : 0.25f * side; }

void VctTechnique::derivedSettings(std::map<std::string, double>& out) const {
    const double voxel = m_uniforms.grid.z, side = voxel * static_cast<double>(m_uniforms.grid.x);
    const glm::vec3 origin = glm::vec3(m_uniforms.worldFromVoxel * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    out["boxSideMetres"] = side;
    out["boxCentreXMetres"] = origin.x + 0.5 * side;
    out["boxCentreYMetres"] = origin.y + 0.5 * side;
    out["boxCentreZMetres"] = origin.z + 0.5 * side;
    out["voxelSizeMetres"] = voxel;
    out["maxDistanceMetres"] = coneLength(static_cast<float>(side));
    out["aoDistanceMetres"] = aoLength(static_cast<float>(side));
}

void VctTechnique::collectCounters(Counters& out) {
    // Counters (one small readback per frame, after the frame is queued: the thesis reports the same
    // counts).
    const bool sparse = m_frameSparse;
    uint32_t c[kCounters];
    m_counters.download(0, sizeof(c), c);
    out["voxelWrites"] = c[0];
    out["trianglesPass1"] = c[1];
    out["trianglesPass2"] = c[2];
    out["casDrops"] = c[3];  // level-0 writes whose compare-and-swap loop gave up (volume.glsl)
    // Triangles whose voxel box may pass the loop budget in one geometry-shader invocation
    // (voxelize_triangle.geom): on llvmpipe their loops end early, on a GPU the watchdog may fire.
    out["oversizedTriangles"] = c[8];
    if (c[8] > 0 && !m_warnedOversized) {
        m_warnedOversized = true;
        spdlog::warn("vct: {} triangles' voxel boxes may take more than the shader loop budget of {} iterations in one "
                     "geometry-shader invocation (resolution={}, triangleInvocations={}): raise triangleInvocations or use "
                     "voxelizer=hybrid",
                     c[8], gl::shaderLoopIterationBudget(), m_resolution, m_triangleInvocations);
    }
    out["resolution"] = m_resolution;
    out["radianceRange"] = m_uniforms.range.x;
    out["bytesPerVoxel"] = allocatedRadianceBytesPerVoxel();
    out["alphaBytesPerVoxel"] = allocatedAlphaBytesPerVoxel();
    if (sparse) {
        bool overflow = false;
        double active = 0.0;
        for (int l = 0; l < m_levels; ++l) {
            ListHead h;
            m_lists[l].buffer.download(0, sizeof(h), &h);
            if (h.count > m_lists[l].capacity) overflow = true;
            if (l == 0) out["activeVoxels"] = h.count;
            active += h.count;
        }
        out["activeVoxelsAllLevels"] = active;
        m_listsValid = !overflow;  // the lists hold every written voxel: the next frame may clear through them
        if (overflow) {
            // Seen after the frame (no wait on its path): the next frame mipmaps densely; this one's
            // mip levels missed the voxels past the list's capacity.
            spdlog::warn("vct: an active-voxel list overflowed; switching to dense mipmapping from the next frame");
            m_sparseActive = false;
        }
        out["sparseOverflow"] = overflow ? 1.0 : 0.0;
    }
    out["sparseMip"] = sparse ? 1.0 : 0.0;
}

}  // namespace bounce
