// Counter-based random numbers: every value is a pure hash of (seed, curve id, stream, counter), so
// results do not depend on thread count, scheduling or the order curves are processed in, and
// deleting a curve does not change the randomness of the others.
#pragma once

#include "kernel/math/vec.h"

#include <cmath>
#include <cstdint>

namespace groom {

/// SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr uint64_t mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// A random stream for one element: `Rng rng(seed, curve_id, stream)`; each call advances a counter.
/// Use a distinct `stream` constant per purpose (shape picks, amplitudes, ...) so adding a draw for
/// one purpose never shifts the values drawn for another.
class Rng {
public:
    constexpr Rng(uint64_t seed, uint64_t id, uint64_t stream = 0)
        : key_(mix64(mix64(seed ^ 0x6a09e667f3bcc909ull) ^ mix64(id + 0x3c6ef372fe94f82bull) ^ (stream * 0xa54ff53a5f1d36f1ull)))
    {
    }

    /// Value number `index` of this stream, independent of how many were drawn before.
    constexpr uint64_t at(uint64_t index) const { return mix64(key_ ^ mix64(index)); }

    constexpr uint64_t next_u64() { return at(counter_++); }
    /// Uniform in [0, 1) with 24 bits of precision (exactly representable floats).
    constexpr float uniform() { return static_cast<float>(next_u64() >> 40) * (1.0f / 16777216.0f); }
    /// Uniform in [0, 1) as double, 53 bits.
    constexpr double uniform_double() { return static_cast<double>(next_u64() >> 11) * (1.0 / 9007199254740992.0); }
    /// Uniform in [lo, hi).
    constexpr float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    /// Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; bias below 2^-32 for n < 2^32).
    constexpr uint32_t below(uint32_t n) { return static_cast<uint32_t>(((next_u64() >> 32) * n) >> 32); }
    /// Uniform point in the unit disc (x, y), by polar mapping (area-uniform).
    void disc(float& x, float& y);

private:
    uint64_t key_;
    uint64_t counter_ = 0;
};

inline void Rng::disc(float& x, float& y)
{
    const float r = std::sqrt(uniform());
    const float a = 6.283185307179586f * uniform();
    x = r * std::cos(a);
    y = r * std::sin(a);
}

}  // namespace groom
