// A whole `bounce reference` run through the library: outputs, run record, and bad paths.
#include "ReferenceTestScenes.h"
#include "core/FileIo.h"
#include "core/ImageIo.h"
#include "reference/ReferenceJob.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

namespace fs = std::filesystem;
using namespace bounce;

namespace {

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / fmt::format("bounce-reference-job-{}-{}", name, ::getpid());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

ReferenceJob smallJob(const fs::path& dir) {
    ReferenceJob job;
    job.scene = "test-furnace";
    job.sceneParams = {{"quality", "low"}};
    job.settings.width = 8;
    job.settings.height = 6;
    job.settings.samplesPerPixel = 16;
    job.settings.bounces = 2;
    job.output = dir / "ref.exr";
    job.stats = dir / "run.json";
    return job;
}

TEST(ReferenceJob, WritesImageAndRunRecord) {
    const fs::path dir = freshDir("ok");
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    const ReferenceJob job = smallJob(dir);
    auto result = runReferenceJob(scene, job);
    ASSERT_TRUE(result.ok()) << result.error().message;
    auto image = readImage(job.output);
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->width(), 8);
    EXPECT_EQ(image->height(), 6);
    EXPECT_EQ(image->pixels(), result->radiance.pixels());  // EXR holds the radiance exactly

    auto text = readTextFile(job.stats);
    ASSERT_TRUE(text.ok());
    const nlohmann::json record = nlohmann::json::parse(*text);
    EXPECT_EQ(record["kind"], "reference");
    EXPECT_EQ(record["scene"]["name"], "test-furnace");
    EXPECT_EQ(record["scene"]["params"]["quality"], "low");
    EXPECT_EQ(record["settings"]["spp"], 16);
    EXPECT_EQ(record["settings"]["bounces"], 2);
    EXPECT_EQ(record["result"]["samplesPerPixel"], 16);
    EXPECT_EQ(record["result"]["paths"], 8 * 6 * 16);
    EXPECT_GT(record["result"]["raysPerSecond"].get<double>(), 0.0);
    EXPECT_GT(record["result"]["pathsPerSecond"].get<double>(), 0.0);
    const std::string kernel = record["renderer"]["shadingKernel"].get<std::string>();
    EXPECT_TRUE(kernel == "x86-64-v4" || kernel == "x86-64-v3" || kernel == "x86-64") << kernel;
    EXPECT_GT(record["noise"]["meanPixelRelativeStdError"].get<double>(), 0.0);
    EXPECT_GT(record["noise"]["imageRelativeStdError"].get<double>(), 0.0);
    // No temporary files are left beside the outputs.
    int files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 2);
}

TEST(ReferenceJob, PngIsToneMapped) {
    const fs::path dir = freshDir("png");
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    ReferenceJob job = smallJob(dir);
    job.output = dir / "ref.png";
    job.stats.clear();
    job.toneMap = ToneMap{-1.0f, ToneCurve::Clamp};
    job.settings.samplesPerPixel = 256;
    auto result = runReferenceJob(scene, job);
    ASSERT_TRUE(result.ok()) << result.error().message;
    auto image = readImage(job.output);
    ASSERT_TRUE(image.ok());
    // Radiance 1 + 0.5 + 0.25 + 0.125 = 1.875 (three reflections) at -1 EV is 0.9375 linear. Over
    // the 48 pixels at 256 spp the mean's noise is about 0.3%, 8-bit sRGB quantisation below 0.5%.
    double sum = 0.0;
    for (const glm::vec3& p : image->pixels()) sum += p.r;
    EXPECT_NEAR(sum / static_cast<double>(image->pixelCount()), 0.9375, 0.01);
}

TEST(ReferenceJob, BadOutputsFailBeforeRenderingAndLeaveNoFile) {
    const fs::path dir = freshDir("bad");
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    ReferenceJob job = smallJob(dir);
    job.settings.samplesPerPixel = 1000000;  // would take minutes if it rendered

    job.output = dir / "missing-folder" / "ref.exr";
    auto missing = runReferenceJob(scene, job);
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("missing-folder"), std::string::npos) << missing.error().message;

    job.output = dir / "ref.tiff";
    auto extension = runReferenceJob(scene, job);
    ASSERT_FALSE(extension.ok());
    EXPECT_NE(extension.error().message.find(".tiff"), std::string::npos) << extension.error().message;

    job.output = dir / "ref.exr";
    job.stats = dir / "run.txt";
    EXPECT_FALSE(runReferenceJob(scene, job).ok());

    job.stats = dir / "no" / "run.json";
    EXPECT_FALSE(runReferenceJob(scene, job).ok());

    if (::geteuid() != 0) {  // root may write anywhere
        const fs::path locked = dir / "locked";
        fs::create_directories(locked);
        fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
        job.output = locked / "ref.exr";
        job.stats.clear();
        EXPECT_FALSE(runReferenceJob(scene, job).ok());
        fs::permissions(locked, fs::perms::owner_all);
    }
    // A scene problem is reported the same way, and also before anything is written.
    job.output = dir / "ref.exr";
    job.stats = dir / "run.json";
    job.settings.samplesPerPixel = 0;
    EXPECT_FALSE(runReferenceJob(scene, job).ok());

    int files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) files += entry.is_regular_file() ? 1 : 0;
    EXPECT_EQ(files, 0);
}

}  // namespace
