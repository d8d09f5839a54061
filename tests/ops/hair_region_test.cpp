// HairRegion against closed forms on a sphere: a hairline that is a circle on the sphere (level or
// tilted) bounds exactly the cap on one side of its plane; a parting along a great circle splits the
// sphere by that circle's plane.
#include "ops/hair_region.h"

#include "circle_on_sphere.h"

#include "kernel/error.h"
#include "kernel/rng.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace groom;

namespace {

const float3 kC{0.5f, 1.0f, -0.5f};
constexpr float kR = 8.0f;
constexpr float kPi = 3.14159265358979f;

CurveSet circle_on_sphere(const float3& normal, float offset, int n, bool reverse = false)
{
    return test::circle_on_sphere(kC, kR, normal, offset, n, reverse);
}

float3 random_on_sphere(Rng& rng)
{
    const float z = 2 * rng.uniform() - 1, a = 2 * kPi * rng.uniform(), s = std::sqrt(1 - z * z);
    return kC + float3(s * std::cos(a), z, s * std::sin(a)) * kR;
}

}  // namespace

TEST(HairRegion, LevelAndTiltedCircularHairlinesBoundTheirCaps)
{
    const AnalyticSphere sphere(kC, kR);
    for (const float3 n : {float3(0, 1, 0), normalize(float3(0, 1, -0.45f)), normalize(float3(0.2f, 1, 0.3f))}) {
        for (bool reverse : {false, true}) {
            const CurveSet hairline = circle_on_sphere(n, 0.25f * kR, 720, reverse);
            const HairRegion region(sphere, hairline, CurveSet(), HairRegionParams{});
            ASSERT_TRUE(region.has_hairline());
            Rng rng(1, 2);
            int checked = 0;
            for (int i = 0; i < 4000; ++i) {
                const float3 p = random_on_sphere(rng);
                const float side = dot(p - kC, n) - 0.25f * kR;  // > 0: the cap above the hairline's plane
                if (std::fabs(side) < 0.01f * kR) continue;  // the polyline's chords stand in for the circle
                EXPECT_EQ(region.inside_hairline(p), side > 0) << p.x << "," << p.y << "," << p.z;
                ++checked;
            }
            EXPECT_GT(checked, 3800);
        }
    }
}

TEST(HairRegion, AGreatCirclePartingSplitsBySideAndStaysBare)
{
    const AnalyticSphere sphere(kC, kR);
    // The parting: the x = kC.x great circle from the front over the top to the back.
    std::vector<int64_t> counts{181};
    CurveSet parting = CurveSet::from_counts(counts);
    auto P = parting.positions_for_write();
    for (int i = 0; i <= 180; ++i) {
        const float a = kPi * i / 180;
        P[i] = kC + float3(0, std::sin(a), std::cos(a)) * kR;
    }
    HairRegionParams params;
    params.parting_gap = 0.4f;
    const HairRegion region(sphere, CurveSet(), parting, params);
    Rng rng(3, 4);
    uint32_t left = 0, right = 0;
    int bare = 0;
    for (int i = 0; i < 4000; ++i) {
        const float3 p = random_on_sphere(rng);
        if (p.y < kC.y + 0.05f * kR) continue;  // the parting's half of the sphere
        const float dx = p.x - kC.x;
        const uint32_t s = region.section(p);
        if (dx > 0.02f * kR) right |= 1u << s;
        if (dx < -0.02f * kR) left |= 1u << s;
        // Distance to the x = kC.x plane is the distance to the parting (its closest point).
        const bool on_gap = std::fabs(dx) < 0.2f - 1e-3f, off_gap = std::fabs(dx) > 0.2f + 0.01f;
        if (on_gap) EXPECT_FALSE(region.haired(p));
        if (off_gap) EXPECT_TRUE(region.haired(p));
        bare += on_gap;
    }
    // Each side has exactly one section, and the two differ.
    EXPECT_TRUE(left == 1u || left == 2u);
    EXPECT_TRUE(right == 1u || right == 2u);
    EXPECT_NE(left, right);
    EXPECT_GT(bare, 10);
    // A segment across the parting crosses it; one beside it does not.
    EXPECT_TRUE(region.crosses_parting(kC + float3(-1, kR - 0.1f, 0), kC + float3(1, kR - 0.1f, 0)));
    EXPECT_FALSE(region.crosses_parting(kC + float3(1, kR - 0.1f, 0), kC + float3(2, kR - 0.3f, 0)));
}

TEST(HairRegion, RefusesHairlinesThatDoNotGoOnceAround)
{
    const AnalyticSphere sphere(kC, kR);
    // Doubles back: half a circle there and back.
    CurveSet back = CurveSet::from_counts(std::vector<int64_t>{20});
    auto P = back.positions_for_write();
    for (int i = 0; i < 20; ++i) {
        const float a = kPi * (i < 10 ? i : 19 - i) / 10 + (i >= 10 ? 0.01f : 0.0f);
        P[i] = kC + float3(std::cos(a) * 6, 2, std::sin(a) * 6);
    }
    EXPECT_THROW(HairRegion(sphere, back, CurveSet(), HairRegionParams{}), InvalidGeometry);
    // Too few points; two curves.
    EXPECT_THROW(HairRegion(sphere, circle_on_sphere({0, 1, 0}, 1, 5), CurveSet(), HairRegionParams{}), InvalidGeometry);
    const CurveSet one = circle_on_sphere({0, 1, 0}, 1, 30);
    CurveSet two = CurveSet::from_counts(std::vector<int64_t>{30, 30});
    std::copy(one.positions().begin(), one.positions().end(), two.positions_for_write().begin());
    std::copy(one.positions().begin(), one.positions().end(), two.positions_for_write().begin() + 30);
    try {
        HairRegion(sphere, two, CurveSet(), HairRegionParams{});
        FAIL();
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("hairline"), std::string::npos) << e.what();
    }
    HairRegionParams bad;
    bad.parting_gap = -1;
    EXPECT_THROW(bad.validate(), InvalidParam);
}

// An open curve passed as the hairline by mistake (a trial passed a parting line to edges, gather,
// sections and partition: all ran, on nonsense). A circle with a gap turns once around its
// centroid's axis, so only its open ends tell: refused when they are more than a tenth of its length
// apart; the same circle closed is taken.
TEST(HairRegion, RefusesAnOpenCurveAsTheHairline)
{
    const AnalyticSphere sphere(kC, kR);
    for (const float gap : {0.5f, 0.15f}) {
        CurveSet open = CurveSet::from_counts(std::vector<int64_t>{60});
        auto P = open.positions_for_write();
        for (int i = 0; i < 60; ++i) {
            const float a = 2.0f * kPi * (1.0f - gap) * float(i) / 59.0f;
            P[i] = kC + float3(std::cos(a) * 6, 2, std::sin(a) * 6);
        }
        try {
            HairRegion(sphere, open, CurveSet(), HairRegionParams{});
            ADD_FAILURE() << "an open curve with a gap of " << gap << " of a turn was taken as a hairline";
        }
        catch (const InvalidGeometry& e) {
            EXPECT_NE(std::string(e.what()).find("open curve"), std::string::npos) << e.what();
        }
        EXPECT_THROW(check_hairline(open, "edges: the hairline"), InvalidGeometry);
    }
    EXPECT_NO_THROW(HairRegion(sphere, circle_on_sphere({0, 1, 0}, 1, 60), CurveSet(), HairRegionParams{}));
}

// A closed hairline written closed (its first point again at the end: a USD periodic curve as read,
// an OBJ record back to its first vertex, a Blender loop of edges) is the same hairline as the open
// form. It was refused ("point 90 turns back": the closing step has no azimuth) by every op reading
// it through HairRegion, and gave edges a zero-length piece. A curve that really turns back or runs
// past its start is refused still.
TEST(HairRegion, AHairlineClosedByRepeatingItsFirstPointIsTheOpenOne)
{
    const AnalyticSphere sphere(kC, kR);
    const CurveSet open = circle_on_sphere(normalize(float3(0, 1, -0.3f)), 0.25f * kR, 90);
    const auto with_points = [](std::vector<float3> pts) {
        CurveSet c = CurveSet::from_counts(std::vector<int64_t>{int64_t(pts.size())});
        std::copy(pts.begin(), pts.end(), c.positions_for_write().begin());
        return c;
    };
    std::vector<float3> pts(open.positions().begin(), open.positions().end());
    std::vector<float3> closed_pts = pts;
    closed_pts.push_back(pts.front());
    const CurveSet closed = with_points(closed_pts);

    const auto span = check_hairline(closed, "hairline");
    ASSERT_EQ(span.size(), pts.size());
    EXPECT_TRUE(std::equal(span.begin(), span.end(), pts.begin()));
    const HairRegion a(sphere, open, CurveSet(), HairRegionParams{}), b(sphere, closed, CurveSet(), HairRegionParams{});
    EXPECT_EQ(a.centroid(), b.centroid());
    Rng rng(5, 6);
    for (int i = 0; i < 2000; ++i) {
        const float3 p = random_on_sphere(rng);
        ASSERT_EQ(a.hairline_margin(p), b.hairline_margin(p)) << i;
    }

    const auto refused = [&](const std::vector<float3>& q, const std::string& says) {
        try {
            HairRegion(sphere, with_points(q), CurveSet(), HairRegionParams{});
            ADD_FAILURE() << "taken: " << says;
        }
        catch (const InvalidGeometry& e) {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
        }
    };
    // Runs on past its start, over its first five points again, then closes.
    std::vector<float3> overlap = pts;
    overlap.insert(overlap.end(), pts.begin(), pts.begin() + 6);
    refused(overlap, "turns back");
    // Ends a little past its first point (a hand-drawn loop closed by overshooting).
    std::vector<float3> past = pts;
    past.push_back(pts[0] + (pts[1] - pts[0]) * 0.3f);
    refused(past, "point 90 turns back");
    // Turns back between two of its points, open or closed.
    std::vector<float3> zigzag = pts;
    std::swap(zigzag[20], zigzag[21]);
    refused(zigzag, "point 21 turns back");
    zigzag.push_back(zigzag.front());
    refused(zigzag, "point 21 turns back");

    // A vertex given twice, and one that wobbles back a fiftieth of a step (0.08 degrees: a scan's
    // hairline, a head tipped back; `edges` took them and every op reading a region refused "turns
    // back", a hostile trial): the point is left out, and the region is the one without it.
    std::vector<float3> twice = pts;
    twice.insert(twice.begin() + 40, pts[40]);
    std::vector<float3> wobble = pts, without = pts;
    wobble[30] = pts[29] + (pts[29] - pts[30]) * 0.02f;
    without.erase(without.begin() + 30);
    const HairRegion d(sphere, with_points(twice), CurveSet(), HairRegionParams{}), e(sphere, with_points(wobble), CurveSet(), HairRegionParams{}),
        f(sphere, with_points(without), CurveSet(), HairRegionParams{});
    Rng r2(5, 6);
    for (int i = 0; i < 2000; ++i) {
        const float3 p = random_on_sphere(r2);
        // Which points are haired: the same, but within a degree of the hairline (the centroid, of
        // every point given, moves a little with the repeated or moved point).
        if (std::fabs(a.hairline_margin(p)) > 1.0f * kPi / 180.0f) ASSERT_EQ(d.inside_hairline(p), a.inside_hairline(p)) << i;
        if (std::fabs(f.hairline_margin(p)) > 1.0f * kPi / 180.0f) ASSERT_EQ(e.inside_hairline(p), f.inside_hairline(p)) << i;
    }
}
