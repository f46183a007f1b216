#pragma once
// The options `bounce reference` and `bounce photon-map` share (scene, size, light-transport scope,
// time limit, seed, threads, frame, outputs, tone mapping, progress): declared once, checked once
// before any work. Each command adds its own (--spp, --photons, ...) and fills its job from these.
#include "app/Cli.h"
#include "app/Options.h"
#include "core/Error.h"
#include "core/ToneMap.h"
#include "reference/PhotonMapJob.h"
#include "reference/ReferenceJob.h"
#include "scene/SceneLoader.h"

#include <CLI/CLI.hpp>
#include <glm/vec2.hpp>

#include <unistd.h>

#include <string>
#include <vector>

namespace bounce {

struct CpuJobArgs {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string size = "512x512";
    std::string bounces = "unbounded";
    bool indirectOnly = false;
    bool diffuseOnly = false;
    double timeLimit = 0.0;
    uint64_t seed = 0;
    int threads = 0;
    uint32_t frame = 0;
    std::string out;
    std::string stats;
    float exposureEv = 0.0f;
    std::string toneCurve = "aces";
    bool progress = false;
    CLI::Option* exposureOption = nullptr;
    CLI::Option* toneCurveOption = nullptr;
};

// The help texts that differ between the commands.
struct CpuJobHelp {
    const char* bounces;
    const char* indirectOnly;
    const char* diffuseOnly;
    const char* timeLimit;
};

void addCpuJobOptions(CLI::App* cmd, CpuJobArgs& args, const CpuJobHelp& help);

// The shared options, checked: one-line errors name the flag. `command` prefixes the warnings.
struct CpuJobCommon {
    SceneParams sceneParams;
    glm::ivec2 size{0};
    int bounces = 0;  // kUnbounded (-1) for 'unbounded'
    ToneMap toneMap;
};
// An empty `out` is allowed (no file is written; the library's callers keep the result).
Expected<CpuJobCommon> checkCpuJobArgs(const CpuJobArgs& args, const char* command, int unbounded);

// `bounce reference` and `bounce photon-map` as library calls (the commands and `import bounce`):
// every flag checked, one-line errors naming it, and the job filled in. The scene is loaded by the
// caller (`args.scene` names it in the record). Writing files is the job's: none when `out` is empty.
struct ReferenceArgs : CpuJobArgs {
    uint32_t spp = 256;
    std::string variance;  // --variance: the per-pixel variance image (.exr) beside the image
    std::string firstReflection = "cosine";  // --first-reflection: cosine | vct-cones (a diagnostic)
};
Expected<ReferenceJob> referenceJobFromArgs(const ReferenceArgs& args);

struct PhotonMapArgs : CpuJobArgs {
    uint64_t photons = 1'000'000;
    int k = 100;
    float maxRadius = 0.0f;
    uint32_t spp = 4;
};
Expected<PhotonMapJob> photonMapJobFromArgs(const PhotonMapArgs& args);

// The reference's noise floors (metrics/NoiseFloor.h, at compare's default display transforms) in its
// run record's "noise": {"floor": {"relMse": ..., ...}}; what `bounce compare` reads beside it.
void addNoiseFloor(nlohmann::ordered_json& record, const PathTracerResult& result);

// One progress line on stderr, redrawn in place while a CPU job runs:
// "LABEL [#####---------] NN%DETAIL", DETAIL printf-formatted. finish() ends the line.
class ProgressLine {
public:
    explicit ProgressLine(bool enabled) : m_enabled(enabled) {}
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;
    ~ProgressLine() { finish(); }
    void draw(const char* label, double fraction, const char* detailFormat, ...) __attribute__((format(printf, 4, 5)));
    void finish();

private:
    bool m_enabled;
    bool m_drawn = false;
};

// The body `bounce reference` and `bounce photon-map` share: the checked job (its flag errors end the
// command before the scene is loaded), the scene loaded and its one-sided surfaces warned about, the
// job run by run(scene, job, progressLine) with a progress line (--progress, or stderr a terminal),
// and on success summary(scene, job, result), the command's one-line summary on stdout.
template <class Job, class Run, class Summary>
int runCpuJobCommand(const char* command, const CpuJobArgs& args, const Expected<Job>& job, Run run, Summary summary) {
    const auto fail = [&](const std::string& message) { return failCommand(command, message); };
    // Every flag is checked before the scene is loaded, so a typo costs nothing.
    if (!job) return fail(job.error().message);
    auto scene = loadScene(args.scene, job->sceneParams);
    if (!scene) return fail(scene.error().message);
    warnOneSidedSurfaces(*scene, {job->settings.width, job->settings.height}, args.frame);
    ProgressLine progress(args.progress || ::isatty(STDERR_FILENO) != 0);
    auto result = run(*scene, *job, progress);
    progress.finish();
    if (!result) return fail(result.error().message);
    summary(*scene, *job, *result);
    return 0;
}

}  // namespace bounce
