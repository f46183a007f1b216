#pragma once
// Line numbers for values of a JSON document. nlohmann::json (3.11) keeps no source positions, so
// errors found after parsing ("light 'key': intensity is negative") are located by scanning the text
// once and recording where each value (by JSON pointer, "/lights/0/intensity") starts.
#include "core/Error.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>

namespace bounce {

// Deepest nesting of arrays and objects a bounce JSON file may have (scene files need 7 levels). It
// bounds the work of a pathological file: JsonLocator's scan recurses once per level and records a
// pointer as long as the depth, so an unbounded depth overflows the stack.
inline constexpr int kMaxJsonDepth = 64;

// Parses a JSON file's text (scene files, studies, camera paths) with every problem as one error
// "NAME:LINE:COLUMN: malformed JSON: ...": syntax errors, numbers that overflow a double (1e999), and
// nesting deeper than kMaxJsonDepth. No nlohmann exception escapes.
Expected<nlohmann::json> parseJsonDocument(const std::string& text, const std::string& name);

class JsonLocator {
public:
    // `text` must be valid JSON at most kMaxJsonDepth deep (parseJsonDocument checks both); the scan
    // does not re-validate.
    explicit JsonLocator(std::string_view text);

    // 1-based line of the member key (for object members) or value at `pointer`; the nearest located
    // ancestor's line when `pointer` itself is not in the document; 0 for an empty document.
    int line(const std::string& pointer) const;

    // 1-based line and column of byte offset `offset` in `text`.
    static std::pair<int, int> lineColumn(std::string_view text, size_t offset);

private:
    void value(const std::string& pointer);
    void skipWhitespace();
    std::string string();

    std::string_view m_text;
    size_t m_pos = 0;
    int m_line = 1;
    std::map<std::string, int> m_lines;
};

}  // namespace bounce
