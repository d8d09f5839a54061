// Test helper: guides whose geometry is known in closed form, for the partition and adjacency tests:
// meridian arcs on the unit sphere and straight guides above the plane y = 0.
#pragma once

#include "kernel/curve_set.h"
#include "kernel/math/vec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace groom::test {

/// Point at latitude `lat` and longitude `lon` (radians) on the sphere of radius r about the origin,
/// +Y up. Seen from outside, going north along a meridian, longitude grows to the left.
inline float3 on_sphere(float lat, float lon, float r = 1.0f)
{
    return {r * std::cos(lat) * std::cos(lon), r * std::sin(lat), r * std::cos(lat) * std::sin(lon)};
}

struct Arc {
    float lon, lat0, lat1;  ///< a meridian arc running north from lat0 to lat1
};

/// Guides sampled along meridian arcs of the unit sphere, 201 points each.
inline CurveSet meridian_guides(const std::vector<Arc>& arcs, int points = 201)
{
    std::vector<int64_t> counts(arcs.size(), points);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t c = 0; c < arcs.size(); ++c) {
        for (int i = 0; i < points; ++i) {
            const float lat = arcs[c].lat0 + (arcs[c].lat1 - arcs[c].lat0) * float(i) / float(points - 1);
            P[cs.points_of(c).begin + i] = on_sphere(lat, arcs[c].lon);
        }
    }
    return cs;
}

/// Straight guides along +Z at the given x, at height h above the plane y = 0, from z = 0 to z = len.
/// Only 5 points each: the closest point must be exact on segments, not just at vertices.
inline CurveSet straight_guides(const std::vector<float>& xs, float h = 0.2f, float len = 4.0f)
{
    std::vector<int64_t> counts(xs.size(), 5);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t c = 0; c < xs.size(); ++c)
        for (int i = 0; i < 5; ++i) P[cs.points_of(c).begin + i] = float3(xs[c], h, len * float(i) / 4.0f);
    return cs;
}

}  // namespace groom::test

#define EXPECT_NEAR3(a, b, tol)                                                                            \
    do {                                                                                                   \
        const ::groom::float3 a_ = (a), b_ = (b);                                                          \
        EXPECT_LE(distance(a_, b_), (tol)) << "(" << a_.x << "," << a_.y << "," << a_.z << ") vs (" << b_.x \
                                           << "," << b_.y << "," << b_.z << ")";                           \
    } while (0)
