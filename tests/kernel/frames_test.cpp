#include "kernel/math/frames.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace groom;

namespace {
void expect_orthonormal(const Frame& f)
{
    EXPECT_NEAR(length(f.t), 1.0f, 1e-5f);
    EXPECT_NEAR(length(f.n), 1.0f, 1e-5f);
    EXPECT_NEAR(dot(f.t, f.n), 0.0f, 1e-5f);
    EXPECT_NEAR(length(f.b - cross(f.t, f.n)), 0.0f, 1e-5f);
}
}  // namespace

// Helix (a cos u, a sin u, b u) has curvature a/c^2 and torsion b/c^2 (c^2 = a^2 + b^2). A rotation-
// minimising frame turns relative to the Frenet frame at the rate of the torsion: after arc length s
// the angle between the RMF normal and the Frenet principal normal is tau * s.
// Even and odd counts: from 16 points the curve is walked as two halves joined by a turn. Three
// turns at most, 21 segments a turn for fewer points (at 15 and 16 points the sampling alone
// misses the tolerance by up to 1.9x: 15 is walked in one piece and fails as 16 does).
class FramesHelix : public ::testing::TestWithParam<int> {};

TEST_P(FramesHelix, TwistMatchesTorsion)
{
    const double a = 1.0, b = 0.35, c = std::sqrt(a * a + b * b), tau = b / (c * c);
    const int n = GetParam();
    const double turns = std::min(3.0, (n - 1) / 21.0), umax = 2.0 * std::numbers::pi * turns;
    std::vector<float3> pts;
    for (int i = 0; i < n; ++i) {
        const double u = umax * i / (n - 1);
        pts.emplace_back(float(a * std::cos(u)), float(a * std::sin(u)), float(b * u));
    }
    const auto frenet_n = [](double u) { return float3(float(-std::cos(u)), float(-std::sin(u)), 0.0f); };
    const auto frenet_b = [&](double u) {
        return float3(float(b * std::sin(u) / c), float(-b * std::cos(u) / c), float(a / c));
    };
    const auto frames = rotation_minimising_frames(pts, frenet_n(0.0));
    double prev = 0.0;
    for (int i = 0; i < n; ++i) {
        expect_orthonormal(frames[i]);
        const double u = umax * i / (n - 1), s = c * u;
        const double angle = std::atan2(dot(frames[i].n, frenet_b(u)), dot(frames[i].n, frenet_n(u)));
        // Unwrap, then compare with the analytic twist (sign: RMF lags the Frenet frame).
        double unwrapped = angle;
        while (unwrapped - prev > std::numbers::pi) unwrapped -= 2.0 * std::numbers::pi;
        while (unwrapped - prev < -std::numbers::pi) unwrapped += 2.0 * std::numbers::pi;
        prev = unwrapped;
        ASSERT_NEAR(std::fabs(unwrapped), tau * s, 2e-3) << "point " << i;
    }
}
INSTANTIATE_TEST_SUITE_P(Frames, FramesHelix, ::testing::Values(17, 32, 63, 64, 1000, 1001, 4001));

// A planar S-curve has an inflection where the Frenet normal flips; the RMF normal started
// perpendicular to the plane must stay exactly perpendicular to it (zero twist), and never flip.
TEST(Frames, SCurveHasNoFlipsAndNoTwist)
{
    std::vector<float3> pts;
    for (int i = 0; i <= 400; ++i) {
        const float x = 4.0f * std::numbers::pi_v<float> * i / 400.0f;
        pts.emplace_back(x, std::sin(x), 0.0f);
    }
    const auto frames = rotation_minimising_frames(pts, {0, 0, 1});
    for (size_t i = 0; i < frames.size(); ++i) {
        expect_orthonormal(frames[i]);
        EXPECT_NEAR(frames[i].n.z, 1.0f, 1e-5f) << i;
        if (i) EXPECT_GT(dot(frames[i].n, frames[i - 1].n), 0.999f);
    }
}

TEST(Frames, InitialNormalParallelToTangentStillGivesAFrame)
{
    const std::vector<float3> pts{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}};
    const auto frames = rotation_minimising_frames(pts, {0, 5, 0});
    for (const Frame& f : frames) expect_orthonormal(f);
}
