// Inputs that crashed, hung or aborted bounce, found by the libFuzzer targets (tests/fuzz, docs/reliability.md
// "Fuzzing") or while triaging them; each is committed under tests/fuzz/regressions/TARGET/ and fed here
// through the ordinary build's loaders. Loaders must answer bad input with one error line naming the
// file; tests/fuzz/Regressions.cmake runs the same files through the `bounce` command line.
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/Heatmap.h"
#include "scene/JsonLocator.h"
#include "scene/PlyCheck.h"
#include "scene/SceneLoader.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace bounce;

namespace {

fs::path regression(const std::string& target, const std::string& name) {
    return fs::path(BOUNCE_SOURCE_DIR) / "tests/fuzz/regressions" / target / name;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The project's rule for bad input: one line that names the file.
void expectOneLineNaming(const Error& error, const std::string& file) {
    EXPECT_EQ(error.message.find('\n'), std::string::npos) << error.message;
    EXPECT_TRUE(contains(error.message, file)) << error.message;
}

std::string nested(int depth) { return std::string(static_cast<size_t>(depth), '[') + std::string(static_cast<size_t>(depth), ']'); }

Image mirrored(const Image& image) {
    Image out(image.width(), image.height());
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) out.at(x, y) = image.at(image.width() - 1 - x, y);
    return out;
}

}  // namespace

// fuzz_study: "1e339" made nlohmann throw out_of_range, which the study parser did not catch
// (`bounce sweep` then died on the exception instead of naming the file and line).
TEST(FuzzRegression, StudyNumberOverflowIsAnErrorWithItsPosition) {
    const fs::path file = regression("study", "number-overflow");
    auto text = readTextFile(file);
    ASSERT_TRUE(text.ok()) << text.error().message;
    auto doc = parseJsonDocument(*text, file.string());
    ASSERT_FALSE(doc.ok());
    expectOneLineNaming(doc.error(), file.string());
    EXPECT_TRUE(contains(doc.error().message, "number-overflow:1:1: number 1e339 is not finite")) << doc.error().message;
}

// Found triaging the above: JsonLocator recursed once per nesting level and kept a pointer string per
// level, so a 100 KB file of brackets overflowed the stack (scene files and studies alike).
TEST(FuzzRegression, DeeplyNestedSceneFileIsAnError) {
    const fs::path file = regression("scene", "deep-nesting.json");
    Expected<Scene> scene = loadScene(file.string());
    ASSERT_FALSE(scene.ok());
    expectOneLineNaming(scene.error(), file.string());
    // Line 1, column 75: the 64th "[" after {"objects": is the 65th level (the "{" is the first).
    EXPECT_TRUE(contains(scene.error().message, "deep-nesting.json:1:75: malformed JSON: arrays and objects nested deeper than 64"))
        << scene.error().message;
}

TEST(FuzzRegression, DeeplyNestedStudyIsAnError) {
    const fs::path file = regression("study", "deep-nesting.json");
    auto text = readTextFile(file);
    ASSERT_TRUE(text.ok()) << text.error().message;
    auto doc = parseJsonDocument(*text, file.string());
    ASSERT_FALSE(doc.ok());
    expectOneLineNaming(doc.error(), file.string());
    EXPECT_TRUE(contains(doc.error().message, "nested deeper than")) << doc.error().message;
}

TEST(FuzzRegression, NestingLimitIsExact) {
    // kMaxJsonDepth levels parse; one more is refused. Brackets inside strings do not count.
    EXPECT_TRUE(parseJsonDocument(nested(kMaxJsonDepth), "a.json").ok());
    EXPECT_FALSE(parseJsonDocument(nested(kMaxJsonDepth + 1), "a.json").ok());
    EXPECT_TRUE(parseJsonDocument("{\"k\": \"" + std::string(200, '[') + "\"}", "a.json").ok());
    EXPECT_TRUE(parseJsonDocument("[\"\\\"[\"]", "a.json").ok()) << "an escaped quote does not end the string";
}

// fuzz_model: assimp 5.2's PLY reader loops forever on a header without "end_header" (ascii) and reads
// past its buffer on a truncated binary one (a segfault). bounce checks the structure first.
TEST(FuzzRegression, PlyHeaderWithoutEndIsAnError) {
    for (const char* name : {"ascii-header-unterminated.ply", "binary-header-unterminated.ply"}) {
        const fs::path file = regression("model", name);
        Expected<Scene> scene = loadScene(file.string());
        ASSERT_FALSE(scene.ok()) << name;
        expectOneLineNaming(scene.error(), file.string());
        EXPECT_TRUE(contains(scene.error().message, "end_header")) << scene.error().message;
    }
}

TEST(PlyCheck, AcceptsWellFormedFilesAndNamesWhatIsWrong) {
    const std::string header = "ply\nformat binary_little_endian 1.0\ncomment two floats\nelement vertex 2\n"
                               "property float x\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    std::string body(8, '\0');             // two vertices of one float
    body += std::string("\x03", 1);        // a face of three indices
    body += std::string(12, '\0');
    EXPECT_TRUE(checkPlyFile(header + body, "m.ply").ok());
    EXPECT_TRUE(checkPlyFile("ply\r\nformat ascii 1.0\r\nelement vertex 0\r\nend_header\r\n", "m.ply").ok())
        << "CRLF line ends";

    const auto error = [](const std::string& bytes) {
        auto r = checkPlyFile(bytes, "m.ply");
        return r.ok() ? std::string("(accepted)") : r.error().message;
    };
    EXPECT_TRUE(contains(error(header + body.substr(0, body.size() - 1)), "m.ply: PLY file is truncated: face 0 of 1"));
    EXPECT_TRUE(contains(error(header + std::string(7, '\0')), "truncated: vertex 1 of 2"));
    EXPECT_TRUE(contains(error("solid\n"), "not a PLY file"));
    EXPECT_TRUE(contains(error("ply\nformat ascii 2.0\nend_header\n"), "PLY header line 2: expected \"format"));
    EXPECT_TRUE(contains(error("ply\nformat ascii 1.0\nproperty float x\nend_header\n"), "line 3: \"property\" before any \"element\""));
    EXPECT_TRUE(contains(error("ply\nformat ascii 1.0\nelement vertex 99\nend_header\n"), "declares 99 items"));
    EXPECT_TRUE(contains(error("ply\nformat ascii 1.0\nelement v 1\nproperty list float int i\nend_header\n1"), "not an integer type"));
    EXPECT_TRUE(contains(error("ply\nformat ascii 1.0\nbogus\nend_header\n"), "unknown keyword \"bogus\""));
    // A list count that runs past the end of the file (255 indices, none there) is caught before assimp.
    EXPECT_TRUE(contains(error(header + std::string(8, '\0') + "\xff"), "truncated: face 0 of 1"));
}

// fuzz_image: an image whose absolute error against its mirror image passes float's range (about 3e38
// against -3e38) gave an infinite heat-map colour bar, and renderHeatmap's check aborted
// `bounce compare --heatmap ... --heatmap-metric abs`.
TEST(FuzzRegression, HeatmapOfOverflowingErrorsIsFinite) {
    const fs::path file = regression("image", "heatmap-range-overflow.exr");
    auto image = readImage(file);
    ASSERT_TRUE(image.ok()) << image.error().message;
    ASSERT_TRUE(checkFinite(*image, file.string()).ok());
    const Image mirror = mirrored(*image);
    for (const ErrorMap& map : {absoluteErrorMap(*image, mirror), squaredErrorMap(*image, mirror),
                                relativeSquaredErrorMap(*image, mirror)}) {
        for (float v : map.values()) EXPECT_TRUE(std::isfinite(v)) << v;
        const float high = map.percentile(0.99);
        EXPECT_TRUE(std::isfinite(high));
        if (high > 0.0f) {
            EXPECT_FALSE(renderHeatmap(map, 0.0f, high).empty());
        }
    }

    auto test = readImage(regression("image", "huge-test.exr"));
    auto reference = readImage(regression("image", "huge-reference.exr"));
    ASSERT_TRUE(test.ok() && reference.ok());
    const ErrorMap abs = absoluteErrorMap(*test, *reference);
    // |3e38 - (-3e38)| = 6e38 is past float's range: it saturates at the largest float.
    EXPECT_EQ(abs.at(0, 0), std::numeric_limits<float>::max());
    EXPECT_EQ(abs.at(1, 0), 0.0f);
    EXPECT_FALSE(renderHeatmap(abs, 0.0f, abs.percentile(0.99)).empty());
}

// Every committed regression input, whatever it once broke: the loader returns (no crash, no hang) and
// an error is one line naming the file. Model and scene files go through loadScene, images through
// readImage; study files are the command line's (Regressions.cmake).
TEST(FuzzRegression, EveryCommittedInputGivesACleanAnswer) {
    size_t files = 0;
    for (const char* target : {"scene", "model", "image"}) {
        const fs::path dir = fs::path(BOUNCE_SOURCE_DIR) / "tests/fuzz/regressions" / target;
        if (!fs::exists(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            ++files;
            const std::string path = entry.path().string();
            if (std::string(target) == "image") {
                auto image = readImage(path);
                if (!image.ok()) expectOneLineNaming(image.error(), path);
            } else {
                Expected<Scene> scene = loadScene(path);
                if (!scene.ok()) expectOneLineNaming(scene.error(), path);
            }
        }
    }
    EXPECT_GE(files, 6u);
}

// Found reviewing fuzz_image's memory use: a 4 KB EXR whose data window claims 16385 x 16385 pixels
// made readImage allocate 3.2 GB before OpenEXR found the pixels missing. Headers are checked against
// kMaxImageSide (the largest --size) before any pixel is allocated, for PNG and embedded images too.
TEST(FuzzRegression, OversizedImageHeadersAreRefusedBeforeAllocating) {
    const fs::path file = regression("image", "oversized-data-window.exr");
    auto image = readImage(file);
    ASSERT_FALSE(image.ok());
    expectOneLineNaming(image.error(), file.string());
    EXPECT_TRUE(contains(image.error().message, "EXR of 16385x16385 pixels is larger than the 16384 x 16384 bounce reads"))
        << image.error().message;

    // A PNG header of 16385 x 1 (its pixel data is missing too: the size is what must be reported).
    const auto be32 = [](uint32_t v) {
        return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
    };
    const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + "IHDR" + be32(16385) + be32(1) +
                            std::string("\x08\x02\x00\x00\x00", 5) + be32(0) /* CRC, not checked by stb */;
    const fs::path pngPath = fs::temp_directory_path() / ("bounce-oversized-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".png");
    { std::ofstream(pngPath, std::ios::binary) << png; }
    auto decoded = readImage(pngPath);
    fs::remove(pngPath);
    ASSERT_FALSE(decoded.ok());
    EXPECT_TRUE(contains(decoded.error().message, "image of 16385x1 pixels is larger than the 16384 x 16384 bounce reads"))
        << decoded.error().message;
}

// fuzz_image (UBSan): readImage offset its pixel pointer by the EXR data window's origin itself, which
// points outside the image for a window not starting at (0, 0). The fuzzer's file (a window from
// y = -1 whose pixel blocks are then wrong) must be a clean error; a well-formed file with an origin
// of (-1, -1) must read with every pixel where it belongs (row-major from the window's corner).
TEST(FuzzRegression, ExrDataWindowOffOriginReads) {
    const fs::path file = regression("image", "data-window-negative-origin.exr");
    auto broken = readImage(file);
    ASSERT_FALSE(broken.ok());
    expectOneLineNaming(broken.error(), file.string());

    const fs::path offset = fs::temp_directory_path() / "bounce-exr-offset-origin.exr";
    const Imath::Box2i window(Imath::V2i(-1, -1), Imath::V2i(1, 0));  // 3x2 pixels
    std::vector<float> r(6), g(6), b(6);
    for (int i = 0; i < 6; ++i) {
        r[i] = static_cast<float>(i);
        g[i] = 10.0f + static_cast<float>(i);
        b[i] = 20.0f + static_cast<float>(i);
    }
    {
        Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(2, 1)), window);
        for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile out(offset.c_str(), header);
        Imf::FrameBuffer fb;
        fb.insert("R", Imf::Slice::Make(Imf::FLOAT, r.data(), window, sizeof(float), 3 * sizeof(float)));
        fb.insert("G", Imf::Slice::Make(Imf::FLOAT, g.data(), window, sizeof(float), 3 * sizeof(float)));
        fb.insert("B", Imf::Slice::Make(Imf::FLOAT, b.data(), window, sizeof(float), 3 * sizeof(float)));
        out.setFrameBuffer(fb);
        out.writePixels(2);
    }
    auto image = readImage(offset);
    fs::remove(offset);
    ASSERT_TRUE(image.ok()) << image.error().message;
    ASSERT_EQ(image->width(), 3);
    ASSERT_EQ(image->height(), 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const int i = y * 3 + x;
            EXPECT_EQ(image->at(x, y), glm::vec3(r[i], g[i], b[i])) << x << "," << y;
        }
}

// fuzz_model (ASan): assimp 5.2.5 reads past its line buffer when an OBJ file's only line is a long
// face, line or point statement ("pformat: a{ 1.1", or a face of 19 indices). Such a file has no
// vertex, so bounce refuses it before assimp reads it; a file with a vertex still loads.
TEST(FuzzRegression, ObjWithoutVerticesIsRefusedBeforeAssimp) {
    for (const char* name : {"only-line-a-statement.obj", "only-line-a-long-face.obj"}) {
        const fs::path file = regression("model", name);
        Expected<Scene> scene = loadScene(file.string());
        ASSERT_FALSE(scene.ok()) << name;
        expectOneLineNaming(scene.error(), file.string());
        EXPECT_TRUE(contains(scene.error().message, "OBJ file has no vertex")) << scene.error().message;
    }
    const fs::path ok = fs::temp_directory_path() / "bounce-obj-one-triangle.obj";
    ASSERT_TRUE(writeTextFileAtomic(ok, "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n").ok());
    Expected<Scene> scene = loadScene(ok.string());
    fs::remove(ok);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
}

// fuzz_model (ASan): assimp gave a .glb or .gltf its glTF reader did not recognise to the reader that
// claimed the content, here the OBJ reader and the over-read above. bounce checks the signature first.
TEST(FuzzRegression, GltfFilesMustLookLikeGltf) {
    for (const char* name : {"obj-text-named.glb", "obj-text-named.gltf"}) {
        const fs::path file = regression("model", name);
        Expected<Scene> scene = loadScene(file.string());
        ASSERT_FALSE(scene.ok()) << name;
        expectOneLineNaming(scene.error(), file.string());
        EXPECT_TRUE(contains(scene.error().message, "not a ")) << scene.error().message;
        EXPECT_TRUE(contains(scene.error().message, "glTF file")) << scene.error().message;
    }
}

// fuzz_model: assimp allocates what a GLB chunk header claims before reading it (3.4 GB for a 397-byte
// file); bounce checks that the header's and every chunk's length fit in the file.
TEST(FuzzRegression, GlbChunkLengthsMustFitTheFile) {
    const fs::path file = regression("model", "chunk-claims-3gb.glb");
    Expected<Scene> scene = loadScene(file.string());
    ASSERT_FALSE(scene.ok());
    expectOneLineNaming(scene.error(), file.string());
    EXPECT_TRUE(contains(scene.error().message, "GLB")) << scene.error().message;
    // The corpus's well-formed GLB (a triangle and a point light) still loads.
    auto bytes = readTextFile(fs::path(BOUNCE_SOURCE_DIR) / "tests/fuzz/corpus/model/triangle.glb.in");
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const fs::path glb = fs::temp_directory_path() / "bounce-triangle.glb";
    ASSERT_TRUE(writeFileAtomic(glb, std::string_view(*bytes).substr(1)).ok());  // past the selector byte
    Expected<Scene> good = loadScene(glb.string());
    fs::remove(glb);
    ASSERT_TRUE(good.ok()) << good.error().message;
    EXPECT_EQ(good->triangleCount(), 1u);
}

// fuzz_model: assimp reads a non-number in an ASCII PLY body as 0 and then aborts on the face of 0
// indices (ai_assert in its triangulation, enabled in Debian's build). bounce checks the ASCII body's
// values and face counts first.
TEST(FuzzRegression, AsciiPlyValuesMustBeNumbersAndFacesHaveIndices) {
    const fs::path file = regression("model", "ascii-face-count-not-a-number.ply");
    Expected<Scene> scene = loadScene(file.string());
    ASSERT_FALSE(scene.ok());
    expectOneLineNaming(scene.error(), file.string());
    EXPECT_TRUE(contains(scene.error().message, "face 0 of 1")) << scene.error().message;
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 0 1\n";
    EXPECT_TRUE(checkPlyFile(header + "3 0 2 1\n", "m.ply").ok());
    EXPECT_TRUE(checkPlyFile(header + "3 0 2", "m.ply").ok()) << "a short body is assimp's to report";
    auto zero = checkPlyFile(header + "0\n", "m.ply");
    ASSERT_FALSE(zero.ok());
    EXPECT_TRUE(contains(zero.error().message, "m.ply: PLY face 0 of 1 has no vertex index")) << zero.error().message;
    auto word = checkPlyFile(header + "x 0 2 1\n", "m.ply");
    ASSERT_FALSE(word.ok());
    EXPECT_TRUE(contains(word.error().message, "\"x\" is not a number")) << word.error().message;
    EXPECT_FALSE(checkPlyFile(header + "3 0 two 1\n", "m.ply").ok());
}

