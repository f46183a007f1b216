#pragma once
// Studies: the file `bounce sweep STUDY.json` reads, checked strictly and expanded into independent
// jobs (docs/studies.md). Parsing, validation and expansion touch no GL: every setting is applied to
// a technique created from the registry (settings are declared once, so the registry is the only
// list of techniques and settings a study knows), every scene is loaded once, and any problem is a
// one-line error "FILE:LINE: KEY: message (known: ...)" before a job runs.
#include "core/Error.h"
#include "scene/SceneLoader.h"
#include "techniques/Registry.h"

#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace bounce::study {

struct SceneSpec {
    std::string id;      // folder name: the scene's name (or file stem) and its parameters
    std::string source;  // built-in name or absolute file path, as loadScene() takes it
    SceneParams params;
};

// One point of a technique's settings grid.
struct Variant {
    std::string technique;
    std::string id;                               // folder name, from the settings
    std::map<std::string, std::string> settings;  // bare names (the technique's) and renderer.NAME
    ReferenceScope scope;
};

enum class JobKind { Reference, Render, Compare, Temporal };
const char* jobKindName(JobKind kind);

struct Job {
    JobKind kind = JobKind::Render;
    // "render/SCENE/TECHNIQUE/VARIANT", "reference/SCENE/SCOPE/fFRAME", ...: also the job's folder
    // under the output folder, so results of several machines merge by copying folders together.
    std::string id;
    // 1: renders and references (independent); 2: compares and temporal jobs, which read stage 1's
    // outputs. Schedulers run stage 2 after stage 1 (GNU parallel: a second list; Slurm: a dependency).
    int stage = 1;
    size_t scene = 0;
    std::optional<size_t> variant;  // render, compare, temporal
    ReferenceScope scope;           // reference, compare, temporal
    uint32_t frame = 0;             // reference: the frame it shows
    std::vector<std::string> inputs;  // ids of the jobs whose outputs this one reads
    // Everything the job's outputs depend on. A finished job's record holds it; a record with a
    // different spec (the study changed) does not count as finished.
    nlohmann::json spec;
};

struct ReferenceQuality {
    uint32_t spp = 64;
    double timeLimit = 0.0;  // seconds per reference image, 0 = none
    uint64_t seed = 0;
    int threads = 0;  // 0 = every core
};

struct TemporalSpec {
    bool enabled = false;
    std::vector<size_t> scenes;       // indices into Study::scenes
    std::set<std::string> techniques;  // empty: every technique of the study
    int frames = 8;
    int startFrame = 0;
    int eventFrame = 0;        // the first frame after the light or object moved
    // How run frame f shows the scene's animation (docs/studies.md "Temporal"): play: frame f; hold:
    // frame min(f, eventFrame) (the animation plays and stops at the event); step: startFrame before
    // the event and eventFrame from it on (a still scene, one jump at the event).
    enum class Animation { Play, Hold, Step };
    Animation animation = Animation::Play;
    double threshold = 0.05;   // relative RMS error against the settled image

    uint32_t sceneFrame(int frame) const {
        switch (animation) {
            case Animation::Play: break;
            case Animation::Hold: return static_cast<uint32_t>(std::min(frame, eventFrame));
            case Animation::Step: return static_cast<uint32_t>(frame < eventFrame ? startFrame : eventFrame);
        }
        return static_cast<uint32_t>(frame);
    }
};
const char* animationName(TemporalSpec::Animation a);

struct Study {
    std::filesystem::path file;    // absolute
    std::string name;
    std::filesystem::path output;  // absolute
    glm::ivec2 size{64, 64};
    int frames = 1;  // still jobs render frames [startFrame, startFrame + frames) and keep the last
    int startFrame = 0;
    std::vector<uint64_t> seeds;  // for techniques that declare a 'seed' setting
    std::map<std::string, std::string> renderer;  // renderer settings for every job
    ReferenceQuality reference;
    TemporalSpec temporal;
    std::vector<SceneSpec> scenes;
    std::vector<Variant> variants;
    std::vector<Job> jobs;  // stage 1 first; the order is stable for a given study file

    uint32_t stillFrame() const { return static_cast<uint32_t>(startFrame + frames - 1); }
    const Job* findJob(const std::string& id) const;
};

// "b1-indirect", "b0", "all-diffuse", ...: a reference scope as a folder name.
std::string scopeName(const ReferenceScope& scope);
nlohmann::json scopeJson(const ReferenceScope& scope);

// Reads, checks and expands a study. `outputOverride` (the --out flag) replaces the file's "output".
Expected<Study> loadStudy(const std::filesystem::path& file, const std::string& outputOverride);

}  // namespace bounce::study
