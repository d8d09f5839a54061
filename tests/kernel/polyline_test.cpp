#include "kernel/math/polyline.h"
#include "kernel/math/spline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace groom;

namespace {
std::vector<float3> circle(int n, float r, bool closed)
{
    std::vector<float3> pts;
    for (int i = 0; i <= (closed ? n : n - 1); ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        pts.emplace_back(float(r * std::cos(a)), 0.0f, float(r * std::sin(a)));
    }
    return pts;
}
}  // namespace

TEST(Polyline, CircleLengthMatchesChordFormulaAndConverges)
{
    // A closed regular n-gon inscribed in radius r has perimeter 2 n r sin(pi/n) exactly.
    for (int n : {8, 64, 4096}) {
        const float r = 2.5f;
        const double exact = 2.0 * n * r * std::sin(std::numbers::pi / n);
        EXPECT_NEAR(polyline_length(circle(n, r, true)), exact, 1e-5 * exact) << n;
    }
    // ... and tends to 2 pi r: error O(1/n^2), below 1e-6 relative at n = 4096.
    EXPECT_NEAR(polyline_length(circle(4096, 1.0f, true)), 2.0 * std::numbers::pi, 2e-6 * 2.0 * std::numbers::pi);
}

TEST(Polyline, ResampleStraightLineGivesEqualSpacingAndKeepsEnds)
{
    const std::vector<float3> pts{{0, 0, 0}, {0.1f, 0, 0}, {0.15f, 0, 0}, {3, 0, 0}};
    const auto out = resample_by_count(pts, 7);
    ASSERT_EQ(out.size(), 7u);
    EXPECT_EQ(out.front(), pts.front());
    EXPECT_EQ(out.back(), pts.back());
    for (int i = 0; i < 7; ++i) EXPECT_NEAR(out[i].x, 0.5f * i, 1e-6f);
}

TEST(Polyline, ResamplePreservesLengthOfCircleArc)
{
    const auto arc = circle(1000, 1.0f, false);
    const auto out = resample_by_count(arc, 200);
    const auto cum = cumulative_lengths(out);
    // Equal arc-length spacing on the input polyline: each chord of the output spans the same arc,
    // so all chords are equal up to the input's own discretisation.
    const double step = cum[1] - cum[0];
    for (size_t i = 2; i < cum.size(); ++i) EXPECT_NEAR(cum[i] - cum[i - 1], step, 1e-5);
}

TEST(Polyline, TangentsSkipZeroLengthSegments)
{
    const std::vector<float3> pts{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}};
    for (const float3& t : polyline_tangents(pts)) EXPECT_NEAR(t.x, 1.0f, 1e-6f);
}

TEST(Spline, CatmullRomInterpolatesControlPoints)
{
    const std::vector<float3> cvs{{0, 0, 0}, {1, 2, 0}, {2, -1, 0}, {3, 0, 1}, {4, 4, 4}};
    const auto pts = evaluate_cubic(cvs, CubicBasis::CatmullRom, false, 4);
    // Non-periodic, unpinned: 2 segments from cvs[1] to cvs[3], 4 samples each + end.
    ASSERT_EQ(pts.size(), 9u);
    EXPECT_EQ(pts[0], cvs[1]);
    EXPECT_EQ(pts[4], cvs[2]);
    EXPECT_EQ(pts[8], cvs[3]);
    const auto pinned = evaluate_cubic(cvs, CubicBasis::CatmullRom, true, 4);
    EXPECT_EQ(pinned.front(), cvs.front());
    EXPECT_EQ(pinned.back(), cvs.back());
}

TEST(Spline, BSplineReproducesLinesAndConstants)
{
    // Uniform B-splines reproduce linear functions: equally spaced collinear points give the line.
    std::vector<float3> cvs;
    for (int i = 0; i < 6; ++i) cvs.emplace_back(float(i), 2.0f * i, 5.0f);
    const auto pts = evaluate_cubic(cvs, CubicBasis::BSpline, false, 8);
    ASSERT_EQ(pts.size(), 3u * 8u + 1u);
    for (size_t i = 0; i < pts.size(); ++i) {
        const float x = 1.0f + float(i) / 8.0f;  // curve spans cvs[1]..cvs[4]
        EXPECT_NEAR(pts[i].x, x, 1e-5f);
        EXPECT_NEAR(pts[i].y, 2.0f * x, 1e-5f);
        EXPECT_NEAR(pts[i].z, 5.0f, 1e-5f);
    }
    // Pinned B-spline ends exactly on the end control points.
    const auto pinned = evaluate_cubic(cvs, CubicBasis::BSpline, true, 8);
    EXPECT_NEAR(distance(pinned.front(), cvs.front()), 0.0f, 1e-5f);
    EXPECT_NEAR(distance(pinned.back(), cvs.back()), 0.0f, 1e-5f);
}

TEST(Spline, UniformSplineReproducesLinearValues)
{
    const std::vector<float> v{0.0f, 1.0f, 2.0f, 3.0f};
    for (float t = 0.0f; t <= 1.0f; t += 0.05f) EXPECT_NEAR(sample_uniform_spline(v, t), 3.0f * t, 1e-5f);
    const std::vector<float> c{0.7f};
    EXPECT_EQ(sample_uniform_spline(c, 0.3f), 0.7f);
    EXPECT_EQ(sample_uniform_spline({}, 0.3f), 1.0f);
}

TEST(Polyline, LocateAtLengthOnAStraightLine)
{
    // Points at x = 0, 1, 3, 3 (twice: a zero-length segment), 6.
    const std::vector<float3> pts{{0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {3, 0, 0}, {6, 0, 0}};
    const std::vector<double> cum = cumulative_lengths(pts);
    struct Want {
        double s;
        size_t lo, hi;
        double t;
        size_t nearest;
    };
    const Want cases[] = {
        {0.25, 0, 1, 0.25, 0},  // inside the first segment
        {0.5, 0, 1, 0.5, 1},    // halfway: the later point
        {1.0, 1, 2, 0.0, 1},    // on a point: the segment it starts
        {2.5, 1, 2, 0.75, 2},
        {3.0, 3, 4, 0.0, 3},    // on coincident points: the last of them
        {4.5, 3, 4, 0.5, 4},
        {6.0, 3, 4, 1.0, 4},    // the tip: the end of the last segment
        {-1.0, 0, 1, 0.0, 0},   // clamped
        {10.0, 3, 4, 1.0, 4},
    };
    size_t cursor = 0;  // the walking form, asked in the table's order (up, then back down, clamped)
    for (const Want& w : cases) {
        const ArcSpot walked = locate_at_length(cum, w.s, cursor);
        EXPECT_EQ(walked.lo, w.lo) << w.s;
        EXPECT_EQ(walked.hi, w.hi) << w.s;
        EXPECT_DOUBLE_EQ(walked.t, w.t) << w.s;
        EXPECT_EQ(walked.nearest, w.nearest) << w.s;
        const ArcSpot a = locate_at_length(cum, w.s);
        EXPECT_EQ(a.lo, w.lo) << w.s;
        EXPECT_EQ(a.hi, w.hi) << w.s;
        EXPECT_DOUBLE_EQ(a.t, w.t) << w.s;
        EXPECT_EQ(a.nearest, w.nearest) << w.s;
        // The same place as point_at_length.
        EXPECT_FLOAT_EQ(point_at_length(pts, cum, w.s).x, float(std::clamp(w.s, 0.0, 6.0))) << w.s;
    }
    // One point: everything is that point.
    const std::vector<double> one{0.0};
    const ArcSpot a = locate_at_length(one, 0.5);
    EXPECT_EQ(a.lo, 0u);
    EXPECT_EQ(a.hi, 0u);
    EXPECT_EQ(a.t, 0.0);
    EXPECT_EQ(a.nearest, 0u);
}
