// `bounce reference`: the ground-truth image of a scene, from the CPU path tracer (Embree + TBB).
// docs/reference.md documents the light-transport scopes, the run record and the noise estimate.
#include "app/Cli.h"
#include "app/CpuJobOptions.h"
#include "app/Options.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/ToneMap.h"
#include "reference/ReferenceJob.h"
#include "scene/SceneLoader.h"

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace bounce {
namespace {

constexpr const char* kCommand = "reference";

int runReference(const ReferenceArgs& args) {
    return runCpuJobCommand(
        kCommand, args, referenceJobFromArgs(args),
        [&](const Scene& scene, const ReferenceJob& job, ProgressLine& line) {
            return runReferenceJob(scene, job, [&](const RenderProgress& p) {
                const double fraction = static_cast<double>(p.samplesDone) / std::max(1u, p.samplesTarget);
                double eta = fraction > 0.0 ? p.elapsedSeconds * (1.0 - fraction) / fraction : 0.0;
                if (args.timeLimit > 0.0) eta = std::min(eta, std::max(0.0, args.timeLimit - p.elapsedSeconds));
                line.draw(kCommand, fraction, "  %u/%u spp  %.1f s  ETA %.0f s   ", p.samplesDone, p.samplesTarget,
                          p.elapsedSeconds, eta);
            });
        },
        [&](const Scene& scene, const ReferenceJob& job, const PathTracerResult& r) {
            // The one-line summary goes to stdout whatever --log-level says (docs/reference.md shows it).
            fmt::print("reference: {} {}x{}, {} spp{} in {:.1f} s ({:.2f} M paths/s, {:.1f} M rays/s); noise {:.2f}% per "
                       "pixel, {:.3f}% image mean; wrote {}{}\n",
                       scene.name, job.settings.width, job.settings.height, r.samplesPerPixel,
                       r.stoppedByTimeLimit ? fmt::format(" (time limit; {} asked)", args.spp) : std::string(),
                       r.renderSeconds, r.pathsPerSecond() * 1e-6, r.raysPerSecond() * 1e-6,
                       100.0 * r.noise.meanPixelRelativeError, 100.0 * r.noise.imageRelativeError, args.out,
                       args.stats.empty() ? std::string() : " and " + args.stats);
        });
}

}  // namespace

void registerReferenceCommand(CLI::App& root, CommandAction& action) {
    auto args = std::make_shared<ReferenceArgs>();
    CLI::App* cmd = root.add_subcommand(kCommand, "Render the ground truth of a scene with the CPU path tracer "
                                                  "(Embree, TBB): EXR radiance or tone-mapped PNG, plus a run record");
    addCpuJobOptions(cmd, *args,
                     {"Indirect bounces K (paths reflect at most K+1 times; 0 = direct light only), or 'unbounded'",
                      "Keep only light that reflected at least twice (full minus emitted and direct)",
                      "Use only the Lambert lobe after the first reflection",
                      "Stop after the last pass that fits in SEC seconds (0 = no limit); the record keeps the spp reached"});
    cmd->add_option("--spp", args->spp, "Samples (camera paths) per pixel")->capture_default_str();
    cmd->add_option("--first-reflection", args->firstReflection,
                    "cosine: the cosine lobe (the reference); vct-cones: a diagnostic, vct's six 60-degree cones and "
                    "weights over the exact incident light (docs/techniques/vct.md, \"The six cones' own bias\")")
        ->capture_default_str();
    cmd->add_option("--variance", args->variance,
                    "Also write the per-pixel variance of the image (.exr, needs --stats): `bounce compare` reads it "
                    "to print the reference's noise floor of every metric");
    cmd->callback([&action, args] { action = [args] { return runReference(*args); }; });
}

}  // namespace bounce
