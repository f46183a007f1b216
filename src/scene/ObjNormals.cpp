// OBJ smoothing groups, read by bounce because assimp 5.2 does not (see ObjNormals.h).
//
// The OBJ format (Wavefront's "Object Files (.obj)" appendix, also at paulbourke.net/dataformats/obj)
// says: "s group_number" sets the smoothing group of the faces that follow; 0 or "off" turns smoothing
// off. A face outside every group is therefore shaded flat, and faces of one group that share a vertex
// share its normal there. assimp's OBJ parser skips the "s" line entirely, and a mesh without normals
// then gets whatever the post-processing computes for every face alike. Rather than guessing which of
// assimp's output triangles came from which "f" statement (assimp splits by object, group and material
// and triangulates), the file's text is rewritten: every face without normals gets explicit "vn"
// references to normals appended at the end of the file. assimp resolves positive indices after the
// whole file is read, so normals defined after the faces are accepted (checked by
// tests/unit/SceneLoaderTest.cpp, which loads the rewritten text through assimp).
#include "scene/ObjNormals.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <vector>

namespace bounce {

namespace {

// One statement: physical lines joined where a line ends in a backslash (as assimp does).
struct LogicalLine {
    size_t begin = 0, end = 0;  // byte range in the original text, line ends included
    std::string content;        // joined text, comment and line ends removed
};

std::vector<LogicalLine> splitLines(std::string_view text) {
    std::vector<LogicalLine> lines;
    size_t pos = 0;
    while (pos < text.size()) {
        LogicalLine line;
        line.begin = pos;
        for (;;) {
            size_t eol = text.find('\n', pos);
            const size_t next = eol == std::string_view::npos ? text.size() : eol + 1;
            if (eol == std::string_view::npos) eol = text.size();
            std::string_view physical = text.substr(pos, eol - pos);
            if (!physical.empty() && physical.back() == '\r') physical.remove_suffix(1);
            pos = next;
            if (!physical.empty() && physical.back() == '\\' && pos < text.size()) {
                physical.remove_suffix(1);
                line.content.append(physical);
                line.content += ' ';
                continue;
            }
            line.content.append(physical);
            break;
        }
        line.end = pos;
        if (const size_t hash = line.content.find('#'); hash != std::string::npos) line.content.resize(hash);
        lines.push_back(std::move(line));
    }
    return lines;
}

std::vector<std::string_view> tokens(std::string_view s) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\v' || s[i] == '\f')) ++i;
        const size_t start = i;
        while (i < s.size() && !(s[i] == ' ' || s[i] == '\t' || s[i] == '\v' || s[i] == '\f')) ++i;
        if (i > start) out.push_back(s.substr(start, i - start));
    }
    return out;
}

bool parseInt(std::string_view s, long long& out) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size();
}

bool parseDouble(std::string_view s, double& out) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size();
}

struct Face {
    size_t line = 0;                    // index into the logical lines
    std::vector<long long> vertices;    // absolute 0-based position indices
    std::vector<std::string> prefixes;  // each corner's "v/vt" as written
    int group = 0;                      // 0: no smoothing group
};

// Twice the polygon's area vector (Newell's method, relative to its first corner): the face normal
// along the right-hand rule of the corners' order, i.e. facing the side the polygon is counter-
// clockwise from. Also right for non-planar quads, where it averages the two triangles' normals.
glm::dvec3 polygonNormal(const std::vector<glm::dvec3>& positions, const std::vector<long long>& corners) {
    glm::dvec3 n(0.0);
    const glm::dvec3 origin = positions[static_cast<size_t>(corners[0])];
    for (size_t i = 0; i < corners.size(); ++i) {
        const glm::dvec3 a = positions[static_cast<size_t>(corners[i])] - origin;
        const glm::dvec3 b = positions[static_cast<size_t>(corners[(i + 1) % corners.size()])] - origin;
        n += glm::cross(a, b);
    }
    return n;
}

// The polygon's interior angle at corner i (radians), 0 when an adjacent edge has no length.
double cornerAngle(const std::vector<glm::dvec3>& positions, const std::vector<long long>& corners, size_t i) {
    const size_t k = corners.size();
    const glm::dvec3 p = positions[static_cast<size_t>(corners[i])];
    const glm::dvec3 a = positions[static_cast<size_t>(corners[(i + 1) % k])] - p;
    const glm::dvec3 b = positions[static_cast<size_t>(corners[(i + k - 1) % k])] - p;
    const double cross = glm::length(glm::cross(a, b));
    const double dot = glm::dot(a, b);
    return cross == 0.0 && dot == 0.0 ? 0.0 : std::atan2(cross, dot);
}

glm::dvec3 normalizedOrZero(glm::dvec3 v) {
    const double len = glm::length(v);
    return len > 0.0 ? v / len : glm::dvec3(0.0);
}

}  // namespace

std::optional<ObjNormalsRewrite> addMissingObjNormals(std::string_view obj) {
    const std::vector<LogicalLine> lines = splitLines(obj);
    std::vector<glm::dvec3> positions;
    long long normals = 0;
    std::map<std::string, int> groupIds;  // smoothing group name -> id >= 1
    int group = 0;
    bool insideCurveSection = false;      // cstype ... end: free-form geometry, skipped as assimp does
    std::vector<Face> faces;

    for (size_t li = 0; li < lines.size(); ++li) {
        const std::vector<std::string_view> t = tokens(lines[li].content);
        if (t.empty()) continue;
        const std::string_view keyword = t[0];
        if (insideCurveSection) {
            insideCurveSection = keyword != "end";
            continue;
        }
        if (keyword == "cstype") {
            insideCurveSection = true;
        } else if (keyword == "v") {
            // x y z, x y z w (homogeneous) or x y z r g b (with a vertex colour), as assimp reads them.
            double c[4] = {0.0, 0.0, 0.0, 1.0};
            const size_t count = t.size() - 1;
            for (size_t k = 0; k < std::min<size_t>(count, 3); ++k)
                if (!parseDouble(t[k + 1], c[k])) return std::nullopt;
            if (count == 4 && (!parseDouble(t[4], c[3]) || c[3] == 0.0)) return std::nullopt;
            positions.emplace_back(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
        } else if (keyword == "vn") {
            ++normals;
        } else if (keyword == "s") {
            long long number = 0;
            if (t.size() < 2 || t[1] == "off" || (parseInt(t[1], number) && number == 0)) {
                group = 0;
            } else {
                const std::string name = parseInt(t[1], number) ? std::to_string(number) : std::string(t[1]);
                const auto [it, added] = groupIds.try_emplace(name, static_cast<int>(groupIds.size()) + 1);
                group = it->second;
            }
        } else if (keyword == "f" && t.size() >= 4) {
            Face face;
            face.line = li;
            face.group = group;
            bool allHaveNormals = true;
            for (size_t k = 1; k < t.size(); ++k) {
                const std::string_view corner = t[k];
                const size_t slash1 = corner.find('/');
                const size_t slash2 = slash1 == std::string_view::npos ? slash1 : corner.find('/', slash1 + 1);
                long long v = 0;
                if (!parseInt(corner.substr(0, slash1), v) || v == 0) return std::nullopt;
                // Negative indices count back from the latest vertex defined so far.
                face.vertices.push_back(v > 0 ? v - 1 : static_cast<long long>(positions.size()) + v);
                const std::string_view texCoord = slash1 == std::string_view::npos
                                                      ? std::string_view()
                                                      : corner.substr(slash1 + 1, slash2 == std::string_view::npos
                                                                                       ? std::string_view::npos
                                                                                       : slash2 - slash1 - 1);
                face.prefixes.push_back(fmt::format("{}/{}", corner.substr(0, slash1), texCoord));
                if (slash2 == std::string_view::npos || slash2 + 1 == corner.size()) allHaveNormals = false;
            }
            if (!allHaveNormals) faces.push_back(std::move(face));
        }
    }
    if (faces.empty()) return std::nullopt;
    for (const Face& f : faces)
        for (long long v : f.vertices)
            if (v < 0 || v >= static_cast<long long>(positions.size())) return std::nullopt;  // assimp reports it

    // Smoothing-group normals: per (group, vertex), the angle-weighted sum of the group's unit face
    // normals. Angle weights make the result independent of how a polygon is split into triangles.
    const auto key = [](int g, long long v) { return (static_cast<uint64_t>(g) << 40) | static_cast<uint64_t>(v); };
    std::unordered_map<uint64_t, glm::dvec3> smooth;
    std::vector<glm::dvec3> faceNormals(faces.size());
    for (size_t i = 0; i < faces.size(); ++i) {
        const Face& f = faces[i];
        faceNormals[i] = normalizedOrZero(polygonNormal(positions, f.vertices));
        if (f.group == 0) continue;
        for (size_t c = 0; c < f.vertices.size(); ++c)
            smooth[key(f.group, f.vertices[c])] += cornerAngle(positions, f.vertices, c) * faceNormals[i];
    }

    ObjNormalsRewrite out;
    std::string appended;  // the new "vn" lines
    long long nextNormal = normals + 1;  // 1-based index of the next appended normal
    std::unordered_map<uint64_t, long long> smoothIndex;
    const auto addNormal = [&](glm::dvec3 n) {
        appended += fmt::format("vn {:.9g} {:.9g} {:.9g}\n", n.x, n.y, n.z);
        return nextNormal++;
    };
    std::vector<std::string> rewritten(lines.size());
    std::vector<bool> isRewritten(lines.size(), false);
    for (size_t i = 0; i < faces.size(); ++i) {
        const Face& f = faces[i];
        std::string line = "f";
        if (f.group == 0) {
            // A degenerate face gets a zero normal; finalizeScene drops its triangles.
            const long long n = addNormal(faceNormals[i]);
            for (const std::string& prefix : f.prefixes) line += fmt::format(" {}/{}", prefix, n);
            ++out.flatFaces;
        } else {
            for (size_t c = 0; c < f.vertices.size(); ++c) {
                const uint64_t k = key(f.group, f.vertices[c]);
                auto it = smoothIndex.find(k);
                if (it == smoothIndex.end()) it = smoothIndex.emplace(k, addNormal(normalizedOrZero(smooth[k]))).first;
                line += fmt::format(" {}/{}", f.prefixes[c], it->second);
            }
            ++out.smoothFaces;
        }
        rewritten[f.line] = line + "\n";
        isRewritten[f.line] = true;
    }

    out.text.reserve(obj.size() + appended.size() + 32 * faces.size());
    for (size_t li = 0; li < lines.size(); ++li) {
        if (isRewritten[li]) out.text += rewritten[li];
        else out.text.append(obj.substr(lines[li].begin, lines[li].end - lines[li].begin));
    }
    if (!out.text.empty() && out.text.back() != '\n') out.text += '\n';
    out.text += "# normals added by bounce (docs/scene.md \"Model files\")\n";
    out.text += appended;
    return out;
}

}  // namespace bounce
