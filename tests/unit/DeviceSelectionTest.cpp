// EGL device selection, the device profile and per-profile setting defaults, without EGL or GL
// (issue 29 #2, #22, #13; gpu/DeviceSelection.h, core/DeviceProfile.h, core/Settings.h).
#include "core/DeviceProfile.h"
#include "core/Settings.h"
#include "gpu/DeviceSelection.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace bounce;
using namespace bounce::gl;

namespace {

// Mesa's software device first, then two GPUs: the enumeration order of a machine with Mesa's EGL
// vendor library listed before NVIDIA's.
std::vector<EglDeviceDesc> machine() {
    std::vector<EglDeviceDesc> d(3);
    d[0] = {0, true, "Mesa software (llvmpipe)"};
    d[1] = {1, false, "NVIDIA H100", "nvidia", "/dev/dri/renderD128"};
    d[2] = {2, false, "NVIDIA H100", "nvidia", "/dev/dri/renderD129"};
    return d;
}

std::vector<int> indices(const std::vector<DeviceCandidate>& c) {
    std::vector<int> out;
    for (const auto& x : c) out.push_back(x.index);
    return out;
}

}  // namespace

TEST(DeviceSelection, AutomaticTriesEveryHardwareDeviceInOrderThenSurfaceless) {
    auto c = chooseDevices(machine(), {});
    ASSERT_TRUE(c.ok()) << c.error().message;
    // The software device is skipped (surfaceless gives llvmpipe too); -1 is the surfaceless platform.
    EXPECT_EQ(indices(*c), (std::vector<int>{1, 2, -1}));
}

TEST(DeviceSelection, OnlySoftwareDevicesGiveSurfaceless) {
    std::vector<EglDeviceDesc> d(1);
    d[0] = {0, true, "Mesa software (llvmpipe)"};
    auto c = chooseDevices(d, {});
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(indices(*c), (std::vector<int>{-1}));
    auto none = chooseDevices({}, {});
    ASSERT_TRUE(none.ok());
    EXPECT_EQ(indices(*none), (std::vector<int>{-1}));
}

TEST(DeviceSelection, AnExplicitIndexIsTheOnlyCandidateEvenASoftwareOne) {
    DeviceRequest r;
    r.index = 2;
    r.source = "--gpu";
    auto c = chooseDevices(machine(), r);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(indices(*c), (std::vector<int>{2}));  // no fallback: the user asked for that device
    r.index = 0;
    c = chooseDevices(machine(), r);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(indices(*c), (std::vector<int>{0}));
}

TEST(DeviceSelection, AnIndexPastTheEnumerationIsAnErrorNamingTheDeviceCount) {
    DeviceRequest r;
    r.index = 99;
    r.source = "--gpu";
    auto c = chooseDevices(machine(), r);
    ASSERT_FALSE(c.ok());
    EXPECT_NE(c.error().message.find("--gpu 99"), std::string::npos) << c.error().message;
    EXPECT_NE(c.error().message.find("3 EGL devices"), std::string::npos) << c.error().message;
    EXPECT_EQ(c.error().message.find('\n'), std::string::npos);
    r.index = 1;
    r.source = "BOUNCE_EGL_DEVICE";
    c = chooseDevices({}, r);
    ASSERT_FALSE(c.ok());
    EXPECT_NE(c.error().message.find("BOUNCE_EGL_DEVICE 1"), std::string::npos) << c.error().message;
    EXPECT_NE(c.error().message.find("no EGL device"), std::string::npos) << c.error().message;
}

TEST(DeviceSelection, PlatformOverrides) {
    DeviceRequest r;
    r.platform = "surfaceless";
    auto c = chooseDevices(machine(), r);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(indices(*c), (std::vector<int>{-1}));
    r.platform = "device";
    c = chooseDevices(machine(), r);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(indices(*c), (std::vector<int>{1, 2}));  // no surfaceless fallback
    std::vector<EglDeviceDesc> software(1);
    software[0] = {0, true, "Mesa software (llvmpipe)"};
    EXPECT_FALSE(chooseDevices(software, r).ok());
    r.platform = "wayland";
    EXPECT_FALSE(chooseDevices(machine(), r).ok());
    r.platform = "surfaceless";
    r.index = 1;
    r.source = "--gpu";
    EXPECT_FALSE(chooseDevices(machine(), r).ok());  // a device and no device at once
}

TEST(DeviceSelection, ParseDeviceIndex) {
    EXPECT_EQ(*parseDeviceIndex("0", "--gpu"), 0);
    EXPECT_EQ(*parseDeviceIndex("12", "--gpu"), 12);
    for (const char* bad : {"", "-1", "1x", "x", " 1", "1.0"}) {
        auto r = parseDeviceIndex(bad, "BOUNCE_EGL_DEVICE");
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.error().message.find("BOUNCE_EGL_DEVICE"), std::string::npos);
    }
}

TEST(DeviceSelection, SweepWorkersSpreadOverTheHardwareDevices) {
    EXPECT_EQ(defaultSweepJobs(machine(), {}), 2);  // one worker per GPU
    const auto w = sweepWorkerDevices(machine(), {}, 5);
    ASSERT_EQ(w.size(), 5u);
    EXPECT_EQ(w[0], 1);
    EXPECT_EQ(w[1], 2);
    EXPECT_EQ(w[2], 1);
    EXPECT_EQ(w[3], 2);
    EXPECT_EQ(w[4], 1);
    // llvmpipe only: one worker by default, and workers take the automatic choice (unchanged).
    std::vector<EglDeviceDesc> software(1);
    software[0] = {0, true, "Mesa software (llvmpipe)"};
    EXPECT_EQ(defaultSweepJobs(software, {}), 1);
    for (const auto& d : sweepWorkerDevices(software, {}, 3)) EXPECT_FALSE(d.has_value());
    // An explicit device pins every worker to it.
    DeviceRequest r;
    r.index = 2;
    EXPECT_EQ(defaultSweepJobs(machine(), r), 1);
    for (const auto& d : sweepWorkerDevices(machine(), r, 3)) EXPECT_EQ(d, 2);
}

TEST(DeviceSelection, SoftwareRendererWithGpuNodesWarnsOnce) {
    const std::vector<DeviceNode> nodes = {{"/dev/nvidia0", "nvidia"}, {"/dev/dri/renderD128", "nvidia"}};
    auto w = softwareFallbackWarning("llvmpipe (LLVM 15.0.6, 256 bits)", nodes);
    ASSERT_TRUE(w.has_value());
    EXPECT_NE(w->find("/dev/nvidia0"), std::string::npos);
    EXPECT_EQ(w->find('\n'), std::string::npos);
    EXPECT_FALSE(softwareFallbackWarning("llvmpipe (LLVM 15.0.6, 256 bits)", {}).has_value());
    EXPECT_FALSE(softwareFallbackWarning("NVIDIA H100 80GB HBM3/PCIe/SSE2", nodes).has_value());
}

TEST(DeviceProfile, RendererDecidesAndBounceProfileOverrides) {
    EXPECT_EQ(profileOfRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"), DeviceProfile::Llvmpipe);
    EXPECT_EQ(profileOfRenderer("softpipe"), DeviceProfile::Llvmpipe);
    EXPECT_EQ(profileOfRenderer("NVIDIA H100 80GB HBM3/PCIe/SSE2"), DeviceProfile::Gpu);
    EXPECT_EQ(profileOfRenderer("AMD Radeon RX 6800 (navi21, LLVM 15.0.7, DRM 3.49, 6.1.0)"), DeviceProfile::Gpu);
    EXPECT_EQ(profileOfRenderer("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"), DeviceProfile::Gpu);
    EXPECT_EQ(*resolveProfile("NVIDIA H100", "llvmpipe"), DeviceProfile::Llvmpipe);
    EXPECT_EQ(*resolveProfile("llvmpipe", "gpu"), DeviceProfile::Gpu);
    EXPECT_EQ(*resolveProfile("llvmpipe", ""), DeviceProfile::Llvmpipe);
    auto bad = resolveProfile("llvmpipe", "fast");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("BOUNCE_PROFILE"), std::string::npos);
}

namespace {
struct ProfiledSettings final : Configurable {
    int batch = 100;  // the llvmpipe value, as a member initialiser must be
    float step = 0.5f;
    int plain = 7;
    void visitSettings(SettingsVisitor& v) override {
        v.field("batch", batch, "per-profile int", 1, 100000, PerProfile<int>{100, 4000});
        v.field("step", step, "per-profile float", 0.0f, 1.0f, PerProfile<float>{0.5f, 0.25f});
        v.field("plain", plain, "no per-profile default", 0, 10);
    }
};
}  // namespace

TEST(ProfileSettings, DefaultsFollowTheProfileAndExplicitValuesWin) {
    ProfiledSettings s;
    applyProfileDefaults(s, DeviceProfile::Gpu);
    EXPECT_EQ(s.batch, 4000);
    EXPECT_EQ(s.step, 0.25f);
    EXPECT_EQ(s.plain, 7);
    ASSERT_TRUE(applySettings(s, {{"batch", "12"}}, "test").ok());
    EXPECT_EQ(s.batch, 12);
    applyProfileDefaults(s, DeviceProfile::Llvmpipe);
    EXPECT_EQ(s.batch, 100);
    EXPECT_EQ(s.step, 0.5f);
    const auto d = describeSettings(s);
    ASSERT_EQ(d.size(), 3u);
    EXPECT_EQ(d[0].profileDefaults, "llvmpipe 100, gpu 4000");
    EXPECT_EQ(d[1].profileDefaults, "llvmpipe 0.5, gpu 0.25");
    EXPECT_TRUE(d[2].profileDefaults.empty());
    EXPECT_EQ(settingsToJson(s)["batch"], 100);
}
