#pragma once
// Compiler logs mapped back to bounce's shader files. Program::build assembles one text per stage
// (prelude, host defines, Bindings.h, includes expanded) without #line, because drivers differ in how
// they honour its source-string number (Mesa always reports 0); the compiler's line numbers are
// positions in that text, mapped back through the table of where each line came from. GL-free, so the
// driver formats are unit-tested (tests/unit/ShaderLogTest.cpp).
#include <fmt/format.h>

#include <regex>
#include <string>
#include <vector>

namespace bounce::gl {

// Where each line of an assembled source came from.
struct LineOrigin {
    std::string file;
    int line = 0;
};

// Rewrites the line prefixes of the drivers' logs into "file:line:": Mesa's "0:12(5):", NVIDIA's
// "0(12) :", and AMD's proprietary and Intel's Windows "ERROR: 0:12:" / "WARNING: 0:12:" (whose
// severity word stays; issue 29 #23). A number past the table is left as the driver wrote it.
inline std::string mapShaderLog(const std::string& log, const std::vector<LineOrigin>& origins) {
    // 1: line start and an optional severity word; 2: source string; 3/4: Mesa line/column;
    // 5: NVIDIA line; 6: AMD line.
    static const std::regex re(R"(((?:^|\n)(?:(?:ERROR|WARNING): )?)(\d+)(?::(\d+)\((\d+)\)|\((\d+)\)|:(\d+)(?=:))\s*:?)");
    std::string result;
    auto begin = log.cbegin();
    std::smatch m;
    while (std::regex_search(begin, log.cend(), m, re)) {
        result.append(begin, m[0].first);
        const std::string number = m[3].matched ? m[3].str() : m[5].matched ? m[5].str() : m[6].str();
        const size_t lineNo = std::stoul(number);
        if (lineNo >= 1 && lineNo <= origins.size())
            result += m[1].str() + fmt::format("{}:{}:", origins[lineNo - 1].file, origins[lineNo - 1].line);
        else
            result += m[0].str();
        begin = m[0].second;
    }
    result.append(begin, log.cend());
    while (!result.empty() && (result.back() == '\n' || result.back() == '\0')) result.pop_back();
    return result;
}

}  // namespace bounce::gl
