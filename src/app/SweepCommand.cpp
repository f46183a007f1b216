// `bounce sweep STUDY.json`: runs a study's jobs locally (--jobs N worker processes, progress bar),
// one job (--job ID, what GNU parallel and Slurm array tasks call), lists them (--list), or writes
// job lists for existing schedulers (--emit parallel|slurm). docs/studies.md is the user's guide.
#include "app/Cli.h"
#include "app/StudyRun.h"
#include "app/SweepJobs.h"
#include "core/FileIo.h"
#include "gpu/DeviceSelection.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

extern char** environ;

namespace bounce {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using study::Job;
using study::Study;

constexpr const char* kCommand = "sweep";
constexpr int kBarWidth = 30;  // characters

struct SweepArgs {
    std::string studyFile;
    std::string out;
    int jobs = 1;
    bool jobsGiven = false;  // --jobs on the command line; otherwise one worker per GPU (docs/gpu.md)
    bool list = false;
    std::string job;
    std::string emit;
    bool progress = false;
};

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string selfExe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("bounce") : p.string();
}

std::string jobCommand(const Study& s, const Job& j) {
    return fmt::format("{} sweep {} --out {} --job {}", shellQuote(selfExe()), shellQuote(s.file.string()),
                       shellQuote(s.output.string()), shellQuote(j.id));
}

std::string logName(const std::string& id) {
    std::string out = id;
    for (char& c : out)
        if (c == '/') c = '~';
    return out + ".log";
}

class ProgressBar {
public:
    ProgressBar(bool enabled, size_t total) : m_enabled(enabled), m_total(total), m_start(std::chrono::steady_clock::now()) {}
    void update(size_t done, size_t running, size_t failed) {
        if (!m_enabled || m_total == 0) return;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
        const double fraction = static_cast<double>(done) / static_cast<double>(m_total);
        const std::string eta = done > 0 ? fmt::format("ETA {}", clock(elapsed / static_cast<double>(done) * static_cast<double>(m_total - done))) : "ETA ?";
        const int filled = static_cast<int>(fraction * kBarWidth);
        std::fprintf(stderr, "\rsweep [%s%s] %zu/%zu jobs  %zu running%s  %s  %s   ",
                     std::string(static_cast<size_t>(filled), '#').c_str(),
                     std::string(static_cast<size_t>(kBarWidth - filled), '-').c_str(), done, m_total, running,
                     failed ? fmt::format("  {} failed", failed).c_str() : "", clock(elapsed).c_str(), eta.c_str());
        std::fflush(stderr);
        m_drawn = true;
    }
    ~ProgressBar() { finish(); }
    void finish() {
        if (m_drawn) std::fputc('\n', stderr);
        m_drawn = false;
    }

private:
    static std::string clock(double seconds) {
        const long s = static_cast<long>(seconds + 0.5);
        return s >= 60 ? fmt::format("{}m{:02}s", s / 60, s % 60) : fmt::format("{}s", s);
    }
    bool m_enabled;
    size_t m_total;
    std::chrono::steady_clock::time_point m_start;
    bool m_drawn = false;
};

// Starts `bounce sweep STUDY --out OUT --job ID` with its output in OUT/logs/ID.log, on EGL device
// `device` (BOUNCE_EGL_DEVICE in its environment) when given.
Expected<pid_t> spawnJob(const Study& s, const Job& j, std::optional<int> device) {
    const fs::path log = s.output / "logs" / logName(j.id);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    const std::string exe = selfExe(), file = s.file.string(), out = s.output.string();
    std::vector<std::string> args = {exe, "sweep", file, "--out", out, "--job", j.id};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e)
        if (!device || std::string_view(*e).rfind("BOUNCE_EGL_DEVICE=", 0) != 0) env.emplace_back(*e);
    if (device) env.push_back(fmt::format("BOUNCE_EGL_DEVICE={}", *device));
    std::vector<char*> envp;
    for (std::string& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return makeError("cannot start {}: {}", exe, std::strerror(rc));
    return pid;
}

// The EGL device of each worker slot: round robin over the hardware devices (none on llvmpipe-only
// machines: workers take the automatic choice, as before); --gpu / BOUNCE_EGL_DEVICE pins all of them.
std::vector<std::optional<int>> workerDevices(int jobs) {
    auto devices = gl::enumerateEglDevices();
    auto request = gl::deviceRequestFromEnvironment();
    if (!devices.ok() || !request.ok()) return std::vector<std::optional<int>>(static_cast<size_t>(jobs));
    return gl::sweepWorkerDevices(*devices, *request, jobs);
}

int runLocal(const Study& s, const SweepArgs& args) {
    std::error_code ec;
    fs::create_directories(s.output / "logs", ec);
    if (ec) return failCommand(kCommand, fmt::format("{}: {}", (s.output / "logs").string(), ec.message()));
    std::vector<const Job*> pending;
    size_t finishedBefore = 0;
    for (const Job& j : s.jobs) {
        if (study::jobFinished(s, j)) ++finishedBefore;
        else pending.push_back(&j);
    }
    ProgressBar bar(args.progress || ::isatty(STDERR_FILENO) != 0, s.jobs.size());
    size_t done = finishedBefore;
    std::set<std::string> failed;
    std::vector<std::string> failedList;
    size_t blocked = 0;
    for (int stage = 1; stage <= 2; ++stage) {
        std::vector<const Job*> queue;
        for (const Job* j : pending)
            if (j->stage == stage) queue.push_back(j);
        std::map<pid_t, const Job*> running;
        std::map<pid_t, size_t> slotOf;  // worker slot of each running job
        const std::vector<std::optional<int>> devices = workerDevices(args.jobs);
        std::vector<bool> slotBusy(devices.size(), false);
        size_t next = 0;
        bar.update(done, 0, failed.size());
        while (next < queue.size() || !running.empty()) {
            while (next < queue.size() && running.size() < static_cast<size_t>(args.jobs)) {
                const Job* j = queue[next++];
                bool inputsFailed = false;
                for (const std::string& in : j->inputs) inputsFailed |= failed.count(in) > 0;
                if (inputsFailed) {  // its inputs failed: it would only fail too
                    ++blocked;
                    failed.insert(j->id);
                    continue;
                }
                const size_t slot = static_cast<size_t>(std::find(slotBusy.begin(), slotBusy.end(), false) - slotBusy.begin());
                auto pid = spawnJob(s, *j, devices[slot]);
                if (!pid) return failCommand(kCommand, pid.error().message);
                running[*pid] = j;
                slotOf[*pid] = slot;
                slotBusy[slot] = true;
            }
            bar.update(done, running.size(), failed.size());
            if (running.empty()) continue;
            int status = 0;
            const pid_t pid = ::waitpid(-1, &status, 0);
            if (pid < 0) return failCommand(kCommand, fmt::format("waitpid: {}", std::strerror(errno)));
            auto it = running.find(pid);
            if (it == running.end()) continue;
            const Job* j = it->second;
            running.erase(it);
            slotBusy[slotOf[pid]] = false;
            slotOf.erase(pid);
            ++done;
            if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
                failed.insert(j->id);
                failedList.push_back(j->id);
            }
            bar.update(done, running.size(), failed.size());
        }
    }
    bar.finish();
    size_t refused = 0;
    for (const Job& j : s.jobs) {
        auto text = readTextFile(study::recordPath(s, j));
        if (!text) continue;
        const json record = json::parse(*text, nullptr, /*allow_exceptions=*/false);
        if (record.is_object() && record.value("status", "ok") != "ok") ++refused;
    }
    fmt::print("sweep: {} jobs in {}: {} ran, {} already finished, {} refused or skipped by the technique\n",
               s.jobs.size(), s.output.string(), pending.size() - failed.size(), finishedBefore, refused);
    if (!failedList.empty() || blocked)
        return failCommand(kCommand, fmt::format("{} job(s) failed ({}{}){}; their logs are in {}", failedList.size(),
                                                 failedList.empty() ? "" : failedList.front(),
                                                 failedList.size() > 1 ? ", ..." : "",
                                                 blocked ? fmt::format(", {} not started because their inputs failed", blocked) : "",
                                                 (s.output / "logs").string()));
    return 0;
}

Expected<void> writeExecutable(const fs::path& path, const std::string& text) {
    BOUNCE_TRY_VOID(writeTextFileAtomic(path, text));
    std::error_code ec;
    fs::permissions(path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec, ec);
    if (ec) return makeError("{}: {}", path.string(), ec.message());
    return {};
}

int emit(const Study& s, const SweepArgs& args) {
    const fs::path dir = s.output / "jobs";
    std::error_code ec;
    fs::create_directories(dir, ec);
    fs::create_directories(s.output / "logs", ec);
    if (ec) return failCommand(kCommand, fmt::format("{}: {}", dir.string(), ec.message()));
    std::string lists[2];
    size_t counts[2] = {0, 0};
    for (const Job& j : s.jobs) {
        lists[j.stage - 1] += jobCommand(s, j) + "\n";
        ++counts[j.stage - 1];
    }
    for (int stage = 1; stage <= 2; ++stage)
        if (auto w = writeTextFileAtomic(dir / fmt::format("stage{}.txt", stage), lists[stage - 1]); !w)
            return failCommand(kCommand, w.error().message);
    if (args.emit == "parallel") {
        const std::string script = fmt::format(
            "#!/bin/sh\n"
            "# Study '{0}' with GNU parallel: stage 1 (renders, references), then stage 2 (compares,\n"
            "# temporal jobs), which reads stage 1's outputs. A finished job is skipped, so rerunning is safe.\n"
            "# More hosts: PARALLEL_OPTS='--sshloginfile hosts.txt' (each host needs bounce, the study and the\n"
            "# output folder at the same paths, e.g. a shared file system; or copy output folders together).\n"
            "here=$(cd \"$(dirname \"$0\")\" && pwd)\n"
            "status=0\n"
            "parallel --will-cite -j {1} ${{PARALLEL_OPTS:-}} --joblog \"$here/stage1.joblog\" < \"$here/stage1.txt\" || status=1\n"
            "parallel --will-cite -j {1} ${{PARALLEL_OPTS:-}} --joblog \"$here/stage2.joblog\" < \"$here/stage2.txt\" || status=1\n"
            "exit $status\n",
            s.name, args.jobs);
        if (auto w = writeExecutable(dir / "run-parallel.sh", script); !w) return failCommand(kCommand, w.error().message);
        fmt::print("sweep: {} + {} jobs listed in {}/stage1.txt and stage2.txt; run them with {}/run-parallel.sh\n",
                   counts[0], counts[1], dir.string(), dir.string());
        return 0;
    }
    for (int stage = 1; stage <= 2; ++stage) {
        const std::string script = fmt::format(
            "#!/bin/bash\n"
            "# Study '{0}', stage {1}: a Slurm job array, task K runs line K of stage{1}.txt.\n"
            "#SBATCH --job-name=bounce-{0}-{1}\n"
            "#SBATCH --array=1-{2}\n"
            "#SBATCH --output={3}/slurm-stage{1}-%a.log\n"
            "set -euo pipefail\n"
            "line=$(sed -n \"${{SLURM_ARRAY_TASK_ID}}p\" {4})\n"
            "eval \"$line\"\n",
            s.name, stage, std::max<size_t>(counts[stage - 1], 1), (s.output / "logs").string(),
            shellQuote((dir / fmt::format("stage{}.txt", stage)).string()));
        if (auto w = writeExecutable(dir / fmt::format("slurm-stage{}.sbatch", stage), script); !w)
            return failCommand(kCommand, w.error().message);
    }
    const std::string submit = fmt::format(
        "#!/bin/sh\n"
        "# Submits study '{0}': the stage 1 array, then the stage 2 array once every stage 1 task ended\n"
        "# (afterany: a failed task's dependants fail with a message naming it). Extra sbatch options\n"
        "# (partition, --gres=gpu:1, ...) in SBATCH_OPTS. Prints the job ids, one per stage.\n"
        "set -eu\n"
        "here=$(cd \"$(dirname \"$0\")\" && pwd)\n"
        "dep=\"\"\n"
        "{1}"
        "{2}",
        s.name,
        counts[0] ? "id1=$(sbatch --parsable ${SBATCH_OPTS:-} \"$here/slurm-stage1.sbatch\")\nid1=${id1%%;*}\necho \"$id1\"\ndep=\"--dependency=afterany:$id1\"\n" : "",
        counts[1] ? "id2=$(sbatch --parsable ${SBATCH_OPTS:-} $dep \"$here/slurm-stage2.sbatch\")\necho \"${id2%%;*}\"\n" : "");
    if (auto w = writeExecutable(dir / "submit-slurm.sh", submit); !w) return failCommand(kCommand, w.error().message);
    fmt::print("sweep: {} + {} jobs as Slurm arrays {}/slurm-stage1.sbatch and slurm-stage2.sbatch; submit with {}/submit-slurm.sh\n",
               counts[0], counts[1], dir.string(), dir.string());
    return 0;
}

int runSweepWith(const SweepArgs& args);

int runSweep(const SweepArgs& args) {
    auto fail = [](const std::string& m) { return failCommand(kCommand, m); };
    if (args.jobs < 1) return fail(fmt::format("--jobs {}: at least one", args.jobs));
    SweepArgs a = args;
    if (!a.jobsGiven && a.job.empty() && !a.list) {
        // One worker per hardware GPU by default; 1 where there is none (llvmpipe: unchanged).
        auto devices = gl::enumerateEglDevices();
        auto request = gl::deviceRequestFromEnvironment();
        if (devices.ok() && request.ok()) a.jobs = gl::defaultSweepJobs(*devices, *request);
    }
    return runSweepWith(a);
}

int runSweepWith(const SweepArgs& args) {
    auto fail = [](const std::string& m) { return failCommand(kCommand, m); };
    if (!args.emit.empty() && args.emit != "parallel" && args.emit != "slurm")
        return fail(fmt::format("--emit: unknown scheduler '{}' (known: parallel, slurm)", args.emit));
    if (static_cast<int>(args.list) + static_cast<int>(!args.job.empty()) + static_cast<int>(!args.emit.empty()) > 1)
        return fail("--list, --job and --emit exclude each other");
    auto loaded = study::loadStudy(args.studyFile, args.out);
    if (!loaded) return fail(loaded.error().message);
    const Study& s = *loaded;
    if (args.list) {
        for (const Job& j : s.jobs)
            fmt::print("{} {:<9} {:<8} {}\n", j.stage, study::jobKindName(j.kind), study::jobFinished(s, j) ? "finished" : "pending", j.id);
        return 0;
    }
    if (!args.job.empty()) {
        const Job* j = s.findJob(args.job);
        if (!j) return fail(fmt::format("--job '{}': no such job in {} (bounce sweep {} --list shows them)", args.job, args.studyFile, args.studyFile));
        if (study::jobFinished(s, *j)) {
            spdlog::info("{}: already finished", j->id);
            return 0;
        }
        if (auto r = study::runJob(s, *j); !r) return fail(fmt::format("{}: {}", j->id, r.error().message));
        return 0;
    }
    if (auto w = study::writeStudyCopy(s); !w) return fail(w.error().message);
    if (!args.emit.empty()) return emit(s, args);
    return runLocal(s, args);
}

}  // namespace

void registerSweepCommand(CLI::App& root, CommandAction& action) {
    auto args = std::make_shared<SweepArgs>();
    CLI::App* cmd = root.add_subcommand(kCommand, "Run a study: scenes x techniques x settings grids, with shared "
                                                  "references, compares and temporal metrics (docs/studies.md)");
    cmd->add_option("STUDY", args->studyFile, "Study file (.json)")->required();
    cmd->add_option("--out", args->out, "Output folder (default: the study's \"output\", beside the study file)");
    cmd->add_option("--jobs", args->jobs, "Jobs run at once on this machine (each uses every core); default: one per "
                                          "hardware GPU, spread over them (BOUNCE_EGL_DEVICE per worker), 1 without a GPU")
        ->capture_default_str();
    cmd->add_flag("--list", args->list, "List the jobs (stage, kind, finished/pending, id) and exit");
    cmd->add_option("--job", args->job, "Run one job by id (what GNU parallel and Slurm tasks call)");
    cmd->add_option("--emit", args->emit, "Write job lists for a scheduler instead of running: parallel or slurm");
    cmd->add_flag("--progress", args->progress, "Draw the progress bar even when stderr is not a terminal");
    cmd->callback([&action, args, cmd] {
        args->jobsGiven = cmd->count("--jobs") > 0;
        action = [args] { return runSweep(*args); };
    });
}

}  // namespace bounce
