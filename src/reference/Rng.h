#pragma once
// Counter-based random numbers for the reference path tracer. A stream is keyed by
// (seed, pixel, sample) and the n-th value is a pure function of (key, n), so an image depends only
// on the seed and never on which thread rendered which pixel, or in which order.
//
// The mixing function is the SplitMix64 finaliser (Steele, Lea and Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014), whose output sequence passes BigCrush.
#include <cstdint>

namespace bounce {

class Rng {
public:
    Rng() noexcept = default;  // a placeholder, to be assigned before use
    Rng(uint64_t seed, uint64_t pixel, uint64_t sample) noexcept
        : m_key(mix((mix(mix(seed + kGolden) ^ pixel) + kGolden) ^ sample)) {}

    // The next 32 uniformly distributed bits.
    uint32_t nextBits() noexcept {
        if (m_hasSpare) {
            m_hasSpare = false;
            return m_spare;
        }
        const uint64_t bits = mix(m_key + (++m_counter) * kGolden);
        m_spare = static_cast<uint32_t>(bits >> 32);
        m_hasSpare = true;
        return static_cast<uint32_t>(bits);
    }

    // Uniform in [0, 1): the top 24 bits scaled by 2^-24, so 1 is never returned.
    float next() noexcept { return static_cast<float>(nextBits() >> 8) * 0x1.0p-24f; }

    static uint64_t mix(uint64_t z) noexcept {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }

private:
    static constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;  // 2^64 / golden ratio (SplitMix64 increment)
    uint64_t m_key = 0;
    uint64_t m_counter = 0;
    uint32_t m_spare = 0;
    bool m_hasSpare = false;
};

}  // namespace bounce
