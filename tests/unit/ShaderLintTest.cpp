// Grep-level shader lints for what llvmpipe tolerates and GPU drivers may not (issue 29; the review's
// check 6, docs/gpu.md "Fixed findings"): no derivative (dFdx, dFdy, fwidth and their Fine/Coarse forms)
// and no implicit-LOD sampling (texture, textureProj, textureOffset) after a `discard` in the same
// function. After a discard the invocation may be terminated (Mesa's hardware drivers treat discard as
// terminate unless a driconf option is on), so its quad's derivatives are undefined (finding #4:
// paraboloid.frag took dFdx/dFdy of its position after discarding texels outside the paraboloid disc).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::string withoutComments(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size(); ++i) {
        if (text.compare(i, 2, "//") == 0) {
            while (i < text.size() && text[i] != '\n') ++i;
            if (i < text.size()) out += '\n';
        } else if (text.compare(i, 2, "/*") == 0) {
            const size_t end = text.find("*/", i + 2);
            for (size_t j = i; j < std::min(end == std::string::npos ? text.size() : end + 2, text.size()); ++j)
                if (text[j] == '\n') out += '\n';
            i = end == std::string::npos ? text.size() : end + 1;
        } else {
            out += text[i];
        }
    }
    return out;
}

// "file:line: what" for each derivative or implicit-LOD sample after a discard in the same function
// body (a body is tracked by brace depth: the discard's effect ends where its function's braces close).
std::vector<std::string> lint(const std::string& file, const std::string& source) {
    static const std::regex kDerivative(R"(\b(dFdx|dFdy|fwidth)(Fine|Coarse)?\s*\(|\btexture(Proj)?(Offset)?\s*\()");
    static const std::regex kDiscard(R"(\bdiscard\s*;)");
    std::vector<std::string> out;
    std::istringstream in(withoutComments(source));
    std::string line;
    int depth = 0, discardDepth = -1, n = 0;
    while (std::getline(in, line)) {
        ++n;
        if (discardDepth >= 0 && std::regex_search(line, kDerivative))
            out.push_back(file + ":" + std::to_string(n) + ": derivative or implicit-LOD sample after a discard: " + line);
        if (std::regex_search(line, kDiscard) && discardDepth < 0) discardDepth = depth;
        for (char c : line) {
            if (c == '{') ++depth;
            if (c == '}') --depth;
        }
        // The function that discarded has closed (its body opened at depth 1 from file scope 0).
        if (discardDepth >= 0 && depth == 0) discardDepth = -1;
    }
    return out;
}

}  // namespace

TEST(ShaderLint, TheLintFindsADerivativeAfterDiscard) {
    // Finding #4's shape, as paraboloid.frag had it: flagged; the fixed order (derivatives first) is not.
    const std::string before = "void main() {\n  if (r2 > 1.0) discard;\n  vec3 n = cross(dFdx(p), dFdy(p));\n}\n";
    const std::string after = "void main() {\n  vec3 n = cross(dFdx(p), dFdy(p));\n  if (r2 > 1.0) discard;\n}\n";
    EXPECT_EQ(lint("before.frag", before).size(), 1u);
    EXPECT_TRUE(lint("after.frag", after).empty());
    // Sampling with an implicit LOD is a derivative too; texelFetch and textureLod are not.
    EXPECT_EQ(lint("t.frag", "void main() {\n discard;\n c = texture(s, uv);\n}\n").size(), 1u);
    EXPECT_TRUE(lint("t.frag", "void main() {\n discard;\n c = textureLod(s, uv, 0.0) + texelFetch(s, p, 0);\n}\n").empty());
    // A discard in one function does not taint the next; comments are ignored.
    EXPECT_TRUE(lint("t.frag", "void f() { discard; }\nvoid main() {\n c = texture(s, uv); // discard;\n}\n").empty());
}

TEST(ShaderLint, NoShaderTakesDerivativesAfterDiscard) {
    const fs::path root = fs::path(BOUNCE_SOURCE_DIR) / "shaders";
    std::vector<std::string> findings;
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        if (!e.is_regular_file()) continue;
        const std::string ext = e.path().extension().string();
        if (ext != ".frag" && ext != ".glsl") continue;  // discard exists in fragment shaders (and their includes)
        std::ifstream f(e.path());
        std::stringstream text;
        text << f.rdbuf();
        ++files;
        for (auto& m : lint(fs::relative(e.path(), root).string(), text.str())) findings.push_back(std::move(m));
    }
    EXPECT_GT(files, 20);  // the tree was found
    for (const auto& m : findings) ADD_FAILURE() << m;
}
