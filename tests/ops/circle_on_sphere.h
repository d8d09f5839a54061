// Test helper: a circle on a sphere as a closed curve, the closed form of a hairline (the cap on one
// side of the circle's plane is exactly what it bounds).
#pragma once

#include "kernel/curve_set.h"
#include "kernel/math/vec.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace groom::test {

/// The circle where the plane through c + normal * offset (unit normal) cuts the sphere (c, R), n
/// points, the first not repeated at the end; `reverse` runs it the other way round.
inline CurveSet circle_on_sphere(const float3& c, float R, const float3& normal, float offset, int n, bool reverse = false)
{
    const float3 e1 = any_perpendicular(normal), e2 = cross(normal, e1);
    const float r = std::sqrt(R * R - offset * offset);
    CurveSet curve = CurveSet::from_counts(std::vector<int64_t>{n});
    auto P = curve.positions_for_write();
    for (int i = 0; i < n; ++i) {
        const float a = 2.0f * 3.14159265358979f * float(i) / float(n) * (reverse ? -1.0f : 1.0f);
        P[i] = c + normal * offset + (e1 * std::cos(a) + e2 * std::sin(a)) * r;
    }
    return curve;
}

}  // namespace groom::test
