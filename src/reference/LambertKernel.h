#pragma once
// The path tracer's vectorised kernel: one reflection of up to 16 paths at once, for hits on
// untextured Lambertian surfaces (flat or with vertex normals), under every kind of light -- the
// built-in scenes' common case. It computes what PathTracer::scatter() computes for such a hit, with
// the same floating-point operations in the same order and the same random numbers, so an image is
// bit-identical whichever code shades it (tests/unit/ReferenceTest.cpp,
// VectorisedKernelEqualsScalarCode). The build never contracts a*b+c (ISO C++ mode), and every
// instruction set variant computes the same IEEE results.
//
// The state is structure-of-arrays; the stages are written in GCC's vector extensions
// (LambertKernelIsa.inl) and compiled three times, for x86-64-v4 (AVX-512), x86-64-v3 (AVX2) and the
// x86-64 baseline, one translation unit each so that every vector operation is lowered for its own
// instruction set; hit() and reflect() call the best variant the CPU runs. Each stage is
// straight-line SIMD code with selects instead of branches. Data-dependent lookups (the hit
// triangle, the chosen light) stay scalar, in PathTracer, between the stages.
#include <cstdint>

#include <glm/vec3.hpp>

namespace bounce::lambert {

inline constexpr int kLanes = 16;

// Light kinds in Lanes::lightKind; the values of LightSampler::Kind (PathTracer.cpp checks).
inline constexpr int32_t kPointLight = 0, kSpotLight = 1, kDirectionalLight = 2, kAreaLight = 3, kTriangleLight = 4;

// Plain arrays: the per-instruction-set translation units must not instantiate inline library code
// (std::array's members), which the linker could then share with code built for the baseline.
template <class T>
using LaneArray = T[kLanes];

struct Vec3Lanes {
    alignas(64) LaneArray<float> x, y, z;
    glm::vec3 at(int i) const noexcept { return {x[i], y[i], z[i]}; }
    void set(int i, glm::vec3 v) noexcept { x[i] = v.x, y[i] = v.y, z[i] = v.z; }
};

// Every path of a packet lives here, in structure-of-arrays form, between Embree's packets (whose
// layout is the same) and the shading code: the kernel reads and writes lanes with `in` set, the
// scalar code the others.
struct Lanes {
    // The paths.
    Vec3Lanes origin{}, direction{};  // of the ray to trace next (direction unit)
    alignas(64) LaneArray<float> tMax{};
    Vec3Lanes throughput{}, radiance{};
    alignas(64) LaneArray<float> bsdfPdf{};  // solid-angle pdf of the BRDF sample that chose `direction`
    alignas(64) LaneArray<int32_t> reflections{}, culledCrossings{};
    alignas(64) LaneArray<uint64_t> rng{};  // Rng::state()
    // The hit of the last traced ray.
    alignas(64) LaneArray<uint32_t> geomId{}, primId{};
    alignas(64) LaneArray<float> u{}, v{}, t{};
    // The kernel's lanes and their hit triangles (PathTracer loads them).
    alignas(64) LaneArray<int32_t> in{};  // 1: this lane is shaded by the kernel
    Vec3Lanes p0{}, p1{}, p2{}, faceNormal{}, albedo{}, emitted{};
    Vec3Lanes n0{}, n1{}, n2{};              // vertex normals where `smooth`
    alignas(64) LaneArray<int32_t> smooth{};  // 1: shade with the interpolated vertex normal
    alignas(64) LaneArray<float> emitterPmf{}, emitterArea{};  // of the hit triangle; area 0 if it does not emit
    alignas(64) LaneArray<int32_t> emissive{}, twoSided{}, absorber{};
    // Between the stages: hit() leaves the light-choice number, PathTracer loads the chosen light.
    Vec3Lanes position{}, normal{}, shadingNormal{}, tangent{}, bitangent{}, offsetPosition{};
    alignas(64) LaneArray<float> uSelect{}, uLight1{}, uLight2{};
    alignas(64) LaneArray<int32_t> wantLight{};
    // The chosen light, as LightSampler::Entry has it: kind (LightSampler::Kind's values), corner
    // (point and spot: position), edges, normal (spot: axis; directional: propagation direction),
    // emitted radiance, intensity or irradiance.
    Vec3Lanes lightCorner{}, lightEdge1{}, lightEdge2{}, lightNormal{}, lightEmitted{};
    alignas(64) LaneArray<float> lightArea{}, lightPmf{}, lightCosCutoff{}, lightExponent{};
    alignas(64) LaneArray<int32_t> lightKind{}, lightTwoSided{};
    // Every lane's reflection (kernel or scalar code): whether the path ends, and its shadow ray.
    alignas(64) LaneArray<int32_t> stop{}, shadowActive{};
    Vec3Lanes shadowOrigin{}, shadowDirection{}, shadowContribution{};
    alignas(64) LaneArray<float> shadowTMax{};
};

// The instruction set hit() and reflect() run: "x86-64-v4", "x86-64-v3" or "x86-64".
const char* instructionSet() noexcept;

// Stage 1: the hit point, its emission, whether the path ends here, the shading frame, the new ray
// origin, and the light sample's three numbers.
void hit(Lanes& lanes, int maxReflections, bool indirectOnly) noexcept;
// Stage 2, after the chosen light is loaded: the light sample, the Lambert BRDF, the MIS weight and
// the shadow ray; then the cosine-weighted direction, the throughput and Russian roulette. Both
// stages write the path state of the `in` lanes only.
void reflect(Lanes& lanes, int rouletteStartReflections) noexcept;

// The variants, one namespace per instruction set (LambertKernelV4.cpp, ...).
#define BOUNCE_LAMBERT_DECLARE(isa)                                              \
    namespace isa {                                                             \
    void hit(Lanes& lanes, int maxReflections, bool indirectOnly) noexcept;     \
    void reflect(Lanes& lanes, int rouletteStartReflections) noexcept;          \
    }
BOUNCE_LAMBERT_DECLARE(v4)
BOUNCE_LAMBERT_DECLARE(v3)
BOUNCE_LAMBERT_DECLARE(base)
#undef BOUNCE_LAMBERT_DECLARE

}  // namespace bounce::lambert
