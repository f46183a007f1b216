// `bounce photon-map`: the photon-mapping ground truth of a scene (src/reference/PhotonMap.h), run
// like `bounce reference`: flags checked before any work, progress on stderr, a time limit, a run
// record, one-line errors and no half-written output. docs/techniques/photon-map.md documents it.
#include "app/Cli.h"
#include "app/CpuJobOptions.h"
#include "app/Options.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/ToneMap.h"
#include "reference/PhotonMapJob.h"
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

constexpr const char* kCommand = "photon-map";

int runPhotonMap(const PhotonMapArgs& args) {
    return runCpuJobCommand(
        kCommand, args, photonMapJobFromArgs(args),
        [&](const Scene& scene, const PhotonMapJob& job, ProgressLine& line) {
            return runPhotonMapJob(scene, job, [&](const PhotonMapProgress& p) {
                const double fraction = static_cast<double>(p.done) / static_cast<double>(std::max<uint64_t>(1, p.target));
                const bool tracing = p.phase == PhotonMapProgress::Phase::Tracing;
                line.draw(tracing ? "photon-map tracing" : "photon-map gathered", fraction, "  %llu/%llu %s  %.1f s   ",
                          static_cast<unsigned long long>(p.done), static_cast<unsigned long long>(p.target),
                          tracing ? "photons" : "rows", p.elapsedSeconds);
            });
        },
        [&](const Scene& scene, const PhotonMapJob& job, const PhotonMapResult& r) {
            const PhotonMapSettings& s = job.settings;
            // The one-line summary goes to stdout whatever --log-level says (docs/reference.md shows it).
            fmt::print("photon-map: {} {}x{}, {} photons emitted{}, {} stored ({:.1f} MB), k {}: trace {:.1f} s, tree {:.2f} s, "
                       "gather {:.1f} s; mean radius {:.4f} m; wrote {}{}\n",
                       scene.name, s.width, s.height, r.photonsEmitted,
                       r.stoppedByTimeLimit ? fmt::format(" (time limit; {} asked)", args.photons) : std::string(),
                       r.photonsStored, static_cast<double>(r.mapBytes) * 1e-6, s.k, r.traceSeconds, r.treeSeconds,
                       r.gatherSeconds, r.meanGatherRadius, args.out, args.stats.empty() ? std::string() : " and " + args.stats);
        });
}

}  // namespace

void registerPhotonMapCommand(CLI::App& root, CommandAction& action) {
    auto args = std::make_shared<PhotonMapArgs>();
    CLI::App* cmd = root.add_subcommand(kCommand, "Render a scene by CPU photon mapping (Embree, nanoflann kd-tree, "
                                                  "k-nearest radiance estimate): the ground truth of photon splatting");
    addCpuJobOptions(cmd, *args,
                     {"Indirect bounces K as `bounce reference`: photons are stored after at most K reflections",
                      "Store photons only after their first reflection: the light of `bounce reference --indirect-only`",
                      "Photons bounce by the Lambert lobe alone",
                      "Stop tracing photons after the last pass that started within SEC seconds (0 = no limit)"});
    cmd->add_option("--photons", args->photons, "Photons emitted from the lights")->capture_default_str();
    cmd->add_option("--k", args->k, "Nearest photons per estimate (k-1 summed inside the k-th's radius)")
        ->capture_default_str();
    cmd->add_option("--max-radius", args->maxRadius, "Cap on the gather radius in metres (0 = none)")->capture_default_str();
    cmd->add_option("--spp", args->spp, "Jittered camera rays (gathers) per pixel")->capture_default_str();
    cmd->callback([&action, args] { action = [args] { return runPhotonMap(*args); }; });
}

}  // namespace bounce
