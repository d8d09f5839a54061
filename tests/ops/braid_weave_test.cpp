// Tests for the braid patterns (ops/braid_weave via ops/braid), read from the output geometry as a
// person would see it: which strand is on top at each crossing, runs of over / under, which pairs
// cross, whether strands touch where they cross and never pass through each other, hand, ply lay, and
// whether the fibers leave see-through gaps. Guides: straight, an S-curve, and cornrows on an exact
// sphere.
#include "ops/braid.h"

#include "fields/surface.h"
#include "kernel/math/frames.h"
#include "kernel/math/polyline.h"
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
    auto P = cs.positions_for_write();
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

/// Angle of a point about the guide axis in the (lateral, up) plane, and its distance from the axis.
double angle_of(const Local& l) { return std::atan2(l.up, l.lateral); }
double radius_of(const Local& l) { return std::hypot(l.up, l.lateral); }

/// Cornrow guides on an exact sphere of radius 10: arcs of constant longitude, 0.2 above the surface.
CurveSet sphere_arcs(int count, double lift = 0.2)
{
    std::vector<int64_t> counts(count, 31);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (int g = 0; g < count; ++g) {
        const double lon = g * 25.0 * kPi / 180.0;
        for (int k = 0; k <= 30; ++k) {
            const double lat = (75.0 - 70.0 * k / 30.0) * kPi / 180.0, r = 10.0 + lift;
            P[g * 31 + k] = {float(r * std::cos(lat) * std::cos(lon)), float(r * std::sin(lat)), float(r * std::cos(lat) * std::sin(lon))};
        }
    }
    return cs;
}

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


// Fishtail: a thin piece from the outside of one section crosses over its own section into the other;
// at every crossing the piece moving toward the middle is on top (herringbone), and every piece
// travels from one section to the other and back once per knot.
TEST(BraidWeave, FishtailOuterPieceCrossesOnTop)
{
    for (const BraidHand hand : {BraidHand::Over, BraidHand::Under}) {
        BraidParams p = plait(8, hand);
        p.pattern = BraidPattern::Fishtail;
        CurveSet out;
        const WeaveReading w = braid_straight(p, 8.0f, &out);
        int checked = 0;
        for (const Crossing& c : inner(w, 0.02, 0.98)) {
            ASSERT_NE(c.top_inward, c.bottom_inward) << c.t;
            EXPECT_EQ(c.top_inward, hand == BraidHand::Over) << c.t;
            ++checked;
        }
        EXPECT_GT(checked, 50);
        for (int i = 0; i < 8; ++i) {
            int sides = 0;
            for (size_t j = 1; j < w.strands[i].size(); ++j) sides += (w.strands[i][j].lateral > 0) != (w.strands[i][j - 1].lateral > 0);
            EXPECT_NEAR(sides, 2 * 4, 1) << "strand " << i;  // 4 knots, over to the other section and back
        }
        EXPECT_GE(min_pair_distance(out, 0, 8), 0.8 * strand_width(out));
    }
}

// Rope and twist: plies wind one way about the axis, one turn per knot; seen from above a ply is over
// the others for N - 1 crossings, then under them for N - 1.
TEST(BraidWeave, RopePliesWindOneWay)
{
    for (const int n : {2, 3, 4}) {
        for (const BraidHand hand : {BraidHand::Over, BraidHand::Under}) {
            SCOPED_TRACE("N = " + std::to_string(n));
            BraidParams p = plait(n, hand);
            p.pattern = n == 2 ? BraidPattern::Twist : BraidPattern::Rope;
            CurveSet out;
            const WeaveReading w = braid_straight(p, 8.0f, &out);
            for (int i = 0; i < n; ++i) {
                double turned = 0.0;
                for (size_t j = 1; j < w.strands[i].size(); ++j) {
                    double d = angle_of(w.strands[i][j]) - angle_of(w.strands[i][j - 1]);
                    d -= 2.0 * kPi * std::round(d / (2.0 * kPi));
                    EXPECT_GT(d * (hand == BraidHand::Over ? 1.0 : -1.0), 0.0) << "ply " << i << " turns back at " << j;
                    turned += d;
                }
                EXPECT_NEAR(std::fabs(turned) / (2.0 * kPi), 4.0, 1e-3);  // 4 knots
                const std::string& q = w.sequence[i];
                const std::string over(n - 1, 'O'), under(n - 1, 'U');
                EXPECT_NE(q.find(over + under + over), std::string::npos) << q;
                EXPECT_EQ(w.max_run, n - 1) << q;
            }
            EXPECT_GE(min_pair_distance(out, 0, n), 0.8 * strand_width(out));
        }
    }
}

// A twist's fibers turn about their ply against the plies' lay (that is what holds a twist).
TEST(BraidWeave, TwistFibersTurnAgainstThePlies)
{
    BraidParams p = plait(2, BraidHand::Over);
    p.pattern = BraidPattern::Twist;
    p.fibers = 6;
    p.fiber_twist = 1.5f;
    const CurveSet strands = braid(straight_guide(8.0f), [&] { BraidParams q = p; q.fibers = 0; return q; }()).curves;
    const CurveSet fibers = braid(straight_guide(8.0f), p).curves;
    const auto SP = strands.positions();
    const auto FP = fibers.positions();
    const auto frame = [](double t) { return straight_frame(t, 8.0); };
    for (int64_t f = 0; f < 6; ++f) {  // fibers of ply 0
        const IndexRange fr = fibers.points_of(f), sr = strands.points_of(0);
        ASSERT_EQ(fr.size(), sr.size());
        double ply_turn = 0.0, fiber_turn = 0.0, prev_ply = 0.0, prev_fib = 0.0;
        for (int64_t j = 0; j < fr.size(); ++j) {
            const GuideFrame g = frame(double(j) / double(fr.size() - 1));
            const float3 ply = SP[sr.begin + j] - g.origin, off = FP[fr.begin + j] - SP[sr.begin + j];
            const double a_ply = std::atan2(dot(ply, g.up), dot(ply, g.lateral));
            const double a_fib = std::atan2(dot(off, g.up), dot(off, g.lateral));
            if (j > 0) {
                const auto step = [](double d) { return d - 2.0 * kPi * std::round(d / (2.0 * kPi)); };
                ply_turn += step(a_ply - prev_ply);
                fiber_turn += step(a_fib - prev_fib);
            }
            prev_ply = a_ply;
            prev_fib = a_fib;
        }
        EXPECT_GT(ply_turn, 0.0);
        EXPECT_LT(fiber_turn, 0.0) << "fiber " << f << " turns with the ply";
    }
}

// Round braid: half the strands wind one way about the axis, half the other; where two meet, one
// passes outside and one inside, and each strand alternates outside / inside at consecutive meetings.
TEST(BraidWeave, RoundBraidAlternatesOutsideInside)
{
    for (const int n : {4, 6}) {
        BraidParams p = plait(n, BraidHand::Over);
        p.pattern = BraidPattern::Round;
        CurveSet out;
        const WeaveReading w = braid_straight(p, 8.0f, &out);
        std::vector<std::string> seq(n);
        std::set<std::pair<int, int>> met;
        struct Meet {
            double t;
            int outside, inside;
        };
        std::vector<Meet> meets;
        const size_t S = w.strands[0].size();
        for (int a = 0; a < n; ++a) {
            for (int b = a + 1; b < n; ++b) {
                for (size_t j = 0; j + 1 < S; ++j) {
                    const auto diff = [&](size_t k) {
                        double d = angle_of(w.strands[a][k]) - angle_of(w.strands[b][k]);
                        return d - 2.0 * kPi * std::round(d / (2.0 * kPi));
                    };
                    const double d0 = diff(j), d1 = diff(j + 1);
                    if (!((d0 < 0.0) != (d1 < 0.0)) || std::fabs(d0 - d1) > kPi) continue;
                    const double ra = radius_of(w.strands[a][j]) + radius_of(w.strands[a][j + 1]);
                    const double rb = radius_of(w.strands[b][j]) + radius_of(w.strands[b][j + 1]);
                    meets.push_back({double(j), ra > rb ? a : b, ra > rb ? b : a});
                    met.insert({a, b});
                }
            }
        }
        std::sort(meets.begin(), meets.end(), [](const Meet& x, const Meet& y) { return x.t < y.t; });
        for (const Meet& m : meets) {
            seq[m.outside] += 'O';
            seq[m.inside] += 'I';
        }
        for (int i = 0; i < n; ++i) {
            SCOPED_TRACE(seq[i]);
            EXPECT_GE(seq[i].size(), 4u * 4u);
            for (size_t k = 1; k < seq[i].size(); ++k) EXPECT_NE(seq[i][k], seq[i][k - 1]);
        }
        EXPECT_EQ(int(met.size()), (n / 2) * (n / 2));  // every strand meets every strand of the other set
        EXPECT_GE(min_pair_distance(out, 0, n), 0.8 * strand_width(out));
    }
}

// On an S-curve the weave is carried by the frames: still a plait, still tight.
TEST(BraidWeave, PlaitOnAnSCurveStillWeaves)
{
    std::vector<int64_t> counts{121};
    CurveSet g = CurveSet::from_counts(counts);
    auto P = g.positions_for_write();
    for (int k = 0; k <= 120; ++k) {
        const double x = 12.0 * k / 120.0;
        P[k] = {float(x), 0.0f, float(1.5 * std::sin(2.0 * kPi * x / 12.0))};
    }
    BraidParams p = plait(3, BraidHand::Under);
    const CurveSet out = braid(g, p).curves;
    // The guide's own frames, independently: resample evenly, rotation-minimising, normal +y.
    const std::vector<float3> C = resample_by_count(std::span<const float3>(P.data(), P.size()), out.points_in(0));
    const std::vector<Frame> F = rotation_minimising_frames(C, float3(0, 1, 0));
    const auto frame = [&](double t) {
        const size_t j = size_t(std::lround(t * double(C.size() - 1)));
        return GuideFrame{C[j], F[j].b, F[j].n};
    };
    const WeaveReading w = read_weave(out, 0, 3, frame);
    EXPECT_EQ(w.max_run, 1);
    for (int i = 0; i < 3; ++i) EXPECT_GE(w.sequence[i].size(), 20u) << w.sequence[i];
    for (const Crossing& c : inner(w, 0.02, 0.98)) EXPECT_TRUE(c.bottom_inward) << c.t;
    EXPECT_GE(min_pair_distance(out, 0, 3), 0.8 * strand_width(out));
}

// Cornrows on an exact sphere: the weave lies along the scalp normal, under-hand by default (the strand
// travelling toward the middle passes beneath, next to the scalp), every strand alternates, none is
// inside the clearance, and crossing strands touch.
TEST(BraidWeave, CornrowsOnASphereAreUnderhandPlaits)
{
    const AnalyticSphere sphere({0, 0, 0}, 10.0f);
    const CurveSet guides = sphere_arcs(3);
    BraidParams p;
    p.orient = BraidOrient::Scalp;
    p.knot_length = 1.3f;
    p.rest = true;
    p.clearance = 0.05f;
    const CurveSet out = braid(guides, p, &sphere).curves;
    const auto GP = guides.positions();
    for (int g = 0; g < 3; ++g) {
        const std::vector<float3> C = resample_by_count(GP.subspan(g * 31, 31), out.points_in(3 * g));
        const std::vector<float3> T = polyline_tangents(C);
        const auto frame = [&](double t) {
            const size_t j = size_t(std::lround(t * double(C.size() - 1)));
            const float3 up = normalize(C[j]);
            return GuideFrame{normalize(C[j]) * 10.0f, normalize(cross(T[j], up)), up};
        };
        const WeaveReading w = read_weave(out, 3 * g, 3, frame);
        SCOPED_TRACE("guide " + std::to_string(g));
        EXPECT_EQ(w.max_run, 1);
        int under = 0, total = 0;
        for (const Crossing& c : inner(w, 0.02, 0.98)) {
            under += c.bottom_inward;
            ++total;
            EXPECT_LE(c.gap, 1.35 * strand_width(out));
        }
        EXPECT_GT(total, 30);
        EXPECT_EQ(under, total);
        EXPECT_GE(min_pair_distance(out, 3 * g, 3), 0.8 * strand_width(out));
    }
    const auto P = out.positions();
    const auto W = out.find<float>(Domain::Point, attr::width);
    for (size_t q = 0; q < out.num_points(); ++q) EXPECT_GE(sphere.distance(P[q]) - 0.5f * W[q], 0.05f - 1e-4f);
}

// Seen from the scalp normal, a braid's fibers leave no see-through gap inside the braid: rasterise
// every fiber (at its width) into the (along, lateral) plane and count empty cells between the outer
// strands' centrelines.
TEST(BraidWeave, FibersLeaveNoSeeThroughGaps)
{
    for (const int n : {3, 5}) {
        BraidParams p = plait(n);
        p.width.reset();
        p.fibers = 40;
        const float length = 8.0f;
        const CurveSet strands = braid(straight_guide(length), [&] { BraidParams q = p; q.fibers = 0; return q; }()).curves;
        const CurveSet fibers = braid(straight_guide(length), p).curves;
        const double fw = fibers.find<float>(Domain::Point, attr::width)[0];
        const double cell = fw / 2.0;
        // Footprint per along-row: between the outermost strand centrelines, from the first to the last knot.
        const auto SP = strands.positions();
        const int64_t S = strands.points_in(0);
        const int cols = int(length / cell) + 1;
        std::vector<double> lo(cols, 1e30), hi(cols, -1e30);
        for (int i = 0; i < n; ++i)
            for (int64_t j = 0; j < S; ++j) {
                const float3 q = SP[strands.points_of(i).begin + j];
                const int c = std::clamp(int(q.x / cell), 0, cols - 1);
                lo[c] = std::min(lo[c], double(q.z));
                hi[c] = std::max(hi[c], double(q.z));
            }
        const double zmin = -3.0, zmax = 3.0;
        const int rows = int((zmax - zmin) / cell) + 1;
        std::vector<uint8_t> covered(size_t(rows) * cols, 0);
        const auto FP = fibers.positions();
        for (size_t f = 0; f < fibers.num_curves(); ++f) {
            const IndexRange r = fibers.points_of(f);
            for (int64_t q = r.begin; q + 1 < r.end; ++q) {
                const float3 a = FP[q], b = FP[q + 1];
                const int steps = int(std::ceil(std::hypot(b.x - a.x, b.z - a.z) / (0.25 * cell))) + 1;
                for (int k = 0; k <= steps; ++k) {
                    const double x = a.x + (b.x - a.x) * k / steps, z = a.z + (b.z - a.z) * k / steps;
                    // A fiber of width fw covers every cell centre within fw / 2.
                    for (int dc = -2; dc <= 2; ++dc)
                        for (int dr = -2; dr <= 2; ++dr) {
                            const int c = int(x / cell) + dc, rr = int((z - zmin) / cell) + dr;
                            if (c < 0 || c >= cols || rr < 0 || rr >= rows) continue;
                            const double cx = (c + 0.5) * cell, cz = zmin + (rr + 0.5) * cell;
                            if (std::hypot(cx - x, cz - z) <= 0.5 * fw) covered[size_t(rr) * cols + c] = 1;
                        }
                }
            }
        }
        int64_t inside = 0, empty = 0;
        const double knot = *p.knot_length;
        for (int c = 0; c < cols; ++c) {
            const double x = (c + 0.5) * cell;
            if (x < knot || x > length - knot || hi[c] < lo[c]) continue;
            for (int rr = 0; rr < rows; ++rr) {
                const double z = zmin + (rr + 0.5) * cell;
                if (z <= lo[c] || z >= hi[c]) continue;
                ++inside;
                empty += !covered[size_t(rr) * cols + c];
            }
        }
        ASSERT_GT(inside, 1000);
        EXPECT_LT(double(empty) / double(inside), 0.002) << "N = " << n << ": " << empty << " of " << inside << " cells see through";
    }
}

// The loose end: past loose_length from the tip the strands no longer cross and part into a row that
// opens by the flare; the tie: a band around the braid at t, its own curve with kind 1.
TEST(BraidWeave, LooseEndOpensAndTieWrapsTheBraid)
{
    BraidParams p = plait(3);
    p.loose_length = 2.0f;
    p.flare = 1.0f;
    p.tie = 0.75f;
    CurveSet out;
    const BraidResult res = braid(straight_guide(8.0f), p);
    out = res.curves;
    ASSERT_EQ(out.num_curves(), 4u);
    const auto kind = out.find<int32_t>(Domain::Curve, "kind");
    ASSERT_EQ(kind.size(), 4u);
    EXPECT_EQ(kind[0] + kind[1] + kind[2], 0);
    EXPECT_EQ(kind[3], 1);
    EXPECT_EQ(res.report.ties, 1);
    const WeaveReading w = read_weave(out, 0, 3, [](double t) { return straight_frame(t, 8.0); });
    for (const Crossing& c : w.crossings) EXPECT_LT(c.t, 0.75 + 1e-6) << "a crossing in the loose end";
    // At the tip the strands lie in a row, level, (1 + flare) times as far apart as the weave's slots
    // (--width A = 0.6 puts three strands' slots at -A, 0, A).
    std::vector<double> lat;
    for (int i = 0; i < 3; ++i) lat.push_back(w.strands[i].back().lateral);
    std::sort(lat.begin(), lat.end());
    const double width = strand_width(out);
    EXPECT_NEAR(lat[1] - lat[0], 2.0 * 0.6, 1e-4);
    EXPECT_NEAR(lat[2] - lat[1], 2.0 * 0.6, 1e-4);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(w.strands[i].back().up, 0.0, 1e-4);
    // The tie circles the braid where it sits: every strand point there is inside the band's loop.
    const auto P = out.positions();
    const IndexRange tie = out.points_of(3);
    double tx = 0.0, ry = 0.0, rz = 0.0;
    for (int64_t q = tie.begin; q < tie.end; ++q) {
        tx += P[q].x / tie.size();
        ry = std::max(ry, std::fabs(double(P[q].y)));
        rz = std::max(rz, std::fabs(double(P[q].z)));
    }
    EXPECT_NEAR(tx, 6.0, 0.05);  // t = 0.75 of 8
    const double band = out.find<float>(Domain::Point, attr::width)[tie.begin];
    int inside = 0;
    for (int i = 0; i < 3; ++i) {
        const IndexRange r = out.points_of(i);
        for (int64_t q = r.begin; q < r.end; ++q) {
            if (std::fabs(P[q].x - 6.0f) > 0.05f) continue;
            // The strand's surface inside the band's inner edge.
            const double hw = 0.5 * out.find<float>(Domain::Point, attr::width)[q];  // pinched at the tie
            const double ey = (std::fabs(P[q].y) + hw) / (ry - 0.5 * band), ez = (std::fabs(P[q].z) + hw) / (rz - 0.5 * band);
            EXPECT_LE(std::max(ey, ez), 1.0 + 1e-4) << "strand " << i << " outside the tie";
            ++inside;
        }
    }
    EXPECT_GT(inside, 0);
}

// A cornrow picks its hair up as it goes: with feed-in it starts narrow at the hairline and reaches
// its full width where the last fibers have joined, instead of starting at full width like a cut
// rope (a trial's pictures). Read from the fibers: the braid's lateral extent over its first 2% against
// its extent past the feed-in stretch (3 knots of 2, so from x = 6 on).
TEST(BraidWeave, FedBraidStartsNarrowAndGrowsToFullWidth)
{
    const float length = 12.0f;
    auto extents = [&](float feed_in) {
        BraidParams p = plait(3);
        p.fibers = 100;
        p.feed_in = feed_in;
        const CurveSet out = braid(straight_guide(length), p).curves;
        double root = 0.0, full = 0.0;
        for (const float3& q : out.positions()) {
            if (q.x <= 0.02f * length) root = std::max(root, double(std::fabs(q.z)));
            if (q.x >= 7.0f && q.x <= 11.0f) full = std::max(full, double(std::fabs(q.z)));
        }
        return std::pair{root, full};
    };
    const auto [root, full] = extents(0.84f);
    // Closed form: the section scales by sqrt(1 - 0.84) = 0.4 at the root; fibers joining there start
    // just beside it (1.1 half widths), and each keeps its full width.
    EXPECT_GT(full, 0.5);
    EXPECT_GT(root / full, 0.3);
    EXPECT_LT(root / full, 0.55) << "root " << root << " full " << full;
    // Without feed-in every fiber starts at the root and the braid is full width there.
    const auto [blunt_root, blunt_full] = extents(0.0f);
    EXPECT_GT(blunt_root / blunt_full, 0.85);
}

// Flyaways leave their strand in a loop (the requested fraction of fibers, by id); feed-in fibers join
// along the braid from beside it, so the braid holds fewer fibers near the root.
TEST(BraidWeave, FlyawaysAndFeedIn)
{
    BraidParams p = plait(3);
    p.fibers = 200;
    p.flyaways = 0.1f;
    p.feed_in = 0.4f;
    const BraidResult res = braid(straight_guide(8.0f), p);
    const CurveSet& out = res.curves;
    BraidParams q = p;
    q.fibers = 0;
    q.flyaways = q.feed_in = 0.0f;
    const CurveSet strands = braid(straight_guide(8.0f), q).curves;
    const double width = strand_width(strands);
    const auto P = out.positions();
    const auto SP = strands.positions();
    int loops = 0, late = 0, beside = 0;
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const IndexRange r = out.points_of(c), s = strands.points_of(c / 200);
        const int64_t j0 = s.size() - r.size();
        double far = 0.0;
        for (int64_t j = 0; j < r.size(); ++j) far = std::max(far, double(length(P[r.begin + j] - SP[s.begin + j0 + j])));
        if (j0 == 0 && far > 1.2 * width) ++loops;
        if (j0 > 0) {
            ++late;
            // Its root lies outside the braid's footprint, across and below.
            const float3 root = P[r.begin];
            beside += std::fabs(root.z) > 0.9 * (strand_width(strands) * 1.5) && root.y < 0.0f;
        }
    }
    EXPECT_NEAR(double(loops) / 600.0, 0.1 * 0.6, 0.03);  // flyaways among the fibers that start at the root
    EXPECT_NEAR(double(late) / 600.0, 0.4, 0.06);
    EXPECT_EQ(res.report.fed_in, late);
    EXPECT_GT(beside, late * 9 / 10);
}
