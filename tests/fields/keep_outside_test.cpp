// keep_outside against exact surfaces, where the rule has a closed form: a point inside the unit
// sphere ends at radius + clearance (+ margin) along its own radial line, a clear point is not
// touched, curves keep their roots, and a group lifts by exactly the missing distance off a plane.
#include "fields/keep_outside.h"
#include "fields/scalp_field.h"
#include "support/sphere_mesh.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <vector>

namespace groom {
namespace {

bool same_bits(const float3& a, const float3& b) { return std::memcmp(&a, &b, sizeof(float3)) == 0; }

/// Float rounding of a move on a unit-sized scene: a few ulps of 1.
constexpr float kTol = 4e-7f;

TEST(KeepOutside, PointInsideEndsAtRadiusPlusClearanceOnItsRadialLine)
{
    const AnalyticSphere sphere({1, 2, 3}, 1.0f);
    const KeepOutside rule{0.25f};
    for (const float3 dir : {float3(1, 0, 0), normalize(float3(1, -2, 0.5f)), normalize(float3(-0.3f, 0.1f, -1))}) {
        // On the surface, inside, near the centre, and outside but within the clearance.
        for (const float r : {1.0f, 0.8f, 0.1f, 1.1f}) {
            float3 p = sphere.center() + dir * r;
            ASSERT_TRUE(keep_outside(p, sphere, rule)) << r;
            // Coordinates up to 4: a few of their ulps.
            EXPECT_NEAR(distance(p, sphere.center()), 1.25f, 2e-6f) << r;
            EXPECT_NEAR(dot(normalize(p - sphere.center()), dir), 1.0f, 2e-6f) << r;
        }
    }
}

TEST(KeepOutside, ClearPointsAreNotTouched)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    // 1.25 out (exactly clear), 3, 1.28.
    for (const float3 q : {float3(1.25f, 0, 0), float3(0, 3, 0), float3(0.6f, 0.8f, 0.8f)}) {
        float3 p = q;
        EXPECT_FALSE(keep_outside(p, sphere, KeepOutside{0.25f}));
        EXPECT_TRUE(same_bits(p, q));
    }
}

TEST(KeepOutside, ExtraAndMarginAddToTheClearance)
{
    const AnalyticSphere sphere({0, 0, 0}, 2.0f);
    float3 p(0, 1, 0);
    ASSERT_TRUE(keep_outside(p, sphere, KeepOutside{0.5f, 0.01f}, 0.25f));
    EXPECT_NEAR(p.y, 2.0f + 0.5f + 0.25f + 0.01f, kTol);
    EXPECT_NEAR(p.x, 0.0f, kTol);
}

/// The exact sphere, except that its projection falls `shortfall` short of the surface: a field that
/// disagrees with itself, as a level set does by its interpolation error.
class ShallowSphere final : public Surface {
public:
    explicit ShallowSphere(float shortfall) : shortfall_(shortfall) {}
    float distance(const float3& p) const override { return exact_.distance(p); }
    float3 normal(const float3& p) const override { return exact_.normal(p); }
    float3 closest_point(const float3& p) const override { return exact_.normal(p) * (1.0f - shortfall_); }

private:
    AnalyticSphere exact_{{0, 0, 0}, 1.0f};
    float shortfall_;
};

TEST(KeepOutside, RetriesDoubleTheMarginUntilTheFieldAgrees)
{
    const ShallowSphere field(0.01f);
    // Margins 0.004, 0.008, 0.016: the third move lands 0.016 - 0.01 = 0.006 out.
    float3 p(0, 0.5f, 0);
    keep_outside(p, field, KeepOutside{0.0f, 0.004f, 8});
    EXPECT_NEAR(p.y, 1.006f, kTol);
    // Two moves are not enough, and the rule stops where it was told to.
    float3 q(0, 0.5f, 0);
    keep_outside(q, field, KeepOutside{0.0f, 0.004f, 2});
    EXPECT_NEAR(q.y, 0.998f, kTol);
    // One move trusts the projection.
    float3 r(0, 0.5f, 0);
    keep_outside(r, field, KeepOutside{0.0f, 0.004f, 1});
    EXPECT_NEAR(r.y, 0.994f, kTol);
}

/// The exact sphere, but its move's query gives `normal_sign` times the normal and, with `pit`, the
/// centre as the closest point: a rim whose normal points into the head (an open eye hole), and a
/// field whose moves only make things worse.
class MisleadingSphere final : public Surface {
public:
    MisleadingSphere(float normal_sign, bool pit) : sign_(normal_sign), pit_(pit) {}
    float distance(const float3& p) const override { return exact_.distance(p); }
    float3 normal(const float3& p) const override { return exact_.normal(p) * sign_; }
    float3 closest_point(const float3& p) const override { return pit_ ? float3(0, 0, 0) : exact_.closest_point(p); }

private:
    AnalyticSphere exact_{{0, 0, 0}, 1.0f};
    float sign_;
    bool pit_;
};

// A move that lands deeper inside than the point started tries the other side of the closest
// point, and a move is never for the worse: where every try is worse the point stays (cull's push
// put hair beside Sintel's eye holes half a unit inside, a trial).
TEST(KeepOutside, AMoveIntoTheHeadTriesTheOtherSideAndNoneMakesThingsWorse)
{
    const MisleadingSphere rim(-1.0f, false);
    float3 p(1.01f, 0, 0);  // outside, short of the clearance 0.1
    ASSERT_TRUE(keep_outside(p, rim, KeepOutside{0.1f}));
    EXPECT_NEAR(p.x, 1.1f, kTol);
    EXPECT_NEAR(length(float3(0, p.y, p.z)), 0.0f, kTol);
    const MisleadingSphere pit(1.0f, true);  // every move lands 0.9 deep or on the far side inside
    for (const int steps : {1, 4}) {
        float3 q(0, 0.95f, 0);
        EXPECT_FALSE(keep_outside(q, pit, KeepOutside{0.1f, 0.0f, steps})) << steps;
        EXPECT_TRUE(same_bits(q, float3(0, 0.95f, 0))) << steps;
    }
}

TEST(KeepOutside, AnchorPullsBackAlongTheOffset)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    // The anchor is outside: the point comes back along the segment to the surface (24 halvings of
    // the offset), keeping its direction from the anchor.
    const float3 anchor(0, 1.5f, 0);
    float3 p(0, 0.5f, 0.5f);
    ASSERT_TRUE(keep_outside(p, sphere, KeepOutside{}, 0.0f, &anchor));
    EXPECT_GE(sphere.distance(p), 0.0f);
    EXPECT_LT(sphere.distance(p), 1e-6f);
    const float3 along = normalize(p - anchor), want = normalize(float3(0, 0.5f, 0.5f) - anchor);
    EXPECT_NEAR(dot(along, want), 1.0f, kTol);
    // The anchor is inside too: the normal move applies.
    const float3 buried(0, 0.2f, 0);
    float3 q(0, 0.5f, 0);
    ASSERT_TRUE(keep_outside(q, sphere, KeepOutside{0.1f}, 0.0f, &buried));
    EXPECT_NEAR(q.y, 1.1f, kTol);
}

TEST(KeepOutside, SpanUsesHalfWidthsAndSkipsKnownClearPoints)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    std::vector<float3> pts = {{0.5f, 0, 0}, {0, 0.5f, 0}, {0, 0, 3}, {0, 0, -0.5f}};
    const std::vector<float3> before = pts;
    const std::vector<float> widths = {0.2f, 0.0f, 0.2f, 0.2f};
    const std::vector<uint8_t> known = {0, 0, 0, 1};  // the caller vouches for the last one
    EXPECT_EQ(keep_outside(pts, sphere, KeepOutside{0.05f}, widths, known), 2);
    EXPECT_NEAR(pts[0].x, 1.15f, kTol);
    EXPECT_NEAR(pts[1].y, 1.05f, kTol);
    EXPECT_TRUE(same_bits(pts[2], before[2]));
    EXPECT_TRUE(same_bits(pts[3], before[3]));
}

/// Counts distance queries, to see which points a form asks about.
class CountingSphere final : public Surface {
public:
    float distance(const float3& p) const override
    {
        ++queries;
        return exact.distance(p);
    }
    float3 normal(const float3& p) const override { return exact.normal(p); }
    float3 closest_point(const float3& p) const override { return exact.closest_point(p); }
    float query(const float3& p, float3& n, float3& c) const override  // the move's query, not counted
    {
        n = exact.normal(p);
        c = exact.closest_point(p);
        return exact.distance(p);
    }
    AnalyticSphere exact{{0, 0, 0}, 1.0f};
    mutable std::atomic<int> queries{0};
};

TEST(KeepOutside, CurvesKeepRootsAndSkipPointsProvablyClear)
{
    CountingSphere sphere;
    // Curve 0 starts inside (its root stays) and dives; curve 1 leaves radially, far out after its
    // first point; curve 2 is a lone root.
    const int64_t counts[3] = {4, 5, 1};
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    const float3 pts[10] = {{0.9f, 0, 0}, {0.8f, 0, 0}, {0.5f, 0, 0}, {2, 0, 0},
                            {0, 1, 0},    {0, 2, 0},    {0, 2.1f, 0}, {0, 2.2f, 0}, {0, 2.3f, 0},
                            {0, 0, 0.5f}};
    std::copy(pts, pts + 10, P.begin());
    const KeepOutsideCount moved = keep_outside(cs, sphere, KeepOutside{0.1f});
    EXPECT_EQ(moved.points, 2);
    EXPECT_EQ(moved.curves, 1);
    const auto Q = cs.positions();
    EXPECT_TRUE(same_bits(Q[0], pts[0]));  // a root inside stays inside
    EXPECT_NEAR(Q[1].x, 1.1f, kTol);
    EXPECT_NEAR(Q[2].x, 1.1f, kTol);
    EXPECT_TRUE(same_bits(Q[3], pts[3]));
    for (int k = 4; k < 10; ++k) EXPECT_TRUE(same_bits(Q[k], pts[k])) << k;
    // Curve 0: its three points, and where each of the two moved ones landed (a move is checked, so
    // that it is never for the worse). Curve 1: (0,2,0) only, the rest are within 0.1 per step of
    // it and 1 out. No root is asked about.
    EXPECT_EQ(sphere.queries.load(), 3 + 2 + 1);
}

// With a margin the pull-back stops once the crossing is bracketed to a sixteenth of it: the point
// ends clear, short of the crossing (the closed form of a line meeting the sphere) by no more than
// that, and a smooth distance gets there in a few queries (regula falsi), not 24 halvings.
TEST(KeepOutside, AnchorPullBackStopsWithinASixteenthOfTheMargin)
{
    const CountingSphere sphere;
    const float margin = 1e-3f;
    for (const float3 tip : {float3(0.1f, 0.3f, 0.2f), float3(0.9f, 0.2f, -0.1f), float3(-0.05f, 0.97f, 0.0f)}) {
        const float3 anchor(0.2f, 1.4f, 0.1f);
        float3 p = tip;
        sphere.queries = 0;
        ASSERT_TRUE(keep_outside(p, sphere, KeepOutside{0.0f, margin, 4}, 0.0f, &anchor));
        EXPECT_LE(sphere.queries.load(), 2 + 10);  // the point and the anchor, then the bracket's steps
        // |anchor + t off| = 1: the crossing t* nearest the anchor, and where the point ended.
        const double ax = anchor.x, ay = anchor.y, az = anchor.z;
        const double ox = double(tip.x) - ax, oy = double(tip.y) - ay, oz = double(tip.z) - az;
        const double qa = ox * ox + oy * oy + oz * oz, qb = 2.0 * (ax * ox + ay * oy + az * oz), qc = ax * ax + ay * ay + az * az - 1.0;
        const double crossing = (-qb - std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
        const double t = std::sqrt(double(length_squared(p - anchor)) / qa), len = std::sqrt(qa);
        EXPECT_GE(sphere.distance(p), 0.0f);
        EXPECT_LE(crossing - t, margin / 16.0 / len + 1e-6) << tip.x;
        EXPECT_GE(crossing - t, -1e-6) << tip.x;
        const float3 along = normalize(p - anchor), want = normalize(tip - anchor);
        EXPECT_NEAR(dot(along, want), 1.0f, kTol);
    }
}

TEST(KeepOutside, GroupLiftsByTheMissingDistanceAndRestsWhenAsked)
{
    const AnalyticPlane floor({0, 0, 0}, {0, 1, 0});
    const KeepOutside rule{0.1f, 0.001f, 32};
    // The lowest point is 0.3 below the floor: the group must rise 0.3 + 0.1 + 0.05 (extra) + 0.001.
    const std::vector<float3> group = {{0, -0.3f, 0}, {1, 0.2f, 0}, {2, 0.0f, 1}};
    EXPECT_NEAR(lift_outside(group, {0, 1, 0}, floor, rule, 0.05f, false), 0.451, 1e-6);
    // Floating 0.5 above: left alone, or lowered to rest at the clearance.
    const std::vector<float3> high = {{0, 0.5f, 0}, {1, 0.7f, 0}};
    EXPECT_EQ(lift_outside(high, {0, 1, 0}, floor, rule, 0.05f, false), 0.0);
    EXPECT_NEAR(lift_outside(high, {0, 1, 0}, floor, rule, 0.05f, true), -(0.5 - 0.151), 1e-6);
    // On a sphere the off-centre points rise by less than the lift; the fixed point still clears all.
    const AnalyticSphere ball({0, 0, 0}, 1.0f);
    const std::vector<float3> section = {{-0.3f, 0.9f, 0}, {0, 0.95f, 0}, {0.3f, 0.9f, 0}};
    const double lift = lift_outside(section, {0, 1, 0}, ball, rule, 0.0f, false);
    float lowest = 1e30f;
    for (const float3& p : section) lowest = std::min(lowest, ball.distance(p + float3(0, float(lift), 0)));
    // The iteration approaches from below and stops once a step is within the margin: the section
    // keeps the clearance, short of the margin by less than the margin.
    EXPECT_GE(lowest, 0.1f);
    EXPECT_LE(lowest, 0.101f + 1e-6f);
}

/// The slot 0 < y < 1 between a floor and a ceiling, solid beyond both: outside the scalp only inside
/// the slot (the gap behind an ear).
class Slot final : public Surface {
public:
    float distance(const float3& p) const override { return std::min(p.y, 1.0f - p.y); }
    float3 normal(const float3& p) const override { return p.y < 0.5f ? float3(0, 1, 0) : float3(0, -1, 0); }
    float3 closest_point(const float3& p) const override { return {p.x, p.y < 0.5f ? 0.0f : 1.0f, p.z}; }
};

// A group taller than the gap it lies in has no clear place along the floor's normal: the lift used
// to march on into the ceiling and through whatever lay beyond (on a head, out of its far side, 52
// units; here the ceiling is solid for ever and the steps doubled to a lift of 10^8). It stops where
// it is clearest, says it was blocked and how short it still is, and no point goes into the ceiling.
TEST(KeepOutside, GroupTallerThanItsGapIsBlockedNotThrownThrough)
{
    const Slot slot;
    const KeepOutside rule{0.1f, 0.0f, 32};
    const std::vector<float3> group = {{0, 0.05f, 0}, {0.3f, 0.9f, 0}};
    LiftOutcome outcome;
    const double lift = lift_outside(group, {0, 1, 0}, slot, rule, 0.0f, false, &outcome);
    EXPECT_TRUE(outcome.blocked);
    EXPECT_GE(lift, 0.0);
    EXPECT_LE(lift, 0.05 + 1e-6);
    EXPECT_NEAR(outcome.worst, -0.05f, 1e-6f);
    for (const float3& p : group) EXPECT_GE(slot.distance(p + float3(0, float(lift), 0)), 0.0f);
    // Room enough: the same group a little shorter rises to rest at the clearance, not blocked.
    const std::vector<float3> shorter = {{0, 0.05f, 0}, {0.3f, 0.75f, 0}};
    EXPECT_NEAR(lift_outside(shorter, {0, 1, 0}, slot, rule, 0.0f, false, &outcome), 0.05, 1e-6);
    EXPECT_FALSE(outcome.blocked);
}

// A field whose sign jumps away from the surface is not 1-Lipschitz, and the curve form's bound
// (a point whose predecessor's distance less the segment is positive is clear) fails across the
// jump: hair that went into Sintel's eye sockets was skipped and left up to 1.5 units inside. Here
// a unit sphere open at its +Y pole (a hole of 15 degrees, an eye socket): a hair from the scalp
// reaches over the hole, 0.27 from its rim and outside, then 0.25 down through it to 0.31 inside.
// The bound said 0.27 - 0.25 > 0, clear; the point must be moved out.
TEST(KeepOutside, CurvesAreCheckedPointByPointWhereTheFieldJumps)
{
    const PolygonSoup sphere = uv_sphere({0, 0, 0}, 1.0f, 24, 48);
    PolygonSoup open;
    open.points = sphere.points;
    for (size_t f = 0; f < sphere.num_faces(); ++f) {
        float3 c;
        for (const int32_t v : sphere.face(f)) c += sphere.points[v];
        if (c.y / float(sphere.face(f).size()) < std::cos(15.0f * float(M_PI) / 180.0f)) open.add_face(sphere.face(f));
    }
    const ScalpField field = build_scalp(open, {0.02f, 3.0f});
    const ScalpField closed = build_scalp(sphere, {0.02f, 3.0f});
    EXPECT_FALSE(field.lipschitz());
    EXPECT_TRUE(closed.lipschitz());

    const int64_t counts[] = {3};
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    P[0] = float3(0.5f, std::sqrt(0.75f), 0.0f);  // the root, on the scalp 30 degrees from the pole
    P[1] = float3(0.0f, 1.05f, 0.0f);
    P[2] = float3(0.0f, 0.8f, 0.0f);
    ASSERT_GT(field.distance(P[1]), 0.25f);
    ASSERT_LT(field.distance(P[2]), -0.3f);
    const KeepOutsideCount moved = keep_outside(cs, field, KeepOutside{0.0f, 1e-5f, 4});
    EXPECT_EQ(moved.points, 1);
    EXPECT_GE(field.distance(cs.positions()[2]), 0.0f);
    EXPECT_GT(distance(cs.positions()[2], float3(0.0f, 0.8f, 0.0f)), 0.3f);
}

}  // namespace
}  // namespace groom
