// `bounce report RESULTS_DIR`: one self-contained HTML page (images and plots inlined) plus
// results.json and results.csv from a study's output folder. The page is made by
// scripts/bounce-report.py (matplotlib plots), compiled into the binary and run with python3.
#include "app/Cli.h"
#include "app/Report.h"

#include <fmt/format.h>

#include <memory>
#include <string>

namespace bounce {
namespace {

constexpr const char* kCommand = "report";

struct ReportArgs {
    std::string results;
    std::string out;
};

int runReport(const ReportArgs& args) {
    auto page = writeStudyReport(args.results, args.out);
    if (!page) return failCommand(kCommand, page.error().message);
    fmt::print("{}\n", page->string());
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
