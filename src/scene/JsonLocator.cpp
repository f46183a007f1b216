#include "scene/JsonLocator.h"

namespace bounce {

namespace {
// JSON pointer escaping (RFC 6901): '~' -> "~0", '/' -> "~1".
std::string escapePointerToken(const std::string& token) {
    std::string out;
    for (char c : token) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}
// Byte offset where the nesting first exceeds `limit` levels, or npos. Brackets inside strings do not count.
size_t tooDeepAt(std::string_view text, int limit) {
    int depth = 0;
    bool inString = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > limit) return i;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return std::string_view::npos;
}
}  // namespace

Expected<nlohmann::json> parseJsonDocument(const std::string& text, const std::string& name) {
    // Before parsing: nlohmann would build the whole deep document first.
    if (const size_t at = tooDeepAt(text, kMaxJsonDepth); at != std::string_view::npos) {
        const auto [line, column] = JsonLocator::lineColumn(text, at);
        return makeError("{}:{}:{}: malformed JSON: arrays and objects nested deeper than {} levels", name, line, column,
                         kMaxJsonDepth);
    }
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is the 1-based offset just past the offending character.
        const auto [line, column] = JsonLocator::lineColumn(text, e.byte > 0 ? e.byte - 1 : 0);
        std::string what = e.what();
        // Drop nlohmann's own "[json.exception.parse_error.101] parse error at line L, column C: " prefix.
        const auto colon = what.find(": ");
        if (colon != std::string::npos) what = what.substr(colon + 2);
        return makeError("{}:{}:{}: malformed JSON: {}", name, line, column, what);
    } catch (const nlohmann::json::out_of_range& e) {
        // nlohmann reports an overflowing number ("number overflow parsing '1e999'") without a position;
        // the quoted token locates it.
        std::string what = e.what();
        const size_t open = what.find('\''), close = what.rfind('\'');
        const std::string token = open != std::string::npos && close > open ? what.substr(open + 1, close - open - 1) : "";
        const size_t at = token.empty() ? std::string::npos : text.find(token);
        if (at == std::string::npos) return makeError("{}: malformed JSON: {}", name, what);
        const auto [line, column] = JsonLocator::lineColumn(text, at);
        return makeError("{}:{}:{}: number {} is not finite (overflows)", name, line, column, token);
    } catch (const nlohmann::json::exception& e) {  // any other nlohmann failure, as one line
        return makeError("{}: malformed JSON: {}", name, e.what());
    }
}

JsonLocator::JsonLocator(std::string_view text) : m_text(text) {
    skipWhitespace();
    if (m_pos < m_text.size()) value("");
}

int JsonLocator::line(const std::string& pointer) const {
    std::string p = pointer;
    while (true) {
        const auto it = m_lines.find(p);
        if (it != m_lines.end()) return it->second;
        if (p.empty()) return 0;
        p.erase(p.rfind('/'));
    }
}

std::pair<int, int> JsonLocator::lineColumn(std::string_view text, size_t offset) {
    int line = 1, column = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return {line, column};
}

void JsonLocator::skipWhitespace() {
    while (m_pos < m_text.size()) {
        const char c = m_text[m_pos];
        if (c == '\n') ++m_line;
        else if (c != ' ' && c != '\t' && c != '\r') break;
        ++m_pos;
    }
}

std::string JsonLocator::string() {
    std::string out;
    ++m_pos;  // opening quote
    while (m_pos < m_text.size() && m_text[m_pos] != '"') {
        if (m_text[m_pos] == '\\' && m_pos + 1 < m_text.size()) {
            ++m_pos;
            const char e = m_text[m_pos];
            // Keys with \u escapes keep the escape text; bounce's keys are plain ASCII.
            out += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'u' ? 'u' : e;
        } else {
            out += m_text[m_pos];
        }
        ++m_pos;
    }
    ++m_pos;  // closing quote
    return out;
}

void JsonLocator::value(const std::string& pointer) {
    m_lines.emplace(pointer, m_line);
    if (m_pos >= m_text.size()) return;
    const char c = m_text[m_pos];
    if (c == '{') {
        ++m_pos;
        skipWhitespace();
        while (m_pos < m_text.size() && m_text[m_pos] != '}') {
            const int keyLine = m_line;
            const std::string child = pointer + "/" + escapePointerToken(string());
            skipWhitespace();
            ++m_pos;  // ':'
            skipWhitespace();
            m_lines[child] = keyLine;  // the key's line: where a reader looks for the member
            value(child);
            skipWhitespace();
            if (m_pos < m_text.size() && m_text[m_pos] == ',') ++m_pos;
            skipWhitespace();
        }
        ++m_pos;
    } else if (c == '[') {
        ++m_pos;
        skipWhitespace();
        for (int i = 0; m_pos < m_text.size() && m_text[m_pos] != ']'; ++i) {
            value(pointer + "/" + std::to_string(i));
            skipWhitespace();
            if (m_pos < m_text.size() && m_text[m_pos] == ',') ++m_pos;
            skipWhitespace();
        }
        ++m_pos;
    } else if (c == '"') {
        string();
    } else {
        while (m_pos < m_text.size() && m_text[m_pos] != ',' && m_text[m_pos] != '}' && m_text[m_pos] != ']' &&
               m_text[m_pos] != ' ' && m_text[m_pos] != '\n' && m_text[m_pos] != '\t' && m_text[m_pos] != '\r')
            ++m_pos;
    }
}

}  // namespace bounce
