#pragma once
// `bounce report` as a library: the page of a study's output folder (scripts/bounce-report.py,
// compiled in and run with python3), with results.json and results.csv beside it.
#include "core/Error.h"

#include <filesystem>

namespace bounce {

// Writes `out` (default RESULTS/report.html) and the two tables beside it; returns the page's path.
// The script's one-line error ("bounce report: ..." without the prefix) is the error's message.
Expected<std::filesystem::path> writeStudyReport(const std::filesystem::path& results, const std::filesystem::path& out = {});

}  // namespace bounce
