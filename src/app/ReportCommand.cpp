// `bounce report RESULTS_DIR`: one self-contained HTML page (images and plots inlined) plus
// results.json and results.csv from a study's output folder. The page is made by
// scripts/bounce-report.py (matplotlib plots), compiled into the binary and run with python3.
#include "app/Cli.h"
#include "app/ReportScript.h"
#include "core/FileIo.h"

#include <fmt/format.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

namespace bounce {
namespace {

namespace fs = std::filesystem;
constexpr const char* kCommand = "report";

struct ReportArgs {
    std::string results;
    std::string out;
};

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

int runReport(const ReportArgs& args) {
    auto fail = [](const std::string& m) { return failCommand(kCommand, m); };
    std::error_code ec;
    if (!fs::is_directory(args.results, ec)) return fail(fmt::format("{}: not a folder", args.results));
    if (::access(args.results.c_str(), R_OK | X_OK) != 0)
        return fail(fmt::format("{}: cannot read the folder: {}", args.results, std::strerror(errno)));
    const fs::path out = args.out.empty() ? fs::path(args.results) / "report.html" : fs::path(args.out);
    if (out.extension() != ".html") return fail(fmt::format("--out {}: the report is an .html file", out.string()));
    const fs::path outDir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(outDir, ec)) return fail(fmt::format("--out {}: folder '{}' does not exist", out.string(), outDir.string()));
    if (auto w = checkWritable(out); !w.ok()) return fail("--out " + w.error().message);
    // The script reads itself from stdin ("python3 -"): nothing to install beside the binary. Debian's
    // interpreter first: python3-matplotlib is installed for it, not for a pyenv or venv python3 on PATH.
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string command = fmt::format("{} - {} {}", python, shellQuote(args.results), shellQuote(out.string()));
    FILE* pipe = ::popen(command.c_str(), "w");
    if (!pipe) return fail(fmt::format("cannot run python3: {}", std::strerror(errno)));
    std::fputs(kReportScript, pipe);
    const int status = ::pclose(pipe);
    if (status == -1) return fail(fmt::format("python3: {}", std::strerror(errno)));
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return fail("python3 not found (scripts/install-deps.sh installs python3 and python3-matplotlib)");
    // The script prints its own one-line "bounce report: ..." error.
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return 1;
    return 0;
}

}  // namespace

void registerReportCommand(CLI::App& root, CommandAction& action) {
    auto args = std::make_shared<ReportArgs>();
    CLI::App* cmd = root.add_subcommand(kCommand, "Turn a `bounce sweep` output folder into one self-contained HTML "
                                                  "page, results.json and results.csv (docs/studies.md)");
    cmd->add_option("RESULTS_DIR", args->results, "The study's output folder (merged from any number of machines)")->required();
    cmd->add_option("--out", args->out, "The page (default RESULTS_DIR/report.html); results.json and .csv go beside it");
    cmd->callback([&action, args] { action = [args] { return runReport(*args); }; });
}

}  // namespace bounce
