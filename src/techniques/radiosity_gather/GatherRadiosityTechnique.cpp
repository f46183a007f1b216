// Gather radiosity, van de Hoef 2013 sec. 4.2, Alg. 4.1 (after Cohen & Greenberg 1985):
//   for b <- 0, maxBounces: for every element i: render all B_j into a hemicube on i, multiply by
//   the delta form factors, integrate, store B_i = E_i + rho_i sum.
// Passes per sweep, in batches of RAD_MAX_BATCH elements: place hemicube records at the elements
// (random per-position rotation), render the radiosity hemicubes (RGBA16F, 4x MSAA: more visibility
// samples per pixel at a 64^2 top face, sec. 4.2), integrate (compute reduction with the resolve
// folded in, or the mip-chain fallback), write B. Each batch sees the previous batches' new values
// (Gauss-Seidel, as Cohen & Greenberg), so `bounces` sweeps carry at least that many bounces.
// The solution restarts from B = E every frame (sec. 5.2: gather does not reuse the last frame), so
// it follows moving objects and lights by construction; at high settings it is the radiosity
// reference of the other three methods (the thesis's reference images, Table 5.1).
// Deviation: elements in RGBA32F (thesis: RGBA16F), shared with the other methods.
// Progress (bounce's, issue 30): the gather is the expensive reference (minutes on the larger scenes
// on llvmpipe), so with `progress` on (auto: stderr is a terminal) it says up front how long it will
// take (hemicubes x the time per hemicube measured over the first batch; auto: only for a gather
// estimated at kProgressIntervalS or more) and then, at most every
// kProgressIntervalS, the hemicubes done, the elapsed and the estimated remaining time, on stderr.
// Measuring needs the GPU's work done: glFinish after each batch, only while reporting.
#include "techniques/radiosity_gather/GatherRadiosityTechnique.h"

#include <fmt/format.h>
#include "gpu/Context.h"

#include <chrono>
#include <cstdio>
#include <unistd.h>

namespace bounce {

void GatherRadiosityTechnique::visitMethodSettings(SettingsVisitor& v) {
    v.field("bounces", m_bounces, "gather sweeps over all elements per frame (thesis: capped, value not given)", 1, 1000);
    v.field("msaa", m_msaa, "samples per radiosity-hemicube pixel (thesis sec. 5.3.1: 4)", 1, 16);
    v.field("integration", m_integration, "compute: parallel reduction (thesis's choice); mipmap: the DX10 fallback (1x1 mip level x pixel count)", kIntegrations);
    v.field("progress", m_progress,
            "progress and estimated time on stderr while gathering, at most a line every 2 s: auto (when stderr is a terminal and the "
            "gather is estimated at 2 s or more), on, off",
            kProgress);
}

void GatherRadiosityTechnique::adjustOptions(radiosity::SystemOptions& o) const {
    o.msaa = m_msaa;
    o.mipIntegration = m_integration == "mipmap";
}

void GatherRadiosityTechnique::solve(FrameContext& ctx) {
    m_system->beginFrame(ctx.scene, ctx.time);
    m_system->computeLights(ctx.lights);
    m_system->reset(RAD_RECEIVERS_ALL, true);
    m_progressLines.clear();
    const bool report = m_progress == "on" || (m_progress == "auto" && ::isatty(STDERR_FILENO) != 0);
    // auto stays silent for a gather estimated shorter than one progress interval (the viewer's
    // frame-by-frame gathers at coarse settings); on always reports.
    const bool always = m_progress == "on";
    if (!report) {
        for (int b = 0; b < m_bounces; ++b) m_system->gatherSweep(ctx.drawer, ctx.timers);
    } else {
        using Clock = std::chrono::steady_clock;
        const auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
        const uint64_t perSweep = m_system->gatherElementCount();
        const uint64_t total = perSweep * static_cast<uint64_t>(m_bounces);
        bool speak = always;
        const auto emit = [&](std::string line) {
            if (!speak) return;
            std::fprintf(stderr, "%s\n", line.c_str());
            std::fflush(stderr);
            m_progressLines.push_back(std::move(line));
        };
        glFinish();  // the frame's earlier passes are not the gather's
        const Clock::time_point start = Clock::now();
        Clock::time_point lastLine = start;
        bool estimated = false;
        for (int b = 0; b < m_bounces; ++b) {
            m_system->gatherSweep(ctx.drawer, ctx.timers, [&](uint32_t doneInSweep) {
                glFinish();
                const Clock::time_point now = Clock::now();
                const uint64_t done = perSweep * static_cast<uint64_t>(b) + doneInSweep;
                const double elapsed = seconds(start, now);
                const double perHemicube = elapsed / static_cast<double>(done);
                const double remaining = perHemicube * static_cast<double>(total - done);
                if (!estimated) {
                    speak = speak || perHemicube * static_cast<double>(total) >= kProgressIntervalS;
                    emit(fmt::format("radiosity-gather: {} hemicubes ({} elements x {} sweeps), {:.1f} ms each over the first "
                                     "batch: about {:.0f} s",
                                     total, perSweep, m_bounces, 1e3 * perHemicube, perHemicube * static_cast<double>(total)));
                    estimated = true;
                    lastLine = now;
                } else if (seconds(lastLine, now) >= kProgressIntervalS && done < total) {
                    emit(fmt::format("radiosity-gather: sweep {}/{}, {}/{} hemicubes ({:.0f} %), {:.0f} s elapsed, about {:.0f} s "
                                     "remaining",
                                     b + 1, m_bounces, done, total, 100.0 * static_cast<double>(done) / static_cast<double>(total),
                                     elapsed, remaining));
                    lastLine = now;
                }
            });
        }
        emit(fmt::format("radiosity-gather: {} hemicubes in {:.1f} s", total, seconds(start, Clock::now())));
    }
    m_frameIterations = static_cast<uint32_t>(m_bounces);
    m_converged = true;
    m_system->commit();
}

}  // namespace bounce
