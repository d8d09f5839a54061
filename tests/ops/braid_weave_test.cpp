// Tests for the braid patterns (ops/braid_weave via ops/braid), read from the output geometry as a
// person would see it: which strand is on top at each crossing, runs of over / under, which pairs
// cross, whether strands touch where they cross and never pass through each other, hand, ply lay, and
// whether the fibers leave see-through gaps. Guides: straight, an S-curve, and cornrows on an exact
// sphere.
#include "ops/braid.h"

#include "fields/surface.h"
#include "kernel/error.h"
#include "kernel/parallel.h"
#include "tests/ops/braid_crossings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <set>

using namespace groom;
using namespace groom::test;

namespace {

constexpr double kPi = std::numbers::pi;

CurveSet straight_guide(float length, int points = 9)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{points});
    auto P = cs.positions();
    for (int k = 0; k < points; ++k) P[k] = {length * float(k) / float(points - 1), 0.0f, 0.0f};
    return cs;
}

/// A straight guide along +x with normal +y: up = +y, lateral = +z.
GuideFrame straight_frame(double t, double length)
{
    return {float3(float(length * t), 0, 0), float3(0, 0, 1), float3(0, 1, 0)};
}

BraidParams plait(int n, BraidHand hand = BraidHand::Auto)
{
    BraidParams p;
    p.strands = n;
    p.hand = hand;
    p.knot_length = 2.0f;
    p.width = 0.6f;
    p.initial_normal = {0, 1, 0};
    return p;
}

WeaveReading braid_straight(const BraidParams& p, float length, CurveSet* out = nullptr)
{
    const BraidResult r = braid(straight_guide(length), p);
    if (out) *out = r.curves;
    return read_weave(r.curves, 0, p.strand_count(), [&](double t) { return straight_frame(t, length); });
}

/// Crossings away from the two ends (the first and last half knot may hold partial steps).
std::vector<Crossing> inner(const WeaveReading& w, double lo, double hi)
{
    std::vector<Crossing> c;
    for (const Crossing& x : w.crossings)
        if (x.t > lo && x.t < hi) c.push_back(x);
    return c;
}

double strand_width(const CurveSet& cs)
{
    return cs.find<float>(Domain::Point, attr::width)[0];
}

double min_pair_distance(const CurveSet& cs, int64_t first, int n)
{
    double best = 1e30;
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b) best = std::min(best, polyline_distance(cs, first + a, first + b));
    return best;
}

/// An exact sphere of radius R at the origin as a Surface.
class Sphere : public Surface {
public:
    explicit Sphere(float r) : r_(r) {}
    float distance(const float3& p) const override { return length(p) - r_; }
    float3 normal(const float3& p) const override { return normalize(p); }
    float3 closest_point(const float3& p) const override { return normalize(p) * r_; }

private:
    float r_;
};

}  // namespace

// The classic plait: every strand alternates over, under at consecutive crossings, and each pair of
// the three crosses. Read as a person would: top view, who is higher where two strands meet.
TEST(BraidWeave, ThreeStrandPlaitAlternatesOverUnder)
{
    for (const BraidHand hand : {BraidHand::Under, BraidHand::Over}) {
        const WeaveReading w = braid_straight(plait(3, hand), 8.0f);
        for (int i = 0; i < 3; ++i) {
            SCOPED_TRACE("strand " + std::to_string(i) + ": " + w.sequence[i]);
            ASSERT_GE(w.sequence[i].size(), 12u);  // 4 knots, 4 crossings per strand per knot
            for (size_t k = 1; k < w.sequence[i].size(); ++k) EXPECT_NE(w.sequence[i][k], w.sequence[i][k - 1]) << "at " << k;
        }
        EXPECT_EQ(w.max_run, 1);
        EXPECT_EQ(w.pair_crossings.size(), 3u);
    }
}

// Under-hand (Dutch): the strand travelling toward the middle passes beneath; over-hand the reverse.
TEST(BraidWeave, ThreeStrandHandDecidesWhoGoesBeneath)
{
    for (const BraidHand hand : {BraidHand::Under, BraidHand::Over}) {
        const WeaveReading w = braid_straight(plait(3, hand), 8.0f);
        int checked = 0;
        for (const Crossing& c : inner(w, 0.05, 0.95)) {
            ASSERT_NE(c.top_inward, c.bottom_inward) << "t " << c.t;  // one moves in, the other out
            EXPECT_EQ(c.bottom_inward, hand == BraidHand::Under) << "t " << c.t;
            ++checked;
        }
        EXPECT_GT(checked, 10);
    }
}

// N = 2..8: no strand over or under for more than two crossings in a row, every pair crosses, and
// strands touch where they cross without passing through each other (closest centrelines >= 0.8
// strand widths, vertical gap at a crossing <= 1.35 widths).
TEST(BraidWeave, FlatPlaitsOfAnyStrandCountWeave)
{
    for (int n = 2; n <= 8; ++n) {
        SCOPED_TRACE("N = " + std::to_string(n));
        CurveSet out;
        const BraidParams p = plait(n);
        const WeaveReading w = braid_straight(p, 8.0f, &out);
        EXPECT_LE(w.max_run, 2);
        for (int i = 0; i < n; ++i) {
            SCOPED_TRACE(w.sequence[i]);
            EXPECT_GE(w.sequence[i].size(), size_t(2 * (n - 1) * 3));  // >= 3 knots' worth
        }
        EXPECT_EQ(int(w.pair_crossings.size()), n * (n - 1) / 2);
        const double width = strand_width(out);
        double max_gap = 0.0, min_gap = 1e30;
        for (const Crossing& c : w.crossings) {
            max_gap = std::max(max_gap, c.gap);
            min_gap = std::min(min_gap, c.gap);
        }
        EXPECT_LE(max_gap, 1.35 * width);
        EXPECT_GE(min_pair_distance(out, 0, n), 0.8 * width);
        EXPECT_GE(min_gap, 0.8 * width);
    }
}

// For N >= 4 the hand is seen at the outer crossings: under-hand, the strand coming in from the edge
// passes beneath.
TEST(BraidWeave, WideFlatPlaitHandAtTheOuterCrossings)
{
    for (int n = 4; n <= 7; ++n) {
        for (const BraidHand hand : {BraidHand::Under, BraidHand::Over}) {
            SCOPED_TRACE("N = " + std::to_string(n) + (hand == BraidHand::Under ? " under" : " over"));
            const BraidParams p = plait(n, hand);
            const WeaveReading w = braid_straight(p, 8.0f);
            const double outer = 0.6 * (1.0 - 2.0 / (n - 1)) + 0.4 * 1.0;  // between the outer slot pair's crossing and the next
            int checked = 0;
            for (const Crossing& c : inner(w, 0.05, 0.95)) {
                if (std::fabs(c.lateral) < outer * *p.width * 0.9) continue;
                EXPECT_EQ(c.bottom_inward, hand == BraidHand::Under) << "t " << c.t << " at " << c.lateral;
                ++checked;
            }
            EXPECT_GT(checked, 4);
        }
    }
}

// The talk's formula as written, kept as --pattern lissajous: each of three strands goes over four
// crossings, then under four (why it is not the default).
TEST(BraidWeave, LissajousPatternIsTheTalksRopeLikeSequence)
{
    BraidParams p = plait(3);
    p.hand = BraidHand::Auto;
    p.pattern = BraidPattern::Lissajous;
    p.height = 0.3f;
    const WeaveReading w = braid_straight(p, 16.0f);
    EXPECT_EQ(w.max_run, 4);
    for (int i = 0; i < 3; ++i) EXPECT_NE(w.sequence[i].find("OOOOUUUU"), std::string::npos) << w.sequence[i];
}

