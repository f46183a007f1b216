// The vectorised kernel's body, compiled once per instruction set: BOUNCE_LAMBERT_ISA names the
// namespace (v4, v3, base) and the including file's compile flags choose the instructions. Only
// builtins and this file's own static functions are used here (see LambertKernel.h).
#include "reference/LambertKernel.h"
#include "reference/Rng.h"
#include "reference/Sampling.h"  // kInvPi

#include <cstdint>

// The helpers below pass 64-byte vectors by value; they are internal and inlined into the kernel
// variants, so the calling-convention difference GCC warns about never crosses a call.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace bounce::lambert::BOUNCE_LAMBERT_ISA {

namespace {

// GCC vector extensions: 16 lanes, lowered to whatever the target has (one AVX-512 register, two
// AVX2 registers, four SSE2 registers). Comparisons yield masks of all-ones or zero lanes.
using F = float __attribute__((vector_size(64)));
using I = int32_t __attribute__((vector_size(64)));
using U32 = uint32_t __attribute__((vector_size(64)));
using U64 = uint64_t __attribute__((vector_size(128)));

static_assert(sizeof(F) == kLanes * sizeof(float) && sizeof(U64) == kLanes * sizeof(uint64_t));

template <class V, class T>
V load(const LaneArray<T>& a) noexcept {
    static_assert(sizeof(V) == sizeof(a));
    V v;
    __builtin_memcpy(&v, a, sizeof v);
    return v;
}
template <class V, class T>
void store(LaneArray<T>& a, V v) noexcept {
    static_assert(sizeof(V) == sizeof(a));
    __builtin_memcpy(a, &v, sizeof v);
}
F loadF(const LaneArray<float>& a) noexcept { return load<F>(a); }
I loadI(const LaneArray<int32_t>& a) noexcept { return load<I>(a); }
// Lanes stored as 0/1 flags, as a mask.
I loadMask(const LaneArray<int32_t>& a) noexcept { return load<I>(a) != 0; }
void storeMask(LaneArray<int32_t>& a, I mask) noexcept { store(a, mask & 1); }

bool any(I mask) noexcept {
    alignas(64) int32_t t[kLanes];
    __builtin_memcpy(t, &mask, sizeof t);
    int32_t bits = 0;
    for (int32_t x : t) bits |= x;
    return bits != 0;
}
F bitsToFloat(I v) noexcept { return reinterpret_cast<F>(v); }
I floatToBits(F v) noexcept { return reinterpret_cast<I>(v); }
F select(I mask, F a, F b) noexcept { return mask ? a : b; }
I selectI(I mask, I a, I b) noexcept { return mask ? a : b; }

// std::min and std::max as the scalar code evaluates them: min(a, b) = b < a ? b : a.
F minOf(F a, F b) noexcept { return select(b < a, b, a); }
F maxOf(F a, F b) noexcept { return select(a < b, b, a); }
F absOf(F a) noexcept { return bitsToFloat(floatToBits(a) & 0x7fffffff); }
// Vector extensions have no square root; a loop over a plain array is vectorised (sqrtps), which a
// loop over the vector's elements is not.
F sqrtOf(F a) noexcept {
    alignas(64) float t[kLanes];
    __builtin_memcpy(t, &a, sizeof t);
    for (float& x : t) x = __builtin_sqrtf(x);
    __builtin_memcpy(&a, t, sizeof t);
    return a;
}

struct F3 {
    F x, y, z;
};
F3 load3(const Vec3Lanes& v) noexcept { return {loadF(v.x), loadF(v.y), loadF(v.z)}; }
void store3(Vec3Lanes& v, F3 a) noexcept {
    store(v.x, a.x);
    store(v.y, a.y);
    store(v.z, a.z);
}
// Stores for the `in` lanes only: the other lanes belong to the scalar code.
void maskedStore(LaneArray<float>& a, I mask, F v) noexcept { store(a, select(mask, v, loadF(a))); }
void maskedStore(LaneArray<int32_t>& a, I mask, I v) noexcept { store(a, mask ? v : loadI(a)); }
void maskedStoreFlag(LaneArray<int32_t>& a, I mask, I flag) noexcept { maskedStore(a, mask, flag & 1); }
void maskedStore3(Vec3Lanes& v, I mask, F3 a) noexcept {
    maskedStore(v.x, mask, a.x);
    maskedStore(v.y, mask, a.y);
    maskedStore(v.z, mask, a.z);
}
F3 operator+(F3 a, F3 b) noexcept { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
F3 operator-(F3 a, F3 b) noexcept { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
F3 operator-(F3 a) noexcept { return {-a.x, -a.y, -a.z}; }
F3 operator*(F3 a, F3 b) noexcept { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
F3 operator*(F3 a, F s) noexcept { return {a.x * s, a.y * s, a.z * s}; }
F3 operator*(F3 a, float s) noexcept { return {a.x * s, a.y * s, a.z * s}; }
F3 operator*(F s, F3 a) noexcept { return {s * a.x, s * a.y, s * a.z}; }
F3 operator/(F3 a, F s) noexcept { return {a.x / s, a.y / s, a.z / s}; }
F dot(F3 a, F3 b) noexcept { return a.x * b.x + a.y * b.y + a.z * b.z; }  // glm::dot's order
F3 select3(I mask, F3 a, F3 b) noexcept { return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z)}; }
F maxComponent3(F3 v) noexcept { return maxOf(v.x, maxOf(v.y, v.z)); }
F splat(float s) noexcept { return F{} + s; }
const I kAllLanes = I{} - 1;

// Sampling.h's powerHeuristic.
F powerHeuristic(F pdfA, F pdfB) noexcept {
    const F a = pdfA * pdfA, b = pdfB * pdfB;
    return select(a > 0.0f, a / (a + b), splat(0.0f));
}

// Sampling.h's offsetRayOrigin, per component.
F offsetComponent(F p, F n) noexcept {
    constexpr float kOrigin = 1.0f / 32.0f;
    constexpr float kFloatScale = 1.0f / 65536.0f;
    constexpr float kIntScale = 256.0f;
    const I ulps = __builtin_convertvector(kIntScale * n, I);  // truncation, as static_cast
    const F moved = bitsToFloat(floatToBits(p) + selectI(p < 0.0f, -ulps, ulps));
    return select(absOf(p) < kOrigin, p + kFloatScale * n, moved);
}
F3 offsetRayOrigin(F3 p, F3 n) noexcept {
    return {offsetComponent(p.x, n.x), offsetComponent(p.y, n.y), offsetComponent(p.z, n.z)};
}

// Rng::next for every lane; lanes outside `draw` keep their state (the returned value is unused).
F nextUniform(U64& state, I draw) noexcept {
    const U64 old = state;
    const U64 stepped = old * Rng::kMultiplier + Rng::kIncrement;
    // 64-bit lane masks from the 32-bit ones.
    const auto keep = __builtin_convertvector(draw, U64) != 0;
    state = keep ? stepped : old;
    const U32 xorShifted = __builtin_convertvector(((old >> 18) ^ old) >> 27, U32);
    const U32 rotation = __builtin_convertvector(old >> 59, U32);
    const U32 bits = (xorShifted >> rotation) | (xorShifted << ((32u - rotation) & 31u));
    return __builtin_convertvector(reinterpret_cast<I>(bits >> 8), F) * 0x1.0p-24f;
}

void hitLanes(Lanes& L, int maxReflections, bool indirectOnly) noexcept {
    const I in = loadMask(L.in);
    const F3 dir = load3(L.direction), ngFront = load3(L.faceNormal), throughput = load3(L.throughput);
    const F u = loadF(L.u), v = loadF(L.v);
    const F w = 1.0f - u - v;
    const F3 p = w * load3(L.p0) + u * load3(L.p1) + v * load3(L.p2);
    // EmbreeScene::surface's shading normal: the interpolated vertex normal, normalised and turned to
    // the face's side, on smooth meshes; the face normal otherwise.
    F3 shadingFront = ngFront;
    const I smooth = in & loadMask(L.smooth);
    if (any(smooth)) {  // skipped for flat meshes: the result would be ngFront in every lane
        const F3 nInterpolated = w * load3(L.n0) + u * load3(L.n1) + v * load3(L.n2);
        const F nLength = sqrtOf(dot(nInterpolated, nInterpolated));
        const F3 nUnit = nInterpolated / nLength;
        const F3 nFaced = select3(dot(nUnit, ngFront) < 0.0f, -nUnit, nUnit);
        shadingFront = select3(smooth & (nLength > 0.0f), nFaced, ngFront);
    }
    const F cosIn = dot(dir, ngFront);
    const I front = cosIn < 0.0f;
    const I seen = front | loadMask(L.twoSided);
    const I refl = loadI(L.reflections);
    const I scopeEmits = indirectOnly ? (refl >= 2) : kAllLanes;
    const I emits = loadMask(L.emissive) & seen & scopeEmits;
    // LightSampler::pdfEmitterHit with the triangle's entry already looked up.
    const F cosLight = absOf(cosIn), distance = loadF(L.t);
    const F area = loadF(L.emitterArea);
    const F lightPdf = select((cosLight > 0.0f) & (area > 0.0f),
                              loadF(L.emitterPmf) * distance * distance / (area * cosLight), splat(0.0f));
    const F weight = select(refl > 0, powerHeuristic(loadF(L.bsdfPdf), lightPdf), splat(1.0f));
    const F3 radiance = load3(L.radiance);
    maskedStore3(L.radiance, in & emits, radiance + throughput * load3(L.emitted) * weight);
    const I stop = loadMask(L.absorber) | ~seen | (refl >= maxReflections);
    maskedStoreFlag(L.stop, in, stop);

    // Both normals on the side the ray came from; a shading normal that turns away from the viewer
    // (at silhouettes) falls back to the face's. Frame's basis around it.
    const F3 ng = select3(front, ngFront, -ngFront);
    F3 n = select3(front, shadingFront, -shadingFront);
    n = select3(dot(n, dir) >= 0.0f, ng, n);
    const F sign = bitsToFloat((floatToBits(n.z) & int32_t(0x80000000)) | floatToBits(splat(1.0f)));
    const F a = -1.0f / (sign + n.z);
    const F c = n.x * n.y * a;
    store3(L.tangent, {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x});
    store3(L.bitangent, {c, sign + n.y * n.y * a, -n.y});
    store3(L.normal, ng);
    store3(L.shadingNormal, n);
    store3(L.position, p);
    store3(L.offsetPosition, offsetRayOrigin(p, ng));
    storeMask(L.wantLight, indirectOnly ? (refl + 1 >= 2) : kAllLanes);

    U64 state = load<U64>(L.rng);
    const I draw = in & ~stop;
    store(L.uSelect, nextUniform(state, draw));
    store(L.uLight1, nextUniform(state, draw));
    store(L.uLight2, nextUniform(state, draw));
    store(L.rng, state);
}

void reflectLanes(Lanes& L, int rouletteStartReflections) noexcept {
    const I in = loadMask(L.in);
    I stop = loadMask(L.stop);
    const F3 p = load3(L.position), ng = load3(L.normal), ns = load3(L.shadingNormal);
    const F3 origin = load3(L.offsetPosition);
    F3 throughput = load3(L.throughput);
    const F3 albedo = load3(L.albedo);

    // LightSampler::sample for every kind of light. Rectangles (corner + u1 e1 + u2 e2) and triangles
    // (uniformTriangle) are sampled by area, point and spot lights sit at their corner, directional
    // lights send the same direction everywhere.
    const I kind = loadI(L.lightKind);
    const I areal = (kind == kAreaLight) | (kind == kTriangleLight), triangle = kind == kTriangleLight;
    const I spot = kind == kSpotLight, directional = kind == kDirectionalLight;
    const F u1 = loadF(L.uLight1), u2 = loadF(L.uLight2);
    const F s = sqrtOf(u1);
    const F b1 = select(triangle, 1.0f - s, u1), b2 = select(triangle, u2 * s, u2);
    const F3 corner = load3(L.lightCorner), lightNormal = load3(L.lightNormal), emittedL = load3(L.lightEmitted);
    const F3 y = select3(areal, corner + b1 * load3(L.lightEdge1) + b2 * load3(L.lightEdge2), corner);
    const F3 toLight = y - p;
    const F d2 = dot(toLight, toLight);
    const F d = sqrtOf(d2);
    const F invD = 1.0f / d;
    const F3 wi = select3(directional, -lightNormal, toLight * invD);
    const F lightPmf = loadF(L.lightPmf);
    // Rectangles and triangles: one-sided unless two-sided, MIS against the BRDF.
    const F cosFront = -dot(wi, lightNormal);
    const I lightFront = cosFront > 0.0f;
    const F cosLight = select(lightFront, cosFront, -cosFront);
    const F lightArea = loadF(L.lightArea);
    const I arealSampled = (d2 > 0.0f) & (lightFront | loadMask(L.lightTwoSided)) & (cosLight > 0.0f);
    const F3 arealPoint = offsetRayOrigin(y, select3(lightFront, lightNormal, -lightNormal));
    const F3 arealIncident = emittedL * (lightArea * cosLight * invD * invD / lightPmf);
    I sampled = arealSampled;
    F3 incident = arealIncident;
    if (any(in & ~areal)) {  // delta lights; skipped when every lane chose a rectangle or triangle
        // Spot lights: inside the cone, intensity times cos^exponent (pow lane by lane, as libm has it).
        const F cosAlpha = -dot(wi, lightNormal);
        const I inCone = (cosAlpha > loadF(L.lightCosCutoff)) & ~(cosAlpha <= 0.0f);
        F3 intensity = emittedL;
        const I needsPow = in & spot & inCone;
        if (any(needsPow)) {
            alignas(64) float falloff[kLanes], cosAlphas[kLanes];
            alignas(64) int32_t powLanes[kLanes];
            __builtin_memcpy(cosAlphas, &cosAlpha, sizeof cosAlphas);
            __builtin_memcpy(powLanes, &needsPow, sizeof powLanes);
            for (int i = 0; i < kLanes; ++i)
                falloff[i] = powLanes[i] ? __builtin_powf(cosAlphas[i], L.lightExponent[i]) : 1.0f;
            intensity = select3(spot, emittedL * load<F>(falloff), emittedL);
        }
        const I pointSampled = (d2 > 0.0f) & (~spot | inCone);
        const F3 pointIncident = intensity * (1.0f / (d2 * lightPmf));
        const F3 directionalIncident = emittedL * (1.0f / lightPmf);
        sampled = selectI(areal, arealSampled, selectI(directional, kAllLanes, pointSampled));
        incident = select3(areal, arealIncident, select3(directional, directionalIncident, pointIncident));
    }
    sampled &= dot(wi, ng) > 0.0f;
    const F lightPdf = select(areal, lightPmf * d2 / (lightArea * cosLight), splat(0.0f));  // 0: a delta light

    // The Lambert BRDF and its cosine-weighted pdf, and the power heuristic; the shadow ray ends at
    // the light point, or runs to infinity towards a directional light.
    const F cosS = dot(wi, ns);
    const I above = cosS > 0.0f;
    const F3 zero{splat(0.0f), splat(0.0f), splat(0.0f)};
    const F3 f = select3(above, albedo * kInvPi, zero);
    const F pdf = select(above, cosS * kInvPi, splat(0.0f));
    const F weight = select(lightPdf > 0.0f, powerHeuristic(lightPdf, pdf), splat(1.0f));
    maskedStoreFlag(L.shadowActive, in, ~stop & loadMask(L.wantLight) & sampled & (maxComponent3(f) > 0.0f));
    maskedStore3(L.shadowOrigin, in, origin);
    maskedStore3(L.shadowDirection, in, select3(directional, wi, select3(areal, arealPoint, y) - origin));
    maskedStore3(L.shadowContribution, in, throughput * f * (cosS * weight) * incident);
    maskedStore(L.shadowTMax, in, select(directional, splat(__builtin_inff()), splat(1.0f)));

    // cosineHemisphere: points of the square [-1,1)^2 until one falls inside the unit disc, each lane
    // drawing only until its own point is accepted.
    U64 state = load<U64>(L.rng);
    F dx = splat(0.0f), dy = splat(0.0f);
    for (I pending = in & ~stop; any(pending);) {
        const F x = 2.0f * nextUniform(state, pending) - 1.0f;
        const F yy = 2.0f * nextUniform(state, pending) - 1.0f;
        const I accept = pending & (x * x + yy * yy < 1.0f);
        dx = select(accept, x, dx);
        dy = select(accept, yy, dy);
        pending &= ~accept;
    }
    const F dz = sqrtOf(1.0f - dx * dx - dy * dy);
    const F3 dirOut = dx * load3(L.tangent) + dy * load3(L.bitangent) + dz * ns;
    throughput = throughput * albedo;
    stop |= dot(dirOut, ng) <= 0.0f;
    const I refl = loadI(L.reflections) + 1;
    maskedStore3(L.origin, in, origin);
    maskedStore3(L.direction, in, dirOut);
    maskedStore(L.tMax, in, splat(__builtin_inff()));
    maskedStore(L.bsdfPdf, in, dz * kInvPi);
    maskedStore(L.reflections, in, refl);

    // Russian roulette.
    const I roulette = in & ~stop & (refl >= rouletteStartReflections);
    const F survive = minOf(splat(1.0f), maxComponent3(throughput));
    const I dies = roulette & ~(nextUniform(state, roulette) < survive);
    maskedStore3(L.throughput, in, select3(roulette, throughput / survive, throughput));
    maskedStoreFlag(L.stop, in, stop | dies);
    store(L.rng, state);
}

}  // namespace

void hit(Lanes& lanes, int maxReflections, bool indirectOnly) noexcept { hitLanes(lanes, maxReflections, indirectOnly); }

void reflect(Lanes& lanes, int rouletteStartReflections) noexcept { reflectLanes(lanes, rouletteStartReflections); }

}  // namespace bounce::lambert::BOUNCE_LAMBERT_ISA
