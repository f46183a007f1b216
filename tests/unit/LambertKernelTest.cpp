// The vectorised kernel's instruction-set variants compute the same bits. The path tracer only runs
// the variant the CPU picks (its image test compares that one with the scalar code), so each
// variant the machine can run is compared here on the same lanes.
#include "reference/LambertKernel.h"
#include "reference/Rng.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>

namespace {

using namespace bounce;
using namespace bounce::lambert;

// Lanes as PathTracer would load them: hits on flat and smooth triangles facing both ways, some
// emitting, some absorbing, paths at several depths, every kind of light.
std::unique_ptr<Lanes> sampleLanes() {
    auto L = std::make_unique<Lanes>();
    Rng rng(7, 0, 0);
    for (int i = 0; i < kLanes; ++i) {
        const auto u = [&] { return rng.next(); };
        L->in[i] = i % 7 != 3;
        L->direction.set(i, glm::vec3(u() - 0.5f, -0.8f, u() - 0.5f));
        L->throughput.set(i, glm::vec3(0.2f + u(), 0.3f + u(), 0.1f + u()));
        L->radiance.set(i, glm::vec3(u(), u(), u()));
        L->bsdfPdf[i] = u();
        L->reflections[i] = i % 4;
        L->rng[i] = Rng(3, static_cast<uint64_t>(i), 1).state();
        L->u[i] = 0.4f * u();
        L->v[i] = 0.4f * u();
        L->t[i] = 0.1f + u();
        L->p0.set(i, glm::vec3(u(), 0.0f, u()));
        L->p1.set(i, glm::vec3(1.0f + u(), 0.0f, u()));
        L->p2.set(i, glm::vec3(u(), 0.0f, 1.0f + u()));
        L->faceNormal.set(i, glm::vec3(0.0f, i % 5 == 0 ? -1.0f : 1.0f, 0.0f));
        L->smooth[i] = i % 3 == 1;  // interpolated vertex normals, tilted off the face
        L->n0.set(i, glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f)));
        L->n1.set(i, glm::normalize(glm::vec3(0.0f, 1.0f, 0.4f)));
        L->n2.set(i, glm::normalize(glm::vec3(-0.2f, 1.0f, -0.1f)));
        L->albedo.set(i, glm::vec3(u(), u(), u()));
        L->emitted.set(i, i % 3 == 0 ? glm::vec3(2.0f, 1.0f, 0.5f) : glm::vec3(0.0f));
        L->emitterPmf[i] = i % 3 == 0 ? 0.25f : 0.0f;
        L->emitterArea[i] = i % 3 == 0 ? 0.5f : 0.0f;
        L->emissive[i] = i % 3 == 0;
        L->twoSided[i] = i % 2;
        L->absorber[i] = i == 9;
        L->lightCorner.set(i, glm::vec3(-0.5f + u(), 2.0f, -0.5f + u()));
        L->lightEdge1.set(i, glm::vec3(0.5f, 0.0f, 0.0f));
        L->lightEdge2.set(i, glm::vec3(0.0f, 0.0f, 0.5f));
        L->lightNormal.set(i, glm::vec3(0.0f, i % 6 == 1 ? 1.0f : -1.0f, 0.0f));
        L->lightEmitted.set(i, glm::vec3(5.0f, 5.0f, 4.0f));
        L->lightArea[i] = i % 2 ? 0.125f : 0.25f;
        L->lightPmf[i] = 0.5f;
        L->lightKind[i] = i % 5;  // every kind: point, spot, directional, rectangle, triangle
        L->lightCosCutoff[i] = 0.5f;
        L->lightExponent[i] = 3.0f;
        L->lightTwoSided[i] = i % 4 == 1;
        L->stop[i] = 1;  // scalar lanes' values, which the kernel must leave alone
        L->shadowTMax[i] = 7.0f;
    }
    return L;
}

using HitFn = void (*)(Lanes&, int, bool) noexcept;
using ReflectFn = void (*)(Lanes&, int) noexcept;

std::unique_ptr<Lanes> run(HitFn hitFn, ReflectFn reflectFn, bool indirectOnly) {
    auto L = sampleLanes();
    hitFn(*L, 3, indirectOnly);
    reflectFn(*L, 2);
    return L;
}

TEST(LambertKernel, InstructionSetVariantsAgreeBitForBit) {
    __builtin_cpu_init();
    for (const bool indirectOnly : {false, true}) {
        const auto base = run(base::hit, base::reflect, indirectOnly);
        // The stages did something: some shadow rays, some paths that go on, some that stop.
        int shadows = 0, going = 0, stopped = 0;
        for (int i = 0; i < kLanes; ++i) {
            if (!base->in[i]) {
                EXPECT_EQ(base->stop[i], 1) << "lane " << i << " is not the kernel's";
                EXPECT_EQ(base->shadowTMax[i], 7.0f) << "lane " << i << " is not the kernel's";
                continue;
            }
            shadows += base->shadowActive[i];
            going += base->stop[i] == 0;
            stopped += base->stop[i] != 0;
        }
        EXPECT_GT(shadows, 0);
        EXPECT_GT(going, 0);
        EXPECT_GT(stopped, 0);
        // GCC only, as in LambertKernel.cpp: clang 14 (the sanitizer build) has no "x86-64-v4" feature
        // string and builds the v3/v4 files for the base instruction set.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
        if (__builtin_cpu_supports("x86-64-v3")) {
            const auto v3run = run(v3::hit, v3::reflect, indirectOnly);
            EXPECT_EQ(std::memcmp(base.get(), v3run.get(), sizeof(Lanes)), 0) << "x86-64-v3";
        }
        if (__builtin_cpu_supports("x86-64-v4")) {
            const auto v4run = run(v4::hit, v4::reflect, indirectOnly);
            EXPECT_EQ(std::memcmp(base.get(), v4run.get(), sizeof(Lanes)), 0) << "x86-64-v4";
        }
#endif
    }
    const std::string chosen = instructionSet();
    EXPECT_TRUE(chosen == "x86-64-v4" || chosen == "x86-64-v3" || chosen == "x86-64") << chosen;
}

}  // namespace
