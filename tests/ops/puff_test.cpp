#include "ops/puff.h"

#include "fields/scalp_field.h"
#include "kernel/curve_set_edit.h"
#include "kernel/error.h"
#include "kernel/io/mesh_io.h"
#include "kernel/parallel.h"
#include "test_support.h"
#include "ops/hair_types.h"
#include "ops/sphere_cap_sampler.h"

#include <gtest/gtest.h>

#include <array>

#include <cmath>
#include <cstdio>
#include <cstring>

using namespace groom;

namespace {

const float3 kHeadC(0, 0, 0);
constexpr float kHeadR = 10.0f;

/// A puff on top of the test head: region around the pole, sphere above it.
PuffParams top_puff()
{
    PuffParams p;
    p.center = float3(0, 12, 0);  // projects onto the pole (0, 10, 0)
    p.radius = 3.0f;
    p.sphere_center = float3(0, 15, 0);
    p.sphere_radius = 6.0f;
    p.rows = 6;
    p.cols = 7;
    return p;
}

/// The same puff tilted 50 degrees towards +X, so the grid sits on a slope of the head.
PuffParams side_puff()
{
    PuffParams p = top_puff();
    const float a = 50.0f * 3.14159265f / 180.0f;
    const float3 dir(std::sin(a), std::cos(a), 0.0f);
    p.center = dir * 12.0f;
    p.sphere_center = dir * 15.0f + float3(0, 0, 1.0f);  // and a little off the region's axis
    return p;
}

std::span<const float3> curve(const CurveSet& cs, size_t c)
{
    const IndexRange r = cs.points_of(c);
    return cs.positions().subspan(r.begin, r.size());
}

}  // namespace

class PuffGuides : public ::testing::TestWithParam<int> {
protected:
    PuffParams params() const { return GetParam() == 0 ? top_puff() : side_puff(); }
};

TEST_P(PuffGuides, TipsLieOnTheSphere)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = params();
    const CurveSet g = puff_guides(head, p);
    ASSERT_EQ(g.num_curves(), size_t(p.rows * p.cols));
    for (size_t c = 0; c < g.num_curves(); ++c) {
        const auto pts = curve(g, c);
        ASSERT_EQ(pts.size(), size_t(p.guide_points));
        EXPECT_LT(std::fabs(distance(pts.back(), p.sphere_center) - p.sphere_radius), 1e-4f * p.sphere_radius) << c;
        // The guide arrives along the sphere's outward normal on the top of the cap (the clean
        // silhouette), and toward the rim from the base's side, never from outside the ball.
        const float3 last = normalize(pts.back() - pts[pts.size() - 2]);
        const float3 normal = normalize(pts.back() - p.sphere_center);
        const float height = dot(normal, normalize(p.sphere_center - normalize(p.center) * kHeadR));
        if (height > 0.8f) EXPECT_GT(dot(last, normal), 0.95f) << c << " at height " << height;
        EXPECT_GT(dot(last, normal), 0.0f) << c;
    }
}

TEST_P(PuffGuides, RootsOnTheScalpInsideTheRegionLeavingAlongTheNormal)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = params();
    const CurveSet g = puff_guides(head, p);
    const float3 c0 = normalize(p.center) * kHeadR;  // the centre's projection onto the head
    float farthest = 0;
    for (size_t c = 0; c < g.num_curves(); ++c) {
        const auto pts = curve(g, c);
        EXPECT_LT(std::fabs(head.distance(pts[0])), 1e-5f * kHeadR) << c;
        EXPECT_LE(distance(pts[0], c0), p.radius) << c;
        farthest = std::max(farthest, distance(pts[0], c0));
        const float3 first = normalize(pts[1] - pts[0]);
        EXPECT_GT(dot(first, normalize(pts[0])), 0.98f) << c;
        for (const float3& q : pts) EXPECT_GE(head.distance(q), -1e-5f * kHeadR);
    }
    // The grid spreads over the region: its outer cells reach most of the way to the rim.
    EXPECT_GT(farthest, 0.7f * p.radius);
}

TEST_P(PuffGuides, GuidesDoNotCross)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = params();
    const CurveSet g = puff_guides(head, p);
    // Adjacent roots are about 2 r / 7 apart; no two guides come within a small fraction of it.
    EXPECT_GT(min_curve_separation(g), 0.02 * p.radius);
}

TEST_P(PuffGuides, TipsCoverTheCapEvenly)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = params();
    p.rows = p.cols = 8;
    const CurveSet g = puff_guides(head, p);
    const float3 c0 = normalize(p.center) * kHeadR;
    const float3 axis = normalize(p.sphere_center - c0);
    std::vector<float3> dirs;
    for (size_t c = 0; c < g.num_curves(); ++c) dirs.push_back(normalize(curve(g, c).back() - p.sphere_center));
    float widest = 0;
    float3 mean;
    for (const float3& d : dirs) {
        const float angle = std::acos(std::clamp(dot(d, axis), -1.0f, 1.0f)) * 180.0f / 3.14159265f;
        EXPECT_LE(angle, p.cap_angle);
        widest = std::max(widest, angle);
        mean += d;
    }
    // The outer ring of cells sits at 7/8 of the disc radius: cos(theta) = 1 - (7/8)^2 (1 - cos cap).
    const float outer = std::acos(1.0f - 49.0f / 64.0f * (1.0f - std::cos(p.cap_angle * 3.14159265f / 180.0f)));
    EXPECT_NEAR(widest * 3.14159265f / 180.0f, outer, 1e-3f);
    // Symmetric about the axis.
    EXPECT_GT(dot(normalize(mean), axis), 0.999f);
    // Even: nearest-neighbour angular spacings within a factor of 3 of each other.
    float lo = INFINITY, hi = 0;
    for (size_t i = 0; i < dirs.size(); ++i) {
        float nearest = INFINITY;
        for (size_t j = 0; j < dirs.size(); ++j)
            if (i != j) nearest = std::min(nearest, std::acos(std::clamp(dot(dirs[i], dirs[j]), -1.0f, 1.0f)));
        lo = std::min(lo, nearest);
        hi = std::max(hi, nearest);
    }
    EXPECT_LT(hi / lo, 3.0f) << lo << " " << hi;
}

INSTANTIATE_TEST_SUITE_P(TopAndSide, PuffGuides, ::testing::Values(0, 1));

TEST(Puff, MinCurveSeparationClosedForm)
{
    // Two parallel unit segments 0.5 apart, then a third crossing the first.
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{3, 2});
    auto P = cs.positions_for_write();
    P[0] = float3(0, 0, 0), P[1] = float3(0.5f, 0, 0), P[2] = float3(1, 0, 0);
    P[3] = float3(0, 0.5f, 0), P[4] = float3(1, 0.5f, 0);
    EXPECT_NEAR(min_curve_separation(cs), 0.5, 1e-7);
    P[3] = float3(0.7f, 0.5f, 0.3f), P[4] = float3(0.7f, -0.5f, 0.3f);  // skew: passes 0.3 over the first
    EXPECT_NEAR(min_curve_separation(cs), 0.3, 1e-6);
    P[3] = float3(0.7f, 0.5f, 0), P[4] = float3(0.7f, -0.5f, 0);  // crossing
    EXPECT_NEAR(min_curve_separation(cs), 0.0, 1e-7);
}

TEST(Puff, SingleGuideGoesStraightToTheTop)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = top_puff();
    p.rows = p.cols = 1;
    const CurveSet g = puff_guides(head, p);
    ASSERT_EQ(g.num_curves(), 1u);
    for (const float3& q : curve(g, 0)) {
        EXPECT_NEAR(q.x, 0.0f, 1e-5f);
        EXPECT_NEAR(q.z, 0.0f, 1e-5f);
    }
    EXPECT_NEAR(curve(g, 0)[0].y, 10.0f, 1e-5f);
    EXPECT_NEAR(curve(g, 0).back().y, 21.0f, 1e-5f);
}

// A puff is a ball sitting on its base, not a cupcake: with the guides leaving the scalp straight
// along its normal for 40% of their way (the old default bend), the hair rose as a column as wide as
// the base and fanned out only higher up, a smooth stalk under a ledge (a trial's pictures). Read
// from the guides, as the silhouette: how far out from the axis they reach at heights a quarter and
// half of the way from the base to the cap's lowest tips, against the straight fan (each guide's chord
// from root to tip) at the same heights.
TEST(Puff, GuidesFanOutFromTheBaseWithoutAStalk)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = top_puff();  // base radius 3 at the pole (y = 10), sphere (0, 15, 0) radius 6, cap 110 degrees
    const CurveSet g = puff_guides(head, p);
    const double rim_y = 15.0 + 6.0 * std::cos(110.0 * 3.14159265358979 / 180.0);
    // Radius from the axis where the polyline crosses height y, the largest over the guides.
    auto reach_at = [&](double y, bool chord) {
        double reach = 0.0;
        for (size_t c = 0; c < g.num_curves(); ++c) {
            const auto all = curve(g, c);
            const std::vector<float3> pts = chord ? std::vector<float3>{all.front(), all.back()} : std::vector<float3>(all.begin(), all.end());
            for (size_t i = 1; i < pts.size(); ++i) {
                if ((pts[i - 1].y - y) * (pts[i].y - y) > 0.0) continue;
                const double t = pts[i].y != pts[i - 1].y ? (y - pts[i - 1].y) / double(pts[i].y - pts[i - 1].y) : 0.0;
                const float3 q = lerp(pts[i - 1], pts[i], float(t));
                reach = std::max(reach, std::sqrt(double(q.x) * q.x + double(q.z) * q.z));
            }
        }
        return reach;
    };
    for (const double f : {0.25, 0.5}) {
        const double y = 10.0 + f * (rim_y - 10.0);
        const double reach = reach_at(y, false), fan = reach_at(y, true);
        EXPECT_GT(reach, 0.88 * fan) << "a stalk: at " << f << " of the way up the guides reach " << reach << ", their chords " << fan;
    }
}

TEST(Puff, GuideAttributes)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = top_puff();
    p.first_id = 40;
    const CurveSet g = puff_guides(head, p);
    const auto id = g.find<int64_t>(Domain::Curve, attr::id);
    const auto kind = g.find<int32_t>(Domain::Curve, "kind");
    const auto guide = g.find<int32_t>(Domain::Curve, "guide");
    ASSERT_EQ(id.size(), g.num_curves());
    ASSERT_EQ(kind.size(), g.num_curves());
    ASSERT_EQ(guide.size(), g.num_curves());
    for (size_t c = 0; c < g.num_curves(); ++c) {
        EXPECT_EQ(id[c], 40 + int64_t(c));
        EXPECT_EQ(kind[c], 0);
        EXPECT_EQ(guide[c], int32_t(c));
    }
    EXPECT_NO_THROW(g.validate());
}

TEST(Puff, GuidesDeterministicAcrossThreadCounts)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    auto run = [&](int threads) {
        ThreadLimit limit(threads);
        return puff_guides(head, side_puff());
    };
    const CurveSet a = run(1), b = run(2);
    ASSERT_EQ(a.num_points(), b.num_points());
    EXPECT_EQ(std::memcmp(a.positions().data(), b.positions().data(), a.positions().size_bytes()), 0);
}

TEST(Puff, TipInsideTheHeadIsRefused)
{
    // A sphere sunk into the head: tips near the cap's rim would be inside the scalp.
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = top_puff();
    p.sphere_center = float3(0, 10.5f, 0);
    p.sphere_radius = 4.0f;
    p.cap_angle = 150.0f;
    try {
        puff_guides(head, p);
        FAIL() << "expected InvalidParam";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`cap_angle`"), std::string::npos) << e.what();
    }
    p.cap_angle = 60.0f;  // the top of the same sphere is clear of the head
    EXPECT_NO_THROW(puff_guides(head, p));
    // A sphere centred under the scalp has no outward cap.
    p.sphere_center = float3(0, 9, 0);
    try {
        puff_guides(head, p);
        FAIL() << "expected InvalidParam";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`sphere_center`"), std::string::npos) << e.what();
    }
}

// The region is centred where `center` lands on the scalp; a centre far off the scalp (a trial's
// was 125 units off Sintel's head, and the puff was refused as "two guides touch") is refused as
// what it is, naming the centre and where it would land. Twice the region's radius off is the limit.
TEST(Puff, ACentreFarOffTheScalpIsRefusedAsSuch)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = top_puff();
    p.center = kHeadC + float3(0, kHeadR + 1.9f * p.radius, 0);  // off, but within twice the radius: on the pole
    EXPECT_NO_THROW(puff_guides(head, p));
    p.center = kHeadC + float3(0, kHeadR + 2.1f * p.radius, 0);
    try {
        puff_guides(head, p);
        FAIL() << "expected InvalidParam";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("from the scalp, more than twice the region's `radius`"), std::string::npos) << e.what();
    }
}

TEST(Puff, RejectsInvalidParams)
{
    auto message = [](const PuffParams& p) {
        try {
            p.validate();
        }
        catch (const InvalidParam& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_EQ(message(top_puff()), "(accepted)");
    PuffParams p = top_puff();
    p.radius = 0;
    EXPECT_NE(message(p).find("`radius` must be a finite number > 0 (got 0)"), std::string::npos) << message(p);
    p = top_puff();
    p.sphere_radius = -1;
    EXPECT_NE(message(p).find("`sphere_radius`"), std::string::npos) << message(p);
    p = top_puff();
    p.sphere_center.x = NAN;
    EXPECT_NE(message(p).find("`sphere_center`"), std::string::npos) << message(p);
    p = top_puff();
    p.center.y = INFINITY;
    EXPECT_NE(message(p).find("`center`"), std::string::npos) << message(p);
    p = top_puff();
    p.rows = 0;
    EXPECT_NE(message(p).find("`rows` must be in 1..256 (got 0)"), std::string::npos) << message(p);
    p = top_puff();
    p.cols = 300;
    EXPECT_NE(message(p).find("`cols` must be in 1..256 (got 300)"), std::string::npos) << message(p);
    p = top_puff();
    p.cap_angle = 180;
    EXPECT_NE(message(p).find("`cap_angle`"), std::string::npos) << message(p);
    p = top_puff();
    p.guide_points = 3;
    EXPECT_NE(message(p).find("`guide_points` must be in [4, 4096] (got 3)"), std::string::npos) << message(p);
    p.guide_points = 100000000;  // ran past the memory before anything said no
    EXPECT_NE(message(p).find("`guide_points` must be in [4, 4096] (got 100000000)"), std::string::npos) << message(p);
    p = top_puff();
    p.bend = 0;
    EXPECT_NE(message(p).find("`bend`"), std::string::npos) << message(p);
    p = top_puff();
    p.first_id = -1;
    EXPECT_NE(message(p).find("`first_id`"), std::string::npos) << message(p);
}

namespace {

PuffParams hairy(PuffParams p, int64_t hairs)
{
    p.hairs = hairs;
    p.curl.amplitude = {0.15f, 0.3f};
    p.curl.frequency = {1.0f, 1.5f};
    p.curl.offset = {0.0f, 0.05f};
    p.curl.seed = 3;
    return p;
}

}  // namespace

TEST(Puff, CurlReachClosedForm)
{
    CurlParams c;
    c.amplitude = {0.1f, 0.3f};
    c.offset = {0.0f, 0.05f};
    c.shape.lame_exponent = 2.5f;
    EXPECT_NEAR(curl_reach(c), 0.3f * std::pow(2.0f, 0.1f) + 0.05f, 1e-6f);
    c.shape.lame_exponent = 1.5f;
    EXPECT_NEAR(curl_reach(c), 0.35f, 1e-6f);
    // Unset amplitude: the hair type's radius, +20%.
    c.amplitude = {0, 0};
    c.units_per_cm = 2.0f;
    c.offset = {};
    const HairTypePreset* t = find_hair_type(c.hair_type);
    ASSERT_NE(t, nullptr);
    EXPECT_NEAR(curl_reach(c), t->radius_cm * 2.0f * 1.2f, 1e-6f);
}

class PuffHairs : public ::testing::TestWithParam<int> {
protected:
    PuffParams params(int64_t hairs) const { return hairy(GetParam() == 0 ? top_puff() : side_puff(), hairs); }
};

TEST_P(PuffHairs, RootsAreaUniformInsideTheRegionAndOnTheScalp)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = params(8000);
    p.curl.frequency = {0.3f, 0.4f};  // few cycles: this test is about the roots
    const PuffResult r = puff(head, test::sphere_cap_sampler(kHeadC, kHeadR), p);
    ASSERT_EQ(r.hairs.num_curves(), 8000u);
    const float3 c0 = normalize(p.center) * kHeadR;
    const float3 axis = normalize(c0);
    const float3 e1 = any_perpendicular(axis), e2 = cross(axis, e1);
    // The region ball cuts the cap cos(theta) >= 1 - r^2 / (2 R^2) around c0.
    const double cos_max = 1.0 - double(p.radius * p.radius) / (2.0 * kHeadR * kHeadR);
    std::vector<int> band(10, 0), sector(8, 0);
    for (size_t c = 0; c < r.hairs.num_curves(); ++c) {
        const float3 root = curve(r.hairs, c)[0];
        ASSERT_LT(std::fabs(head.distance(root)), 1e-5f * kHeadR);
        ASSERT_LE(distance(root, c0), p.radius * (1 + 1e-6f));
        const float3 d = normalize(root);
        band[std::min(9, int((1.0 - dot(d, axis)) / (1.0 - cos_max) * 10.0))]++;
        const double phi = std::atan2(double(dot(d, e2)), double(dot(d, e1))) + 3.141592653589793;
        sector[std::min(7, int(phi / 6.283185307179586 * 8.0))]++;
    }
    double bands = 0, sectors = 0;
    for (int b : band) bands += (b - 800.0) * (b - 800.0) / 800.0;
    for (int s : sector) sectors += (s - 1000.0) * (s - 1000.0) / 1000.0;
    EXPECT_LT(bands, 27.88);   // chi-square, 9 degrees of freedom, p = 0.001
    EXPECT_LT(sectors, 24.32); // 7 degrees of freedom
}

TEST_P(PuffHairs, SilhouetteNothingInsideAndDirectionsFollowGuides)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = params(1500);
    const PuffResult r = puff(head, test::sphere_cap_sampler(kHeadC, kHeadR), p);
    const float reach = curl_reach(p.curl);
    const auto near = r.hairs.find<int32_t>(Domain::Curve, "guide");
    ASSERT_EQ(near.size(), r.hairs.num_curves());

    // The widest angular gap between neighbouring guide tips.
    const size_t ng = r.guides.num_curves();
    std::vector<float3> gdir(ng);
    for (size_t g = 0; g < ng; ++g) gdir[g] = normalize(curve(r.guides, g).back() - p.sphere_center);
    float spacing = 0;
    for (size_t g = 0; g < ng; ++g) {
        float nearest = INFINITY;
        for (size_t h = 0; h < ng; ++h)
            if (h != g) nearest = std::min(nearest, std::acos(std::clamp(dot(gdir[g], gdir[h]), -1.0f, 1.0f)));
        spacing = std::max(spacing, nearest);
    }

    float worst_tip = 0;
    for (size_t c = 0; c < r.hairs.num_curves(); ++c) {
        const auto pts = curve(r.hairs, c);
        for (const float3& q : pts) ASSERT_GE(head.distance(q), -1e-5f * kHeadR) << "hair " << c;
        const float off = std::fabs(distance(pts.back(), p.sphere_center) - p.sphere_radius);
        worst_tip = std::max(worst_tip, off);
        // The nearest guide really is the nearest (by root), and the hair points where it points.
        const float3 root = pts[0];
        for (size_t g = 0; g < ng; ++g) ASSERT_LE(distance(root, curve(r.guides, near[c])[0]), distance(root, curve(r.guides, g)[0]));
        const float3 tipdir = normalize(pts.back() - p.sphere_center);
        EXPECT_LT(std::acos(std::clamp(dot(tipdir, gdir[near[c]]), -1.0f, 1.0f)), 2.0f * spacing) << "hair " << c;
        const auto gp = curve(r.guides, near[c]);
        EXPECT_GT(dot(normalize(pts.back() - pts[0]), normalize(gp.back() - gp[0])), 0.85f) << "hair " << c;
    }
    EXPECT_LE(worst_tip, reach + 1e-4f * p.sphere_radius);
    EXPECT_GT(worst_tip, 0.0f);  // the curls do move the tips: the bound is not trivially met
}

// Tips as a person sees the ball: covered from the top down to the cap's rim, as evenly as the roots
// cover the base. Blending the guides alone never reached past their outermost ring (5/6 of the disc
// for the 6 x 7 grid, u = 0.69 below), so every hair rooted outside it ended on that one circle: a
// sharp edge around the ball, with bare sphere under it. Read as the tips' equal-area coordinate
// u = (1 - cos theta) / (1 - cos cap) around the cap's axis, uniform over the cap's area.
TEST_P(PuffHairs, TipsCoverTheCapToItsRim)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = params(4000);
    const PuffResult r = puff(head, test::sphere_cap_sampler(kHeadC, kHeadR), p);
    const float3 c0 = normalize(p.center) * kHeadR;
    const float3 axis = normalize(p.sphere_center - c0);
    const double one_minus_cos_cap = 1.0 - std::cos(double(p.cap_angle) * 3.141592653589793 / 180.0);
    std::vector<int> fifth(5, 0);
    for (size_t c = 0; c < r.hairs.num_curves(); ++c) {
        const float3 d = normalize(curve(r.hairs, c).back() - p.sphere_center);
        const double u = (1.0 - double(dot(d, axis))) / one_minus_cos_cap;
        fifth[size_t(std::clamp(int(u * 5.0), 0, 4))]++;
    }
    // Each fifth of the cap's area holds a fifth of the tips (800), within 25% (the curls move tips
    // by up to their reach, 0.35 on a sphere of radius 6, about 3 degrees).
    for (int k = 0; k < 5; ++k) {
        EXPECT_GE(fifth[size_t(k)], 600) << "fifth " << k << " of the cap (by area) holds " << fifth[size_t(k)] << " of 4000 tips";
        EXPECT_LE(fifth[size_t(k)], 1000) << "fifth " << k << " of the cap (by area) holds " << fifth[size_t(k)] << " of 4000 tips";
    }
}

// A hair's tip on the cap depends on where it follows the guides and on the direction they give it,
// not on the disc axes PuffCap picked: `groom transform` may rotate a puff's file, and `groom
// gather` then rebuilds the cap from the rotated scalp, whose axes any_perpendicular picks anew.
TEST(Puff, CapTipDoesNotDependOnTheDiscAxes)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = side_puff();  // its axis leans off the normal, where the choice of axes shows
    const float3 base = normalize(p.center) * kHeadR;
    const PuffCap a = PuffCap::make(head, base, p.radius, p.sphere_center, p.sphere_radius, p.cap_angle);
    PuffCap b = a;
    const float turn = 0.6f;  // the disc's axes turned by 0.6 radians about the normal, the cap's made as make() does
    b.u = a.u * std::cos(turn) + a.v * std::sin(turn);
    b.v = a.v * std::cos(turn) - a.u * std::sin(turn);
    b.ut = normalize(b.u - b.axis * dot(b.u, b.axis));
    b.vt = cross(b.axis, b.ut);
    for (const std::array<float, 2> o : {std::array<float, 2>{1.0f, 0.5f}, {-2.0f, 1.5f}, {0.3f, -2.9f}}) {
        const float3 x = base + a.u * o[0] + a.v * o[1];
        const float3 blended = p.sphere_center + normalize(a.axis * 0.4f + a.ut * o[0] + a.vt * o[1]) * p.sphere_radius;
        const float3 ta = a.tip_for(x, blended), tb = b.tip_for(x, blended);
        EXPECT_LT(distance(ta, tb), 1e-5f * p.sphere_radius) << ta.x << "," << ta.y << "," << ta.z << " against " << tb.x << "," << tb.y << "," << tb.z;
        // On the sphere, at the equal-area polar angle of x's distance from the base's centre.
        EXPECT_NEAR(distance(ta, p.sphere_center), p.sphere_radius, 1e-5f * p.sphere_radius);
        const double rho = std::min(1.0, std::hypot(double(o[0]), double(o[1])) / double(p.radius));
        const double cos_t = 1.0 - rho * rho * (1.0 - std::cos(double(p.cap_angle) * 3.141592653589793 / 180.0));
        EXPECT_NEAR(dot(normalize(ta - p.sphere_center), a.axis), cos_t, 1e-5);
        // The azimuth the blended tip gives.
        const float3 side = blended - p.sphere_center - a.axis * dot(blended - p.sphere_center, a.axis);
        const float3 tside = ta - p.sphere_center - a.axis * dot(ta - p.sphere_center, a.axis);
        EXPECT_GT(dot(normalize(side), normalize(tside)), 1.0f - 1e-5f);
    }
}

TEST_P(PuffHairs, AttributesAndIds)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = params(200);
    p.first_id = 10;
    const PuffResult r = puff(head, test::sphere_cap_sampler(kHeadC, kHeadR), p);
    const CurveSet all = join(r.guides, r.hairs);
    const size_t ng = r.guides.num_curves();
    ASSERT_EQ(all.num_curves(), ng + 200);
    const auto id = all.find<int64_t>(Domain::Curve, attr::id);
    const auto kind = all.find<int32_t>(Domain::Curve, "kind");
    ASSERT_EQ(id.size(), all.num_curves());
    ASSERT_EQ(kind.size(), all.num_curves());
    for (size_t c = 0; c < all.num_curves(); ++c) {
        EXPECT_EQ(id[c], 10 + int64_t(c));
        EXPECT_EQ(kind[c], c < ng ? 0 : 1);
    }
    EXPECT_FALSE(all.find<int32_t>(Domain::Point, "shape").empty());
    EXPECT_NO_THROW(all.validate());
}

TEST_P(PuffHairs, DeterministicAcrossThreadCounts)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    const PuffParams p = params(1000);
    auto run = [&](int threads) {
        ThreadLimit limit(threads);
        return puff(head, test::sphere_cap_sampler(kHeadC, kHeadR), p).hairs;
    };
    const CurveSet a = run(1), b = run(2);
    ASSERT_EQ(a.num_points(), b.num_points());
    EXPECT_EQ(std::memcmp(a.positions().data(), b.positions().data(), a.positions().size_bytes()), 0);
}

INSTANTIATE_TEST_SUITE_P(TopAndSide, PuffHairs, ::testing::Values(0, 1));

TEST(Puff, RejectsInvalidHairParams)
{
    const AnalyticSphere head(kHeadC, kHeadR);
    PuffParams p = hairy(top_puff(), -1);
    EXPECT_THROW(p.validate(), InvalidParam);
    p = hairy(top_puff(), 10);
    p.hair_points = 3;
    EXPECT_THROW(p.validate(), InvalidParam);
    p = hairy(top_puff(), 10);
    p.neighbours = 0;
    EXPECT_THROW(p.validate(), InvalidParam);
    p = hairy(top_puff(), 10);
    p.power = 0;
    EXPECT_THROW(p.validate(), InvalidParam);
    // Curl options are checked as `groom curl` checks them.
    p = hairy(top_puff(), 10);
    p.curl.uniformity = 2.0f;
    try {
        puff(head, test::sphere_cap_sampler(kHeadC, kHeadR), p);
        FAIL() << "expected InvalidParam";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`uniformity`"), std::string::npos) << e.what();
    }
}

TEST(Puff, RealHeadSilhouetteAndNothingInside)
{
    GROOM_REQUIRE_SHARED(path, "lee_perry_smith/LeePerrySmith.obj");
    const PolygonSoup soup = read_mesh(path);
    const ScalpField scalp = build_scalp(soup);
    Bounds3 box;
    for (const float3& p : soup.points) box.extend(p);
    const float3 size = box.size();
    PuffParams p;
    const float3 c0 = scalp.closest_point(float3(box.center().x - 0.22f * size.x, box.hi.y + 0.2f * size.y, box.center().z - 0.1f * size.z));
    p.center = c0;
    p.radius = 0.12f * size.x;
    p.sphere_radius = 0.25f * size.x;
    p.sphere_center = c0 + scalp.normal(c0) * (0.75f * p.sphere_radius);
    p.cap_angle = 100.0f;
    p.hairs = 2000;
    p.curl.hair_type = "4a";
    p.curl.units_per_cm = size.x / 16.0f;
    const PuffResult r = puff(scalp, scalp_root_sampler(scalp), p);
    // The guides cannot cross (puff_guides would have refused) and end on the sphere.
    EXPECT_GT(min_curve_separation(r.guides), 0.0);
    for (size_t c = 0; c < r.guides.num_curves(); ++c) {
        EXPECT_LT(std::fabs(distance(curve(r.guides, c).back(), p.sphere_center) - p.sphere_radius), 1e-4f * p.sphere_radius);
        EXPECT_LE(distance(curve(r.guides, c)[0], c0), p.radius);
    }
    // The level set's own accuracy: a small fraction of a voxel.
    const float tol = 0.05f * scalp.voxel_size();
    const float reach = curl_reach(p.curl);
    for (size_t c = 0; c < r.hairs.num_curves(); ++c) {
        const auto pts = curve(r.hairs, c);
        EXPECT_LE(distance(pts[0], c0), p.radius * (1 + 1e-5f));
        for (size_t i = 1; i < pts.size(); ++i) ASSERT_GE(scalp.distance(pts[i]), -tol) << "hair " << c << " point " << i;
        EXPECT_LE(std::fabs(distance(pts.back(), p.sphere_center) - p.sphere_radius), reach + 1e-4f * p.sphere_radius) << c;
    }
}
