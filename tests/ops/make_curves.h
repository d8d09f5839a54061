// Test helper: a CurveSet from explicit point lists, for the braid tests that write their guides out
// point by point.
#pragma once

#include "kernel/curve_set.h"
#include "kernel/math/vec.h"

#include <cstdint>
#include <vector>

namespace groom::test {

/// One curve per list, its points in order (root first).
inline CurveSet make_curves(const std::vector<std::vector<float3>>& curves)
{
    std::vector<int64_t> counts;
    for (const auto& c : curves) counts.push_back(int64_t(c.size()));
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    size_t q = 0;
    for (const auto& c : curves)
        for (const float3& p : c) P[q++] = p;
    return cs;
}

}  // namespace groom::test
