// PositionKey: a point's exact position as a hash key, for finding the vertices of a soup that
// share one (welding statistics, tracing a repaired triangle back to the file's part it came from).
#pragma once

#include "kernel/math/vec.h"

#include <cstdint>
#include <cstring>

namespace groom {

struct PositionKey {
    uint32_t x, y, z;
    bool operator==(const PositionKey&) const = default;

    /// The key of p: its coordinates' bits, with -0 and +0 the same position.
    static PositionKey of(const float3& p) { return {bits(p.x), bits(p.y), bits(p.z)}; }

private:
    static uint32_t bits(float f)
    {
        if (f == 0.0f) f = 0.0f;
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    }
};

struct PositionHash {
    size_t operator()(const PositionKey& k) const
    {
        uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
        h ^= (h >> 29) + k.y * 0xBF58476D1CE4E5B9ull;
        h ^= (h >> 31) + k.z * 0x94D049BB133111EBull;
        return static_cast<size_t>(h ^ (h >> 32));
    }
};

}  // namespace groom
