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
}  // namespace

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
