#pragma once
// Random numbers for the reference path tracer. Each camera path has its own stream, keyed by
// (seed, pixel, sample): the key is hashed into the starting state of a PCG32 generator (O'Neill,
// "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms for Random Number
// Generation", 2014, XSH-RR output), so an image depends only on the seed and never on which thread
// rendered which pixel, or in which order.
//
// The hash is the SplitMix64 finaliser (Steele, Lea and Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014). Streams start at independent-looking points of PCG's 2^64 cycle; a path
// uses a few hundred numbers at most, so overlapping streams are vanishingly unlikely.
#include <cstdint>

namespace bounce {

class Rng {
public:
    Rng() noexcept = default;  // a placeholder, to be assigned before use
    Rng(uint64_t seed, uint64_t pixel, uint64_t sample) noexcept
        : m_state(mix((mix(mix(seed + kGolden) ^ pixel) + kGolden) ^ sample)) {}

    // The next 32 uniformly distributed bits (PCG32 XSH-RR).
    uint32_t nextBits() noexcept {
        const uint64_t old = m_state;
        m_state = old * kMultiplier + kIncrement;
        const auto xorShifted = static_cast<uint32_t>(((old >> 18) ^ old) >> 27);
        const auto rotation = static_cast<uint32_t>(old >> 59);
        return (xorShifted >> rotation) | (xorShifted << ((32u - rotation) & 31u));
    }

    // Uniform in [0, 1): 24 random bits scaled by 2^-24, so 1 is never returned.
    float next() noexcept { return static_cast<float>(nextBits() >> 8) * 0x1.0p-24f; }

    // The raw state, for code that steps many generators side by side (reference/LambertKernel.cpp).
    static Rng fromState(uint64_t state) noexcept {
        Rng r;
        r.m_state = state;
        return r;
    }
    uint64_t state() const noexcept { return m_state; }

    static uint64_t mix(uint64_t z) noexcept {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }

    static constexpr uint64_t kMultiplier = 6364136223846793005ull;  // PCG's 64-bit LCG multiplier (Knuth)
    static constexpr uint64_t kIncrement = 1442695040888963407ull;   // PCG's default odd increment

private:
    static constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;      // 2^64 / golden ratio (SplitMix64)
    uint64_t m_state = 0;
};

}  // namespace bounce
