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
