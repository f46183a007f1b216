// The coarse-to-fine, empty-aware 3x3 upsampling of the Nichols multiresolution buffer (Nichols 2010
// §3.2.5, shaders/techniques/nichols/upsample.comp, shared by isr, hisr and multires-splat) on a small
// synthetic atlas, against a CPU implementation written from the thesis's description
// (/work/shared/specs/nichols-2010-multiresolution-image-space.md, "Upsampling and combination") with
// the choices the thesis leaves open taken as bounce documents them (upsample.comp's header):
//   - the input of level l is level l+1's result, nearest (each texel reads its parent texel);
//   - a texel "has data" if it was rendered at l (atlas alpha) or its input has data;
//   - the weights are the (1,2,1)x(1,2,1) tent (the thesis gives none);
//   - a texel rendered at l keeps rendered + input unfiltered (the thesis filters it too);
//   - everything else with data becomes the weighted mean of rendered + input over the 3x3 texels with
//     data; texels without data stay empty (alpha 0).
// Mutations this test was checked against: docs/techniques/rsm.md ("Mutation checks").
#include "GpuTestSupport.h"
#include "techniques/nichols/MultiresBuffer.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace bounce;

namespace {

class NicholsUpsampleGpuTest : public gputest::GpuTest {};

struct Level {
    glm::ivec2 size{0};
    std::vector<glm::vec4> texels;  // row-major, y * width + x
    glm::vec4& at(glm::ivec2 c) { return texels[static_cast<size_t>(c.y * size.x + c.x)]; }
    const glm::vec4& at(glm::ivec2 c) const { return texels[static_cast<size_t>(c.y * size.x + c.x)]; }
};

// The §3.2.5 pseudo-code, coarsest to finest, with the choices listed at the top of this file; with
// Nearest an unrendered texel with data copies its input, with Bilinear it interpolates the coarser
// level's result at its centre, empty parents counting as black (the comparison filters of the
// `upsampling` setting).
std::vector<Level> cpuUpsample(const std::vector<Level>& rendered,
                               nichols::UpsampleFilter filter = nichols::UpsampleFilter::EmptyAware) {
    const int levels = static_cast<int>(rendered.size());
    std::vector<Level> result(rendered.size());
    for (int l = levels - 1; l >= 0; --l) {
        const Level& r = rendered[static_cast<size_t>(l)];
        Level& out = result[static_cast<size_t>(l)];
        out.size = r.size;
        out.texels.assign(r.texels.size(), glm::vec4(0.0f));
        // inputTexels: the coarser level's result, nearest; none at the coarsest level.
        auto input = [&](glm::ivec2 c) -> glm::vec4 {
            if (l + 1 >= levels) return glm::vec4(0.0f);
            const Level& parent = result[static_cast<size_t>(l + 1)];
            return parent.at(glm::min(c / 2, parent.size - 1));
        };
        auto hasData = [&](glm::ivec2 c) { return r.at(c).a > 0.5f || input(c).a > 0.5f; };
        for (int y = 0; y < r.size.y; ++y)
            for (int x = 0; x < r.size.x; ++x) {
                const glm::ivec2 t(x, y);
                if (!hasData(t)) continue;  // empty stays empty
                if (r.at(t).a > 0.5f) {
                    out.at(t) = glm::vec4(glm::vec3(r.at(t)) + glm::vec3(input(t)), 1.0f);
                    continue;
                }
                if (filter == nichols::UpsampleFilter::Nearest) {
                    out.at(t) = glm::vec4(glm::vec3(input(t)), 1.0f);
                    continue;
                }
                if (filter == nichols::UpsampleFilter::Bilinear) {
                    const Level& parent = result[static_cast<size_t>(l + 1)];
                    const glm::dvec2 p = (glm::dvec2(t) + 0.5) * 0.5 - 0.5;
                    const glm::ivec2 p0(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
                    const glm::dvec2 f = p - glm::dvec2(p0);
                    glm::dvec3 sum(0.0);
                    for (int dy = 0; dy <= 1; ++dy)
                        for (int dx = 0; dx <= 1; ++dx) {
                            const glm::vec4 v = parent.at(glm::clamp(p0 + glm::ivec2(dx, dy), glm::ivec2(0), parent.size - 1));
                            const double w = (dx ? f.x : 1.0 - f.x) * (dy ? f.y : 1.0 - f.y);
                            if (v.a > 0.5f) sum += w * glm::dvec3(glm::vec3(v));
                        }
                    out.at(t) = glm::vec4(glm::vec3(sum), 1.0f);
                    continue;
                }
                glm::dvec3 sum(0.0);
                double totalWeight = 0.0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const glm::ivec2 n = t + glm::ivec2(dx, dy);
                        if (n.x < 0 || n.y < 0 || n.x >= r.size.x || n.y >= r.size.y || !hasData(n)) continue;
                        const double w = (2 - std::abs(dx)) * (2 - std::abs(dy));
                        sum += w * (glm::dvec3(glm::vec3(r.at(n))) + glm::dvec3(glm::vec3(input(n))));
                        totalWeight += w;
                    }
                out.at(t) = glm::vec4(glm::vec3(sum / totalWeight), 1.0f);
            }
    }
    return result;
}

// Deterministic pseudo-random numbers in [0, 1) (a 32-bit LCG; no std distribution, whose output
// differs between standard libraries).
struct Lcg {
    uint32_t state;
    float next() {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f;
    }
};

}  // namespace

static void checkAgainstCpu(nichols::UpsampleFilter filter) {
    // 12x10 -> 6x5 -> 3x2: odd sizes, so level 1's last row has no parent row of its own (clamped).
    const std::vector<glm::ivec2> sizes = {{12, 10}, {6, 5}, {3, 2}};
    auto buffer = nichols::MultiresBuffer::create();
    ASSERT_TRUE(buffer.ok()) << buffer.error().message;
    buffer->begin(sizes);
    ASSERT_EQ(buffer->levels(), 3);

    // Each texel rendered with probability 0.35, independently per level, so that texels are rendered at
    // one level, at several (rendered + inherited add), or nowhere (about 27 % of level 0 stays empty).
    // Unrendered atlas texels are zero, as after MultiresBuffer::begin's clear.
    Lcg rng{12345u};
    std::vector<Level> rendered;
    const glm::ivec2 atlasSize = buffer->atlasSize();
    std::vector<glm::vec4> atlas(static_cast<size_t>(atlasSize.x * atlasSize.y), glm::vec4(0.0f));
    for (int k = 0; k < 3; ++k) {
        Level level;
        level.size = sizes[static_cast<size_t>(k)];
        level.texels.assign(static_cast<size_t>(level.size.x * level.size.y), glm::vec4(0.0f));
        const glm::ivec2 origin = buffer->levelOrigin(k);
        for (int y = 0; y < level.size.y; ++y)
            for (int x = 0; x < level.size.x; ++x) {
                const bool on = rng.next() < 0.35f;
                const glm::vec4 v = on ? glm::vec4(rng.next(), rng.next(), rng.next(), 1.0f) : glm::vec4(0.0f);
                level.at({x, y}) = v;
                atlas[static_cast<size_t>((origin.y + y) * atlasSize.x + origin.x + x)] = v;
            }
        rendered.push_back(level);
    }
    glTextureSubImage2D(buffer->atlas().id(), 0, 0, 0, atlasSize.x, atlasSize.y, GL_RGBA, GL_FLOAT, atlas.data());
    buffer->upsample(filter);

    const std::vector<Level> expected = cpuUpsample(rendered, filter);
    int empty0 = 0, filtered0 = 0;
    for (int k = 0; k < 3; ++k) {
        const Level& e = expected[static_cast<size_t>(k)];
        std::vector<glm::vec4> gpu(e.texels.size());
        glGetTextureImage(buffer->result().id(), k, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(gpu.size() * sizeof(glm::vec4)),
                          gpu.data());
        for (int y = 0; y < e.size.y; ++y)
            for (int x = 0; x < e.size.x; ++x) {
                const glm::vec4 want = e.at({x, y}), got = gpu[static_cast<size_t>(y * e.size.x + x)];
                // 1e-6: float sums of at most nine terms below 3 (three levels of values below 1) and one
                // division; the CPU sums in double, so only the GPU's float rounding (~3e-7) remains.
                for (int c = 0; c < 4; ++c)
                    EXPECT_NEAR(got[c], want[c], 1e-6f) << "level " << k << " texel " << x << "," << y << " channel " << c;
                if (k == 0) {
                    empty0 += want.a < 0.5f;
                    filtered0 += want.a > 0.5f && rendered[0].at({x, y}).a < 0.5f;
                }
            }
    }
    // The atlas exercises every branch at level 0: empty texels, filtered (inherited) texels and, by
    // construction, texels rendered there.
    EXPECT_GT(empty0, 5);
    EXPECT_GT(filtered0, 20);
}

TEST_F(NicholsUpsampleGpuTest, EmptyAwareUpsamplingMatchesTheCpuFormula) { checkAgainstCpu(nichols::UpsampleFilter::EmptyAware); }
TEST_F(NicholsUpsampleGpuTest, NearestUpsamplingMatchesTheCpuFormula) { checkAgainstCpu(nichols::UpsampleFilter::Nearest); }
TEST_F(NicholsUpsampleGpuTest, NaiveBilinearUpsamplingMatchesTheCpuFormula) { checkAgainstCpu(nichols::UpsampleFilter::Bilinear); }

// The three filters differ on the same atlas (each is a different reconstruction, not a renamed one).
TEST_F(NicholsUpsampleGpuTest, FiltersDiffer) {
    Lcg rng{777u};
    std::vector<Level> rendered;
    for (glm::ivec2 size : {glm::ivec2(8, 8), glm::ivec2(4, 4), glm::ivec2(2, 2)}) {
        Level level;
        level.size = size;
        for (int i = 0; i < size.x * size.y; ++i)
            level.texels.push_back(rng.next() < 0.4f ? glm::vec4(rng.next(), rng.next(), rng.next(), 1.0f) : glm::vec4(0.0f));
        rendered.push_back(level);
    }
    const auto a = cpuUpsample(rendered, nichols::UpsampleFilter::EmptyAware)[0].texels;
    const auto n = cpuUpsample(rendered, nichols::UpsampleFilter::Nearest)[0].texels;
    const auto b = cpuUpsample(rendered, nichols::UpsampleFilter::Bilinear)[0].texels;
    double an = 0.0, ab = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        an += glm::length(glm::vec3(a[i] - n[i]));
        ab += glm::length(glm::vec3(a[i] - b[i]));
    }
    EXPECT_GT(an, 0.5);
    EXPECT_GT(ab, 0.5);
}
