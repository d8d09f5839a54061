// drape_runs (fields/drape_runs.h) on a sphere's level set: a run keep_outside would fold is laid
// over the sphere along one direction, to the sphere's closed form; what has no fold the move made
// is left; the result is the same for any thread count.
#include "fields/drape_runs.h"
#include "fields/scalp_field.h"
#include "kernel/parallel.h"
#include "support/curve_turns.h"
#include "support/sphere_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

using namespace groom;
using groom::test::largest_turns;
using groom::test::Turn;

namespace {

constexpr float kR = 10.0f;

const ScalpField& sphere()
{
    static const ScalpField s = build_scalp(icosphere({0, 0, 0}, kR, 5), {kR / 40.0f, 3.0f});
    return s;
}

/// The record keep_outside would make of the points of `cs` that differ from `before`.
std::vector<MovedPoint> moves(const CurveSet& cs, const std::vector<float3>& before)
{
    std::vector<MovedPoint> m;
    for (size_t i = 0; i < before.size(); ++i)
        if (!(cs.positions()[i] == before[i])) m.push_back({int64_t(i), before[i]});
    return m;
}

/// 13 points along y = 9.5 from x = -6 to 6: x in [-3, 3] lie under the sphere's cap.
CurveSet chord_under_the_cap()
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{13});
    auto P = cs.positions_for_write();
    for (int i = 0; i < 13; ++i) P[size_t(i)] = {float(i - 6), 9.5f, 0.0f};
    return cs;
}

}  // namespace

TEST(DrapeRuns, AFoldedRunIsLaidOverTheSphereAlongOneDirection)
{
    // The run under the cap gathered at the top and folded back (as keep_outside left hair in an
    // ear flap: each point at a rim point of its own choosing). Laid again, each point goes straight
    // up (the moves' mean, across the chord) onto the sphere: (x, sqrt(R^2 - x^2), 0), to within the
    // level set's error (voxel R / 40: 0.05), in order, turning by no more than the cap does.
    const ScalpField& s = sphere();
    CurveSet cs = chord_under_the_cap();
    const std::vector<float3> before(cs.positions().begin(), cs.positions().end());
    auto P = cs.positions_for_write();
    for (int i = 3; i <= 9; ++i) P[size_t(i)] = {i == 9 ? -0.5f : 0.0f, kR, 0.0f};
    ASSERT_GT(largest_turns(cs)[0].degrees, 90.0);
    const KeepOutside rule{0.0f, 1e-4f, 16};
    const DrapeCount d = drape_runs(cs, moves(cs, before), s, rule);
    EXPECT_EQ(d.runs, 1);
    EXPECT_EQ(d.curves, 1);
    for (int i = 0; i < 13; ++i) {
        const float x = float(i - 6);
        const float3 p = cs.positions()[size_t(i)];
        if (i < 3 || i > 9) {
            EXPECT_EQ(p, before[size_t(i)]) << i;  // outside the run: untouched
            continue;
        }
        EXPECT_NEAR(p.x, x, 1e-4f) << i;
        EXPECT_NEAR(p.z, 0.0f, 1e-4f) << i;
        EXPECT_NEAR(p.y, std::sqrt(kR * kR - x * x), 0.05f) << i;
        EXPECT_GE(s.distance(p), 0.0f) << i;  // clear by the rule
    }
    // The cap between x = -3 and 3 turns by 2 asin(0.3) = 35 degrees in all; the joins at the run's
    // ends by about as much.
    EXPECT_LT(largest_turns(cs)[0].degrees, 40.0);
}

TEST(DrapeRuns, RunsMovedWithoutAFoldAreLeftAsTheyAre)
{
    // keep_outside's own push of the chord (each point out along the sphere's normal) does not
    // fold it: nothing is laid again. Nor is anything when no point moved.
    const ScalpField& s = sphere();
    CurveSet cs = chord_under_the_cap();
    const std::vector<float3> before(cs.positions().begin(), cs.positions().end());
    const KeepOutside rule{0.0f, 1e-4f, 16};
    std::vector<MovedPoint> record;
    keep_outside(cs, s, rule, &record);
    const std::vector<float3> pushed(cs.positions().begin(), cs.positions().end());
    ASSERT_NE(pushed[6], before[6]);
    ASSERT_EQ(record.size(), 7u);  // x = -3 .. 3
    for (size_t k = 0; k < record.size(); ++k) EXPECT_EQ(record[k].before, before[size_t(record[k].index)]);
    EXPECT_EQ(drape_runs(cs, record, s, rule).runs, 0);
    EXPECT_EQ(drape_runs(cs, {}, s, rule).runs, 0);
    for (size_t i = 0; i < pushed.size(); ++i) EXPECT_EQ(cs.positions()[i], pushed[i]) << i;
}

TEST(DrapeRuns, AFoldTheCurveAlreadyHadIsNotTheMovesToMend)
{
    // A hairpin the input itself makes (a coil, a guide folded on purpose) stays, even where points
    // of it were moved.
    const ScalpField& s = sphere();
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{5});
    auto P = cs.positions_for_write();
    const float3 pin[5] = {{-4, 9.5f, 0}, {0, 9.8f, 0}, {4, 9.5f, 0}, {0, 9.9f, 0}, {-4, 10.5f, 0}};
    for (int i = 0; i < 5; ++i) P[size_t(i)] = pin[i];
    const std::vector<float3> before(P.begin(), P.end());
    P[1] = {0, kR, 0}, P[3] = {0.1f, kR, 0};
    const std::vector<float3> moved(P.begin(), P.end());
    EXPECT_EQ(drape_runs(cs, moves(cs, before), s, KeepOutside{0.0f, 1e-4f, 16}).runs, 0);
    for (size_t i = 0; i < moved.size(); ++i) EXPECT_EQ(cs.positions()[i], moved[i]) << i;
}

TEST(DrapeRuns, SameForAnyThreadCount)
{
    // 1,200 folded runs (the chord under the cap turned about the vertical axis), laid with one
    // thread and with all: the same bits, and the same record from keep_outside.
    const ScalpField& s = sphere();
    constexpr int kCurves = 1200;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(kCurves, 13));
    auto P = cs.positions_for_write();
    for (int c = 0; c < kCurves; ++c) {
        const float a = 6.2831853f * float(c) / float(kCurves), ca = std::cos(a), sa = std::sin(a);
        for (int i = 0; i < 13; ++i) P[size_t(c * 13 + i)] = {float(i - 6) * ca, 9.5f, float(i - 6) * sa};
    }
    const std::vector<float3> before(P.begin(), P.end());
    for (int c = 0; c < kCurves; ++c)
        for (int i = 3; i <= 9; ++i) P[size_t(c * 13 + i)] = {i == 9 ? -0.5f * std::cos(6.2831853f * float(c) / float(kCurves)) : 0.0f, kR, 0.0f};
    const std::vector<MovedPoint> record = moves(cs, before);
    const KeepOutside rule{0.0f, 1e-4f, 16};
    const auto run = [&](int threads) {
        ThreadLimit limit(threads);
        CurveSet copy = cs;
        const DrapeCount d = drape_runs(copy, record, s, rule);
        EXPECT_EQ(d.curves, kCurves);
        return copy;
    };
    const CurveSet one = run(1), all = run(0);
    EXPECT_EQ(std::memcmp(one.positions().data(), all.positions().data(), one.positions().size_bytes()), 0);

    const auto record_of = [&](int threads) {
        ThreadLimit limit(threads);
        CurveSet copy = CurveSet::from_counts(std::vector<int64_t>(kCurves, 13));
        auto Q = copy.positions_for_write();
        std::copy(before.begin(), before.end(), Q.begin());
        std::vector<MovedPoint> r;
        keep_outside(copy, s, rule, &r);
        return r;
    };
    const std::vector<MovedPoint> r1 = record_of(1), r2 = record_of(0);
    ASSERT_EQ(r1.size(), size_t(kCurves) * 7);
    ASSERT_EQ(r1.size(), r2.size());
    for (size_t k = 0; k < r1.size(); ++k) {
        EXPECT_EQ(r1[k].index, r2[k].index);
        EXPECT_EQ(r1[k].before, r2[k].before);
        if (k > 0) EXPECT_LT(r1[k - 1].index, r1[k].index);
    }
}

TEST(DrapeRuns, ARecordOutOfOrderIsRefused)
{
    const ScalpField& s = sphere();
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{13, 13});
    const std::vector<MovedPoint> record = {{15, {0, 0, 0}}, {2, {0, 0, 0}}};
    EXPECT_THROW(drape_runs(cs, record, s, KeepOutside{0.0f, 1e-4f, 16}), InvalidParam);
}
