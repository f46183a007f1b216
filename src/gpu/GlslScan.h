#pragma once
// Text scans of GLSL sources that need no GL (unit-tested in tests/unit/GlslScanTest.cpp). Hand-written
// instead of std::regex: ProgramChecks ran a regex per storage block per stage on every program build,
// which was 69 % of radiosity's set-up under the sanitizers (2.6 s a pipeline; perf, issue 30 CI time).
#include <cctype>
#include <string_view>

namespace bounce::gl {

inline bool isGlslWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

// Whether `text` declares a buffer block named `name`: the word `buffer`, white space, then `name` as a
// whole word (what the regex `\bbuffer\s+NAME\b` matched).
inline bool declaresBufferBlock(std::string_view text, std::string_view name) {
    constexpr std::string_view kKeyword = "buffer";
    if (name.empty()) return false;
    for (size_t at = text.find(kKeyword); at != std::string_view::npos; at = text.find(kKeyword, at + 1)) {
        if (at > 0 && isGlslWordChar(text[at - 1])) continue;
        size_t p = at + kKeyword.size();
        const size_t spaceFrom = p;
        while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p])) != 0) ++p;
        if (p == spaceFrom || text.compare(p, name.size(), name) != 0) continue;
        const size_t end = p + name.size();
        if (end == text.size() || !isGlslWordChar(text[end])) return true;
    }
    return false;
}

}  // namespace bounce::gl
