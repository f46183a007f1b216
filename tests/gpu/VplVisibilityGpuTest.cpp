// The RSM-family gathers' optional VPL visibility (techniques/screen_voxels/VplVisibility.h): on
// furnished-room, the light each technique puts into the indirect shadows of the table and the bookshelf
// against the path tracer's one-bounce indirect light, with visibility off (the thesis) and on; and in
// the empty room, where nothing occludes, visibility must leave the image as it was.
#include "NicholsTestSupport.h"
#include "techniques/Pipeline.h"

#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {
class VplVisibilityGpuTest : public gputest::GpuTest {};

constexpr int kSize = 64;  // pixels per side: 4096 receivers, seconds per technique on llvmpipe
// Reference samples per pixel: the one-bounce image of this scene at 64^2 has a per-pixel noise of a few
// per cent at 4096 spp, and the regions below sum 100+ pixels, so their sums are good to about 1 %.
constexpr uint32_t kReferenceSpp = 4096;

const std::vector<std::string>& techniques() {
    static const std::vector<std::string> names = {"rsm", "isr", "hisr", "multires-splat"};
    return names;
}

// furnished-room's furniture (src/scene/FurnishedRoomScene.cpp): the table's footprint and the shelf's
// box, metres.
constexpr float kTableX = -0.6f, kTableZ = -0.2f, kTableHalfLength = 0.6f, kTableHalfWidth = 0.4f;
constexpr float kShelfX0 = 0.3f, kShelfX1 = 1.5f, kShelfTop = 1.8f, kShelfBack = -2.0f, kShelfFront = -1.6f;
constexpr float kOnTheFloor = 0.005f;  // metres: G-buffer positions of floor pixels are y = 0 up to rounding

struct Region {
    const char* name;
    std::function<bool(glm::vec3)> contains;
};

const std::vector<Region>& regions() {
    static const std::vector<Region> r = {
        {"under the table",
         [](glm::vec3 p) {
             return p.y < kOnTheFloor && std::abs(p.x - kTableX) < kTableHalfLength && std::abs(p.z - kTableZ) < kTableHalfWidth;
         }},
        {"inside the shelf",
         [](glm::vec3 p) { return p.x > kShelfX0 && p.x < kShelfX1 && p.y < kShelfTop && p.z > kShelfBack && p.z < kShelfFront; }},
    };
    return r;
}

struct Rendered {
    Image indirect, positions;
    Counters counters;
};

Rendered renderWith(const Scene& scene, const std::string& technique, bool visibility) {
    auto p = makePipeline(scene, technique, {{"vplVisibility", visibility ? "true" : "false"}}, kSize);
    const FrameStats stats = p->renderFrame(0);
    return {p->readback(Component::Indirect), readTexture(p->gbuffer().position()), stats.counters};
}

double regionLuminance(const Image& image, const Image& positions, const Region& region, int* pixels = nullptr) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (region.contains(positions.at(x, y))) {
                sum += luminance(image.at(x, y));
                ++n;
            }
    if (pixels) *pixels = n;
    return sum;
}

double imageLuminance(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& v : image.pixels()) sum += luminance(v);
    return sum;
}

const Image& furnishedReference() {
    static const Image reference = [] {
        auto scene = loadScene("furnished-room");
        EXPECT_TRUE(scene.ok());
        return oneBounceReference(*scene, kSize, 0, kReferenceSpp);
    }();
    return reference;
}
}  // namespace

TEST_F(VplVisibilityGpuTest, VisibilityRemovesTheLightInTheFurnituresIndirectShadows) {
    auto scene = loadScene("furnished-room");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Image& reference = furnishedReference();
    for (const std::string& technique : techniques()) {
        SCOPED_TRACE(technique);
        const Rendered off = renderWith(*scene, technique, false);
        const Rendered on = renderWith(*scene, technique, true);
        EXPECT_EQ(off.counters.count("visibilityRays"), 0u);
        ASSERT_GT(on.counters.at("visibilityRays"), 0.0);
        EXPECT_GT(on.counters.at("visibilityBlocked"), 0.0);
        const double refTotal = imageLuminance(reference);
        const double offTotal = imageLuminance(off.indirect) / refTotal, onTotal = imageLuminance(on.indirect) / refTotal;
        std::printf("%s: whole image off / reference %.3f, on / reference %.3f, blocked %.1f %% of %.0f rays\n",
                    technique.c_str(), offTotal, onTotal,
                    100.0 * on.counters.at("visibilityBlocked") / on.counters.at("visibilityRays"),
                    on.counters.at("visibilityRays"));
        RecordProperty(technique + " whole image off", std::to_string(offTotal));
        RecordProperty(technique + " whole image on", std::to_string(onTotal));
        // The whole room: without visibility about a third too much light (the issue's +35 %); with it
        // within a quarter of that excess. What remains is over-occlusion at the grid's resolution (a
        // marked voxel column or slice blocks a segment passing anywhere through it: openings shrink by
        // about half a column at each edge; measured 0.9-1.6 % low, 2.4-3.1 % before the voxelization set
        // each triangle's exact depth span per column) and the concave edges' loss (0.3-0.4 %
        // in the empty room, below).
        EXPECT_GT(offTotal, 1.2);
        EXPECT_LT(std::abs(onTotal - 1.0), 0.25 * std::abs(offTotal - 1.0));
        std::map<std::string, double> ratios;
        for (const Region& region : regions()) {
            int pixels = 0;
            const double ref = regionLuminance(reference, off.positions, region, &pixels);
            ASSERT_GT(pixels, 60) << region.name << " must be in view";
            const double offRatio = regionLuminance(off.indirect, off.positions, region) / ref;
            const double onRatio = regionLuminance(on.indirect, on.positions, region) / ref;
            std::printf("%s, %s (%d pixels): off / reference %.3f, on / reference %.3f\n", technique.c_str(), region.name,
                        pixels, offRatio, onRatio);
            RecordProperty(technique + " " + region.name + " off", std::to_string(offRatio));
            RecordProperty(technique + " " + region.name + " on", std::to_string(onRatio));
            ratios[std::string(region.name) + " off"] = offRatio;
            ratios[std::string(region.name) + " on"] = onRatio;
        }
        // Under the table the floor sees the lit ceiling only past the table's edges: without visibility
        // the gathers put 28x the one-bounce light there; with it the excess is gone, to within 5 % of
        // itself. The light that is left is below the reference (measured 0.56 for rsm, 0.89 for the
        // techniques that gather for coarse cells; 0.39 and 0.69 before the exact voxel footprints), as it is made of segments grazing the table's edges,
        // where the grid's over-occlusion weighs most (isr, with the earlier derivative footprints: 0.69
        // at the default 128^2 x 128 bits, 0.93 at 256^2 x 256, 1.16 at 512^2 x 512); the bound allows down to 0.3, the reference's own noise
        // being about 1 %.
        const double tableOff = ratios["under the table off"], tableOn = ratios["under the table on"];
        EXPECT_GT(tableOff, 10.0);
        EXPECT_LT(std::abs(tableOn - 1.0), 0.05 * std::abs(tableOff - 1.0));
        EXPECT_GT(tableOn, 0.3);
        EXPECT_LT(tableOn, 1.3);
        // Inside the shelf the ceiling is seen through the compartments' openings, 8 voxel columns high:
        // too much light without visibility (1.6x), too little with it (measured 0.73; with the earlier
        // derivative voxel footprints 0.52, isr 0.66 with a 256^2 x 256-bit grid, 0.77 with 512^2 x 512): the openings lose about half a column at each
        // edge. Held to that documented limitation: not below 0.4, and below the reference.
        const double shelfOff = ratios["inside the shelf off"], shelfOn = ratios["inside the shelf on"];
        EXPECT_GT(shelfOff, 1.4);
        EXPECT_GT(shelfOn, 0.4);
        EXPECT_LT(shelfOn, 1.0);
    }
}

TEST_F(VplVisibilityGpuTest, AnEmptyRoomIsUnchanged) {
    // Nothing occludes in the empty room (a closed convex box), so every VPL is visible from every
    // receiver and the image must not change, except next to the room's concave edges: a receiver
    // within about a voxel column of another wall has that wall's bits in the columns its segments
    // start through, and loses VPLs (docs/techniques/rsm.md, "VPL visibility").
    auto scene = loadScene("furnished-room", {{"furniture", "none"}});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (const std::string& technique : techniques()) {
        SCOPED_TRACE(technique);
        const Rendered off = renderWith(*scene, technique, false);
        const Rendered on = renderWith(*scene, technique, true);
        const double ratio = imageLuminance(on.indirect) / imageLuminance(off.indirect);
        int changed = 0;
        for (size_t i = 0; i < off.indirect.pixels().size(); ++i) {
            const float a = luminance(off.indirect.pixels()[i]), b = luminance(on.indirect.pixels()[i]);
            changed += std::abs(a - b) > 0.01f * a;
        }
        const double blocked = on.counters.at("visibilityBlocked") / on.counters.at("visibilityRays");
        RecordProperty(technique + " empty changed pixels", changed);
        std::printf("%s, empty room: on / off %.4f, %d of %d pixels changed by more than 1 %%, %.2f %% of rays blocked\n",
                    technique.c_str(), ratio, changed, kSize * kSize, 100.0 * blocked);
        RecordProperty(technique + " empty on/off", std::to_string(ratio));
        // Tolerances: the pixels along the edges (measured 72-86 of 4096, 1.6-4.7 % of the rays blocked)
        // lose part of their light; the whole image may lose up to 2 % (measured 0.34-0.43 %).
        EXPECT_GT(ratio, 0.98);
        EXPECT_LE(ratio, 1.0 + 1e-6);  // visibility only removes light
        EXPECT_LT(changed, kSize * kSize / 20);
    }
}
