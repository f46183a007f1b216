#include "app/Report.h"

#include "app/ReportScript.h"
#include "core/FileIo.h"

#include <fmt/format.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>

namespace bounce {
namespace {

namespace fs = std::filesystem;

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

Expected<fs::path> writeStudyReport(const fs::path& results, const fs::path& outArg) {
    std::error_code ec;
    if (!fs::is_directory(results, ec)) return makeError("{}: not a folder", results.string());
    if (::access(results.c_str(), R_OK | X_OK) != 0)
        return makeError("{}: cannot read the folder: {}", results.string(), std::strerror(errno));
    const fs::path out = outArg.empty() ? results / "report.html" : outArg;
    if (out.extension() != ".html") return makeError("--out {}: the report is an .html file", out.string());
    const fs::path outDir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(outDir, ec)) return makeError("--out {}: folder '{}' does not exist", out.string(), outDir.string());
    if (auto w = checkWritable(out); !w.ok()) return makeError("--out {}", w.error().message);
    // The script's stdout (the page's absolute path) and stderr (its "bounce report: ..." error) go
    // to temporary files: the caller prints the one and reports the other.
    char outName[] = "/tmp/bounce-report-out-XXXXXX", errName[] = "/tmp/bounce-report-err-XXXXXX";
    const int outFd = ::mkstemp(outName);
    if (outFd < 0) return makeError("cannot make a temporary file: {}", std::strerror(errno));
    ::close(outFd);
    const int errFd = ::mkstemp(errName);
    if (errFd < 0) {
        ::unlink(outName);
        return makeError("cannot make a temporary file: {}", std::strerror(errno));
    }
    ::close(errFd);
    // The script reads itself from stdin ("python3 -"): nothing to install beside the binary. Debian's
    // interpreter first: python3-matplotlib is installed for it, not for a pyenv or venv python3 on PATH.
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string command = fmt::format("{} - {} {} >{} 2>{}", python, shellQuote(results.string()), shellQuote(out.string()),
                                            shellQuote(outName), shellQuote(errName));
    FILE* pipe = ::popen(command.c_str(), "w");
    if (!pipe) {
        ::unlink(outName);
        ::unlink(errName);
        return makeError("cannot run python3: {}", std::strerror(errno));
    }
    std::fputs(kReportScript, pipe);
    const int status = ::pclose(pipe);
    const auto outText = readTextFile(outName);
    const auto errText = readTextFile(errName);
    ::unlink(outName);
    ::unlink(errName);
    if (status == -1) return makeError("python3: {}", std::strerror(errno));
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return makeError("python3 not found (scripts/install-deps.sh installs python3 and python3-matplotlib)");
    // Everything but the script's own one-line error goes on to stderr (warnings of its libraries).
    std::istringstream lines(errText ? *errText : std::string());
    std::string message;
    const std::string prefix = "bounce report: ";
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind(prefix, 0) == 0) message = line.substr(prefix.size());
        else std::cerr << line << "\n";
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return makeError("{}", message.empty() ? fmt::format("the report script failed (status {})", status) : message);
    // The script prints the page's absolute path last.
    std::string page = outText ? *outText : std::string();
    while (!page.empty() && (page.back() == '\n' || page.back() == '\r')) page.pop_back();
    if (const size_t nl = page.rfind('\n'); nl != std::string::npos) {
        std::cout << page.substr(0, nl + 1);  // anything else it printed
        page = page.substr(nl + 1);
    }
    return page.empty() ? fs::absolute(out) : fs::path(page);
}

}  // namespace bounce
