// Random similarity transforms (rotation, uniform scale, translation) for tests that check a result
// does not depend on where and how large the input is: build from the moved input, map the answers
// back, compare. Computed in double so the transform adds no more than float rounding of its own.
#pragma once

#include "kernel/math/vec.h"
#include "kernel/polygon_soup.h"

#include <cstdint>

namespace groom {

struct Similarity {
    double rotation[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  ///< proper rotation (det +1)
    double scale = 1.0;
    double translation[3] = {0, 0, 0};

    /// A uniformly random rotation, a scale log-uniform in [min_scale, max_scale] and a translation
    /// up to `max_offset` (before scaling) along each axis, all drawn from Rng(seed, 0).
    static Similarity random(uint64_t seed, double min_scale, double max_scale, double max_offset);

    float3 apply(const float3& p) const;                ///< scale * R p + t
    float3 apply_direction(const float3& d) const;      ///< R d
    float3 inverse_direction(const float3& d) const;    ///< R^T d
    PolygonSoup apply(const PolygonSoup& soup) const;   ///< every point moved, faces unchanged
};

}  // namespace groom
