#pragma once
// The GPU machinery the four hemicube radiosity methods of van de Hoef 2013 share: the radiosity
// atlas (B and Bu, RGBA32F), the element/quad/shooter records, the hemicube renderer (ID, radiosity,
// combined ID + shot, low-resolution back shot + distance), hemicube integration (compute reduction
// or the mip-chain fallback), shooter selection and generation, the reconstruction passes and the
// display. RadiosityTechnique.cpp's essay maps each to the thesis's passes and to GL 4.5.
#include "core/Error.h"
#include "gpu/GpuInfo.h"
#include "gpu/GpuTimers.h"
#include "gpu/Objects.h"
#include "gpu/Program.h"
#include "render/DirectLighting.h"
#include "render/GBuffer.h"
#include "render/LightSet.h"
#include "render/SceneDrawer.h"
#include "techniques/radiosity/PatchModel.h"
#include "techniques/radiosity/radiosity_shared.h"

#include <functional>
#include <memory>
#include <vector>

namespace bounce::radiosity {

struct SystemOptions {
    PatchOptions patches;
    int hemicubeSize = 64;      // top-face pixels per side (thesis sec. 5.3.1: 64)
    int backSize = 16;          // back shot hemicubes (sec. 4.5.2: 16)
    int msaa = 4;               // samples of the radiosity and back hemicubes (sec. 5.3.1: 4)
    bool mipIntegration = false;
    int visibilitySamples = 4;  // nearest hemicube pixels tested (sec. 5.2.1: 4)
    bool randomRotation = true;
    float ffSubdivideRatio = 0.05f;  // A_s / r^2 above which the disk approximation is split
    int ffSubdivisions = 8;          // sub-disks per side then
    int crossGrid = 4;              // PROJECTEDRADIOSITY gridSize (sec. 4.5.2: 4)
    bool reprojection = true;
    bool crossFormFactorWeights = false;  // crossWeights=formFactor (bounce's option)
};

// Per-quad sums read back for FINDSHOOTINGQUAD (radiance x area, W/sr per channel).
struct QuadStats {
    glm::vec3 unshot{0.0f}, shot{0.0f}, total{0.0f};
    float area = 0.0f;
};

// A shooting patch as the CPU chooses it: an element rectangle of one quad.
struct ShooterRect {
    uint32_t quad = 0;
    glm::ivec2 lo{0}, hi{0};  // inclusive element range
};

enum class HemicubeKind { Id, Radiosity, Combined, Back };
enum class ShooterAt { Front, Back };

class RadiositySystem {
public:
    // One-line error when `msaa` exceeds the GL's colour or depth multisample-texture samples (issue 29 #11).
    static Expected<void> checkMsaa(int msaa, const gl::GpuInfo& info);
    static Expected<std::unique_ptr<RadiositySystem>> create(const Scene& scene, const SystemOptions& options);

    const PatchModel& patches() const { return m_model; }
    const SystemOptions& options() const { return m_options; }

    // Body transforms at `time`; a body "moves" when its transform differs from the one of the last
    // commit() (the previous redistribution).
    void beginFrame(const Scene& scene, float time);
    void commit();  // old bodies := current bodies
    bool anyMoving() const { return m_anyMoving; }
    bool bodyMoving(uint32_t body) const { return m_moving[body] != 0; }
    // Bodies that count as M when this is set (cross redistribution's removed set), else movement.
    void setMovingOverride(const std::vector<char>* moving);
    size_t movingElementCount() const;

    // Elements: B = Bu = E + D_new, D = D_new (or all 0) on the selected receivers.
    void reset(int receivers, bool toEmission);
    // Point, spot and directional lights (bounce's extension, radiosity.md): D_new, the direct
    // radiance rho E cos V / pi each element reflects of them (shadow-map visibility), then its change
    // since the last apply shot into the solution on `receivers`: B += D_new - D, Bu += D_new - D, D =
    // D_new (a moving light is a change of emission, as a moving emitter). No-ops without such lights.
    void computeLights(const render::LightSet& lights);
    void applyLights(int receivers);
    bool hasPunctualLights() const { return !m_punctual.empty(); }
    float maxLightRadiance() const { return m_maxLightRadiance; }  // luminance, unshadowed, at t = 0
    // One gather sweep (Alg. 4.1): a radiosity hemicube per element, integrated, B = E + rho sum;
    // `afterBatch(done)`, if given, after each batch's passes are issued (done: elements gathered in
    // this sweep so far; the gather's progress report).
    void gatherSweep(render::SceneDrawer& drawer, gl::GpuTimers& timers, const std::function<void(uint32_t)>& afterBatch = {});
    uint32_t gatherElementCount() const;  // the elements a sweep gathers at (one hemicube each)

    std::vector<QuadStats> quadStats();
    // Uploads shooters [first, first + n) of the shooter buffer and computes T for them.
    void loadShooters(const std::vector<ShooterRect>& rects);
    void computeShooters(uint32_t first, uint32_t count, bool keepShot);
    void clearShooterUnshot(uint32_t first, uint32_t count);
    // Hemicube records of shooters [first, first + count) in `role` (0-3), at their front or back,
    // placed with the old or the current bodies; then rendered (ID into role 0/1 arrays, combined
    // into role 1 + shot, back into role 2/3 after the MSAA resolve).
    void placeShooterHemicubes(uint32_t role, uint32_t first, uint32_t count, ShooterAt at, bool old);
    void renderHemicubes(render::SceneDrawer& drawer, HemicubeKind kind, uint32_t role, uint32_t count, bool old,
                         render::DrawFilter filter, gl::GpuTimers& timers);
    // GATHERRADIOSITY (Alg. 4.4): integrate role 1's shot hemicubes, B_s += rho_s sum.
    void gatherShot(uint32_t count, gl::GpuTimers& timers);
    // A reconstruction pass over every element with shooters [first, first + count) of the batch.
    void reconstruct(int mode, int receivers, uint32_t first, uint32_t count, bool insert, gl::GpuTimers& timers);
    // B as radiance into direct (E, plus the punctual lights' direct light per pixel) and indirect
    // (B - E - D) targets of the camera view.
    void display(render::SceneDrawer& drawer, const render::View& camera, const render::GBuffer& gbuffer,
                 const render::LightSet& lights, const gl::Texture& direct, const gl::Texture& indirect, bool nearest);

    // Tests: element radiosity B and Bu read back (one per element, in element order).
    std::vector<glm::vec3> readTotal() const;
    std::vector<glm::vec3> readUnshot() const;
    // Tests: the hemicube records of role `role` (gather: 0; shooters: 0-3) as the last batch placed them.
    std::vector<gpu::RadHemicubeGpu> readHemicubeRecords(uint32_t role, uint32_t count) const;
    uint32_t hemicubesRendered() const { return m_hemicubes; }
    void resetCounters() { m_hemicubes = 0; }
    float emittedPower() const { return m_emittedPower; }  // sum of A (E + D at rest, unshadowed) luminance
    // The hemicube arrays as the last batch left them (the viewer's debug views): five layers per
    // hemicube of the batch, 5 k + 0 the top face (R x R), 5 k + 1..4 the sides (the lower R/2 rows).
    const gl::Texture& idHemicubes(bool old) const { return old ? m_idA : m_idB; }  // R32UI: surface + 1 of the quad seen, 0 none
    const gl::Texture& shotHemicubes() const { return m_shot; }
    const gl::Texture& backHemicubes(bool old) const { return old ? m_backOld : m_backNew; }
    const gl::Texture& radiosityHemicubes() const { return m_radMs; }  // multisampled (gather)

private:
    void bindCommon() const;
    // Hemicube records [recordBase, + count) at elements (mode 0) or shooters' fronts (1) / backs (2).
    void placeRecords(int mode, uint32_t first, uint32_t count, uint32_t recordBase, bool old);
    std::vector<glm::vec3> readAtlas(const gl::Texture& t) const;

    PatchModel m_model;
    SystemOptions m_options;
    float m_far = 100.0f, m_offset = 1e-3f;
    float m_emittedPower = 0.0f, m_maxLightRadiance = 0.0f;
    std::vector<size_t> m_punctual;  // scene.lights indices of point, spot and directional lights
    uint32_t m_maxShooters = 0, m_hemicubes = 0;
    std::vector<gpu::ObjectGpu> m_objectData;
    std::vector<gpu::RadBodyGpu> m_bodies, m_bodiesOld;
    std::vector<char> m_moving;
    const std::vector<char>* m_movingOverride = nullptr;
    bool m_anyMoving = false, m_haveOld = false;

    gl::Texture m_total, m_unshot, m_lightNew, m_light;
    render::DirectLighting m_directLights;
    gl::Buffer m_quads, m_elements, m_triangles, m_bodyBuffer, m_bodyOldBuffer, m_objectsOld, m_shooters,
        m_records, m_stats, m_pass;
    gl::Texture m_deltaFF;
    gl::Texture m_idA, m_idB, m_shot, m_depth, m_radMs, m_depthMs, m_backMs, m_backDepthMs, m_backOld, m_backNew,
        m_weighted;
    gl::Framebuffer m_fboIdA, m_fboIdB, m_fboCombined, m_fboRad, m_fboBack, m_fboDisplay;
    gl::Texture m_displayDepth;
    glm::ivec2 m_displaySize{0};
    gl::VertexArray m_emptyVao;
    gl::Program m_hc[4], m_hcLight[4], m_display[2], m_place, m_quadStats, m_shooterPass, m_clear, m_integrateMs,
        m_integrateSingle, m_integrateMip, m_resolve, m_ffMultiply, m_reconstruct, m_lightPass;
};

}  // namespace bounce::radiosity
