// The million-VPL limit of Nichols (2010) Figs. 4.9/4.13 on a small cornell-box: the every-texel gather of
// a 1024^2 RSM (cornell-box's spot has one perspective map: 1,048,576 VPLs), rendered once, and every
// Nichols technique's indirect image against it. One test on purpose: the limit costs about two minutes on
// llvmpipe at 64^2 (docs/techniques/rsm.md), so it is rendered in one process for all techniques; the
// other Nichols tests use the 256^2 every-texel gather (NicholsTestSupport.h), which this test ties to the
// million-VPL limit.
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"

namespace bounce {
namespace {

using namespace nicholstest;

class NicholsMillionVplGpuTest : public gputest::GpuTest {};

struct Case {
    const char* name;
    const char* technique;
    std::map<std::string, std::string> settings;
    double bound;        // relative RMS error against the million-VPL gather
    double relMseBound;  // relMSE (metrics/ErrorMetrics.h, the measure) against it
};

TEST_F(NicholsMillionVplGpuTest, EveryTechniqueIsWithinItsBoundOfTheMillionVplGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image limit = renderIndirect(*scene, "rsm", {{"rsmSize", "1024"}, {"vplGrid", "1024"}}, kSize);
    ASSERT_TRUE(finiteAndNonNegative(limit));
    ASSERT_GT(totalRadiance(limit), 0.0);

    // The proxy limit of the other tests: measured 5.9 % (the 256^2 RSM's texels are 16x the million
    // VPLs' footprint; its remaining error is the discretisation of the light's reflected flux).
    const double proxyError = relativeRmsError(convergedLimit("cornell-box", kSize), limit);
    RecordProperty("everyTexel256RelRms", std::to_string(proxyError));
    EXPECT_LT(proxyError, 0.08);

    // The thesis's setting (RSM 256^2, 256 VPLs or clusters) as in bench/NicholsBench.cpp BM_NicholsError.
    // Bounds: the measured error (in the comment) plus about 20 % of it, room for a different llvmpipe or
    // GPU rounding and small retuning; a broken pass (lost VPLs, wrong form factor, a level missing in
    // the upsampling) moves these errors far beyond that. They are large in absolute terms because 256
    // VPLs are few and the 16^2 coarsest eye level covers a 4x4-pixel block of a 64^2 image.
    // relMSE (mean of (x - r)^2 / (r^2 + 0.01)) is small in absolute terms because the 0.01 W^2/(m^4 sr^2)
    // epsilon dominates the dim indirect light; its bounds are likewise the measured value plus ~25 %.
    const std::vector<Case> cases = {
        {"rsm", "rsm", {{"rsmSize", "256"}, {"vplGrid", "16"}}, 0.36, 0.0096},                                // 29.7 %, 0.0076
        {"isrRegular", "isr", {{"rsmSize", "256"}, {"vplMode", "regular"}, {"vplGrid", "16"}}, 0.36, 0.0098},  // 29.9 %, 0.0078
        {"multiresSplat", "multires-splat", {{"rsmSize", "256"}, {"vplGrid", "16"}}, 0.36, 0.0098},          // 29.9 %, 0.0078 (= isr regular)
        {"isrClusters", "isr", {{"rsmSize", "256"}, {"lightFinest", "64"}}, 0.18, 0.0019},                     // 14.7 %, 0.0015
        {"hisr", "hisr", {{"rsmSize", "256"}}, 0.185, 0.0023},                                                 // 15.4 %, 0.0018
    };
    for (const Case& c : cases) {
        const Image indirect = renderIndirect(*scene, c.technique, c.settings, kSize);
        ASSERT_TRUE(finiteAndNonNegative(indirect)) << c.name;
        const double error = relativeRmsError(indirect, limit);
        RecordProperty(std::string(c.name) + "RelRms", std::to_string(error));
        EXPECT_LT(error, c.bound) << c.name;
        auto metrics = compareImages(indirect, limit);
        ASSERT_TRUE(metrics.ok()) << metrics.error().message;
        RecordProperty(std::string(c.name) + "RelMse", std::to_string(metrics->relMse));
        EXPECT_LT(metrics->relMse, c.relMseBound) << c.name;
        // More VPLs are closer to the limit: every 256-VPL technique is further away than the 65k-VPL proxy.
        EXPECT_GT(error, proxyError) << c.name;
    }
}

}  // namespace
}  // namespace bounce
