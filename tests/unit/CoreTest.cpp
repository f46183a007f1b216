#include "core/Error.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "core/ToneMap.h"
#include "scene/Scene.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <filesystem>

namespace fs = std::filesystem;
using namespace bounce;

namespace {
fs::path tempDir() {
    fs::path dir = fs::temp_directory_path() / ("bounce-core-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}
}  // namespace

TEST(Expected, CarriesValueOrError) {
    Expected<int> good = 3;
    ASSERT_TRUE(good.ok());
    EXPECT_EQ(*good, 3);
    Expected<int> bad = makeError("x{}", 1);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "x1");
}

TEST(ToneMap, SrgbRoundTrip) {
    for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(srgbDecode(srgbEncode(v)), v, 1e-5f);
    // sRGB reference points: 0.5 linear encodes to 0.7354 (IEC 61966-2-1 formula).
    EXPECT_NEAR(srgbEncode(0.5f), 0.735357f, 1e-5f);
}

TEST(ToneMap, ExposureDoublesRadiance) {
    ToneMap a{0.0f, ToneCurve::Clamp}, b{1.0f, ToneCurve::Clamp};
    EXPECT_NEAR(toDisplay(glm::vec3(0.2f), b).r, toDisplay(glm::vec3(0.4f), a).r, 1e-6f);
}

TEST(ImageIo, ExrRoundTripIsExact) {
    Image img(7, 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) img.at(x, y) = {x * 0.5f, y * 1e3f, -1.25f};
    fs::path p = tempDir() / "rt.exr";
    ASSERT_TRUE(writeImage(p, img).ok());
    auto back = readImage(p);
    ASSERT_TRUE(back.ok()) << back.error().message;
    ASSERT_EQ(back->width(), 7);
    ASSERT_EQ(back->height(), 5);
    for (size_t i = 0; i < img.pixelCount(); ++i) EXPECT_EQ(back->data()[i], img.data()[i]);
}

TEST(ImageIo, PngRoundTripWithinQuantisation) {
    Image img(4, 4, glm::vec3(0.25f, 0.5f, 0.75f));
    fs::path p = tempDir() / "rt.png";
    ASSERT_TRUE(writeImage(p, img, ToneMap{0.0f, ToneCurve::Clamp}).ok());
    auto back = readImage(p);
    ASSERT_TRUE(back.ok());
    // 8-bit sRGB steps are at most ~0.005 in linear units at these values.
    EXPECT_NEAR(back->at(1, 1).g, 0.5f, 0.005f);
}

TEST(ImageIo, BadPathsFailWithoutPartialFiles) {
    Image img(2, 2);
    EXPECT_FALSE(writeImage("/nonexistent-dir/x.png", img).ok());
    EXPECT_FALSE(writeImage(tempDir() / "x.bmp", img).ok());
    auto missing = readImage(tempDir() / "missing.exr");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("missing.exr"), std::string::npos);
    fs::path garbage = tempDir() / "garbage.exr";
    ASSERT_TRUE(writeTextFileAtomic(garbage, "not an exr").ok());
    EXPECT_FALSE(readImage(garbage).ok());
    for (auto& e : fs::directory_iterator(tempDir()))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// OutputFiles writes outputs that belong together: when one cannot be written (here a link to
// /dev/full, whose writes fail with ENOSPC), none is left, and the previous version is kept.
TEST(FileIo, OutputFilesLeaveNothingWhenOneFails) {
    const fs::path dir = tempDir() / "together";
    fs::remove_all(dir);
    fs::create_directories(dir);
    ASSERT_TRUE(writeTextFileAtomic(dir / "image.png", "old").ok());
    fs::create_symlink("/dev/full", dir / "full.json");
    OutputFiles files;
    files.add(dir / "image.png", "new");
    files.add(dir / "full.json", "{}");
    const auto r = files.commit();
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("full.json"), std::string::npos) << r.error().message;
    EXPECT_EQ(*readTextFile(dir / "image.png"), "old");
    size_t entries = 0;
    for (auto& e : fs::directory_iterator(dir)) {
        ++entries;
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
    }
    EXPECT_EQ(entries, 2u);  // image.png and the link
    EXPECT_TRUE(fs::is_character_file("/dev/full"));  // written in place, never replaced
}

// A symbolic link to a file is followed: the file it names is replaced, the link stays a link.
TEST(FileIo, WritesThroughSymbolicLinks) {
    const fs::path dir = tempDir() / "links";
    fs::remove_all(dir);
    fs::create_directories(dir);
    ASSERT_TRUE(writeTextFileAtomic(dir / "target.txt", "one").ok());
    fs::create_symlink("target.txt", dir / "link.txt");
    ASSERT_TRUE(writeTextFileAtomic(dir / "link.txt", "two").ok());
    EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
    EXPECT_EQ(*readTextFile(dir / "target.txt"), "two");
    // A device is written in place: /dev/null swallows it, and stays a device.
    EXPECT_TRUE(writeTextFileAtomic("/dev/null", "gone").ok());
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(FileIo, CheckWritableNamesTheFolder) {
    const auto missing = checkWritable(tempDir() / "no-such-folder" / "out.png");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("no-such-folder"), std::string::npos);
    // /proc refuses new files to everyone, root included (permission bits would not stop root).
    const auto proc = checkWritable("/proc/out.png");
    ASSERT_FALSE(proc.ok());
    EXPECT_NE(proc.error().message.find("not writable"), std::string::npos) << proc.error().message;
    EXPECT_TRUE(checkWritable(tempDir() / "fine.png").ok());
}

TEST(ImageIo, NonFiniteIsReported) {
    Image img(3, 3);
    img.at(2, 1).g = std::nanf("");
    auto r = checkFinite(img, "tex.png");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("(2, 1)"), std::string::npos);
}

TEST(TransformTrack, InterpolatesAndLoops) {
    TransformTrack track;
    track.keys = {{0.0f, glm::vec3(0.0f)}, {1.0f, glm::vec3(2.0f, 0.0f, 0.0f)}};
    EXPECT_NEAR(track.evaluate(0.25f)[3].x, 0.5f, 1e-6f);
    EXPECT_NEAR(track.evaluate(1.25f)[3].x, 0.5f, 1e-6f);  // wraps
    track.loop = false;
    EXPECT_NEAR(track.evaluate(7.0f)[3].x, 2.0f, 1e-6f);  // holds the end
}

TEST(Light, SpotFluxMatchesClosedForm) {
    Light spot;
    spot.type = LightType::Spot;
    spot.intensity = glm::vec3(1.0f);
    spot.falloffExponent = 1.0f;
    spot.cutoffAngle = glm::half_pi<float>();
    // Laine's 180-degree cosine spot: flux = pi * I0.
    EXPECT_NEAR(spot.flux().r, glm::pi<float>(), 1e-5f);
    spot.falloffExponent = 0.0f;
    EXPECT_NEAR(spot.flux().r, 2.0f * glm::pi<float>(), 1e-5f);
}
