#include "scene/PlyCheck.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <cstdint>
#include <cstring>
#include <vector>

namespace bounce {

namespace {

// Longest header bounce reads, bytes: real headers are a few hundred bytes.
constexpr size_t kMaxHeaderBytes = 64 * 1024;

enum class Encoding { Ascii, LittleEndian, BigEndian };

struct Property {
    int size = 0;       // scalar: bytes per value; list: bytes per item
    int countSize = 0;  // list: bytes of the item count; 0 for a scalar
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

// Bytes of a PLY scalar type (both the original names and the sized ones), 0 for an unknown name.
int typeSize(std::string_view t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

// An unsigned list count of `size` bytes at `p`, in the file's byte order.
uint64_t readCount(const unsigned char* p, int size, Encoding encoding) {
    uint64_t v = 0;
    for (int i = 0; i < size; ++i) {
        const int k = encoding == Encoding::LittleEndian ? size - 1 - i : i;
        v = (v << 8) | p[k];
    }
    return v;
}

}  // namespace

Expected<void> checkPlyFile(std::string_view bytes, const std::string& where) {
    // Header lines end in "\n" (or "\r\n"); the header ends with the line "end_header".
    std::vector<Element> elements;
    bool sawFormat = false;
    Encoding encoding = Encoding::Ascii;
    size_t pos = 0;
    size_t bodyStart = std::string_view::npos;
    for (int lineNumber = 1; bodyStart == std::string_view::npos; ++lineNumber) {
        const size_t end = bytes.find('\n', pos);
        if (end == std::string_view::npos || end > kMaxHeaderBytes)
            return makeError("{}: PLY header has no \"end_header\" line{}", where,
                             end == std::string_view::npos ? "" : fmt::format(" in its first {} bytes", kMaxHeaderBytes));
        std::string_view line = bytes.substr(pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos = end + 1;
        const auto w = words(line);
        const auto bad = [&](const std::string& what) {
            return makeError("{}: PLY header line {}: {}", where, lineNumber, what);
        };
        if (lineNumber == 1) {
            if (line != "ply") return makeError("{}: not a PLY file (the first line is not \"ply\")", where);
            continue;
        }
        if (line.find('\0') != std::string_view::npos) return bad("a NUL byte in the header");
        if (w.empty()) return bad("empty line");
        const std::string_view key = w[0];
        if (key == "comment" || key == "obj_info") continue;
        if (key == "format") {
            if (sawFormat) return bad("a second \"format\" line");
            if (w.size() != 3 || w[2] != "1.0") return bad("expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
            if (w[1] == "ascii") encoding = Encoding::Ascii;
            else if (w[1] == "binary_little_endian") encoding = Encoding::LittleEndian;
            else if (w[1] == "binary_big_endian") encoding = Encoding::BigEndian;
            else return bad(fmt::format("unknown format \"{}\" (known: ascii, binary_little_endian, binary_big_endian)", w[1]));
            sawFormat = true;
        } else if (key == "element") {
            if (!sawFormat) return bad("\"element\" before the \"format\" line");
            Element e;
            if (w.size() != 3) return bad("expected \"element NAME COUNT\"");
            const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
            if (ec != std::errc() || p != w[2].data() + w[2].size())
                return bad(fmt::format("element count \"{}\" is not a non-negative integer", w[2]));
            // Every item of an element with properties takes at least one byte of the body.
            if (e.count > bytes.size()) return bad(fmt::format("element '{}' declares {} items, more than the file's {} bytes", w[1], e.count, bytes.size()));
            e.name = std::string(w[1]);
            elements.push_back(std::move(e));
        } else if (key == "property") {
            if (elements.empty()) return bad("\"property\" before any \"element\"");
            Property p;
            if (w.size() == 5 && w[1] == "list") {
                p.countSize = typeSize(w[2]);
                p.size = typeSize(w[3]);
                if (p.countSize == 0 || p.size == 0) return bad(fmt::format("unknown list types \"{} {}\"", w[2], w[3]));
                if (w[2] == "float" || w[2] == "float32" || w[2] == "double" || w[2] == "float64")
                    return bad(fmt::format("list count type \"{}\" is not an integer type", w[2]));
            } else if (w.size() == 3) {
                p.size = typeSize(w[1]);
                if (p.size == 0) return bad(fmt::format("unknown property type \"{}\"", w[1]));
            } else {
                return bad("expected \"property TYPE NAME\" or \"property list COUNT_TYPE ITEM_TYPE NAME\"");
            }
            elements.back().properties.push_back(p);
        } else if (key == "end_header") {
            if (w.size() != 1) return bad("text after \"end_header\"");
            if (!sawFormat) return bad("\"end_header\" without a \"format\" line");
            bodyStart = pos;
        } else {
            return bad(fmt::format("unknown keyword \"{}\" (known: format, element, property, comment, obj_info, end_header)", key));
        }
    }
    if (encoding == Encoding::Ascii) {
        // assimp reads what is not a number as 0 and aborts on a face of 0 indices (an ai_assert in
        // its triangulation, built into Debian's library; found by fuzz_model): every value must be a
        // number and a face's index count at least 1. Short bodies assimp reports itself.
        const std::string_view body = bytes.substr(bodyStart);
        size_t at = 0;
        const auto next = [&]() -> std::string_view {
            while (at < body.size() && std::isspace(static_cast<unsigned char>(body[at]))) ++at;
            const size_t start = at;
            while (at < body.size() && !std::isspace(static_cast<unsigned char>(body[at]))) ++at;
            return body.substr(start, at - start);
        };
        const auto number = [](std::string_view token, double& value) {
            const std::string text(token);
            char* end = nullptr;
            value = std::strtod(text.c_str(), &end);
            return !text.empty() && end == text.c_str() + text.size();
        };
        for (const Element& e : elements) {
            for (uint64_t i = 0; i < e.count; ++i) {
                for (const Property& p : e.properties) {
                    const std::string_view token = next();
                    if (token.empty()) return {};  // short body: assimp's own error
                    double value = 0.0;
                    if (!number(token, value))
                        return makeError("{}: PLY {} {} of {}: \"{}\" is not a number", where, e.name, i, e.count,
                                         std::string(token.substr(0, 32)));
                    if (p.countSize == 0) continue;
                    if (!(value >= 0.0) || value != std::floor(value) || value > 1e9)
                        return makeError("{}: PLY {} {} of {}: list count \"{}\" is not a count", where, e.name, i,
                                         e.count, std::string(token));
                    if (e.name == "face" && value < 1.0)
                        return makeError("{}: PLY face {} of {} has no vertex index", where, i, e.count);
                    for (uint64_t k = 0; k < static_cast<uint64_t>(value); ++k) {
                        const std::string_view item = next();
                        if (item.empty()) return {};
                        double v = 0.0;
                        if (!number(item, v))
                            return makeError("{}: PLY {} {} of {}: \"{}\" is not a number", where, e.name, i, e.count,
                                             std::string(item.substr(0, 32)));
                    }
                }
            }
        }
        return {};
    }

    // Binary: every declared item must lie inside the file.
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    uint64_t at = bodyStart;
    const uint64_t size = bytes.size();
    for (const Element& e : elements) {
        for (uint64_t i = 0; i < e.count; ++i) {
            for (const Property& p : e.properties) {
                if (p.countSize == 0) {
                    at += static_cast<uint64_t>(p.size);
                } else {
                    if (at + static_cast<uint64_t>(p.countSize) > size) at = size + 1;
                    else {
                        const uint64_t n = readCount(data + at, p.countSize, encoding);
                        at += static_cast<uint64_t>(p.countSize);
                        // n < 2^32 and size < 2^63: the product cannot overflow.
                        at += n * static_cast<uint64_t>(p.size);
                    }
                }
                if (at > size)
                    return makeError("{}: PLY file is truncated: {} {} of {} ends past the end of the file ({} bytes)",
                                     where, e.name, i, e.count, size);
            }
        }
    }
    return {};
}

}  // namespace bounce
