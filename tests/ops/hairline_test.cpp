// The default hairline: on an exact sphere its points follow the closed form (height below the top
// from the key fractions of the measured length, on the surface, mirror-symmetric); on the default head
// it sits where a hairline does (above the brows, above the ears, down at the nape) and goes once around.
#include "ops/hairline.h"

#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "ops/hair_region.h"
#include "ops/head.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace groom;

TEST(Hairline, OnASphereFollowsTheKeyHeights)
{
    const float3 C{1, 2, 3};
    const float R = 10;
    const AnalyticSphere sphere(C, R);
    Bounds3 box;
    box.extend(C - float3(R, R, R));
    box.extend(C + float3(R, R, R));
    HairlineParams p;
    p.points = 360;  // one point per degree: azimuth 0 is point 180, 90 is point 270
    const CurveSet h = make_hairline(sphere, box, p);
    ASSERT_EQ(h.num_points(), 360u);
    const auto P = h.positions();
    // The top is C + R up; the length is measured 0.4 R below it: 2 sqrt(R^2 - (0.6 R)^2) = 1.6 R.
    const float L = 1.6f * R;
    auto height_below_top = [&](int i) { return C.y + R - P[i].y; };
    EXPECT_NEAR(height_below_top(180), p.forehead * L, 2e-3f * R);
    EXPECT_NEAR(height_below_top(0), p.nape * L, 2e-3f * R);
    EXPECT_NEAR(height_below_top(180 + 55), p.temple * L, 2e-3f * R);
    EXPECT_NEAR(height_below_top(180 - 80), p.sideburn * L, 2e-3f * R);
    EXPECT_NEAR(height_below_top(180 + 105), p.ear * L, 2e-3f * R);
    for (int i = 0; i < 360; ++i) {
        EXPECT_NEAR(distance(P[i], C), R, 1e-3f * R) << i;  // on the surface
        if (i > 0) {
            // Left and right mirror each other across the x = C.x plane.
            const float3 m = P[360 - i];
            EXPECT_NEAR(m.x - C.x, -(P[i].x - C.x), 1e-3f * R) << i;
            EXPECT_NEAR(m.y, P[i].y, 1e-3f * R) << i;
        }
    }
    // Forehead faces +z (forward).
    EXPECT_GT(P[180].z - C.z, 0.5f * R);
    // It goes once around: a hair region accepts it.
    EXPECT_NO_THROW(HairRegion(sphere, h, CurveSet(), HairRegionParams{}));
}

TEST(Hairline, OnTheDefaultHeadSitsWhereAHairlineDoes)
{
    HeadParams hp;
    hp.resolution = 48;
    const ScalpField scalp = build_scalp(make_head(hp));
    const CurveSet h = make_hairline(scalp, scalp.bounds(), HairlineParams{});
    const auto P = h.positions();
    const int n = int(P.size());
    const float tol = scalp.voxel_size();
    for (const float3& p : P) EXPECT_LT(std::fabs(scalp.distance(p)), tol);
    // Head frame (ops/head.h): brows at y = 1.6 near z = 9, ear tops at y = 2.1, chin at -11.7.
    const float3 front = P[n / 2], back = P[0];
    EXPECT_GT(front.y, 5.0f);   // a forehead above the brows
    EXPECT_LT(front.y, 9.0f);   // below the crown (top at y = 12)
    EXPECT_GT(front.z, 6.0f);
    EXPECT_LT(back.y, 0.0f);    // the nape, below the ears
    EXPECT_GT(back.y, -8.0f);   // above the neck's base
    EXPECT_LT(back.z, -6.0f);
    for (int i = 0; i < n; ++i) {
        // Over the ears (|x| > 6 near z = -1) the hairline passes above their tops.
        if (std::fabs(P[i].x) > 6.5f && std::fabs(P[i].z + 0.9f) < 1.0f) EXPECT_GT(P[i].y, 2.1f) << i;
    }
    const HairRegion region(scalp, h, CurveSet(), HairRegionParams{});
    EXPECT_TRUE(region.inside_hairline({0, 12, -1}));    // crown
    EXPECT_FALSE(region.inside_hairline({0, 0, 9}));     // between the eyes
    EXPECT_FALSE(region.inside_hairline({0, -11, 6}));   // chin
    EXPECT_FALSE(region.inside_hairline({0, -15, -6}));  // back of the neck
}

// A head on a tall body: the middle of the bounds is far below the head, so the axis through it
// meets the head only at its top and the length cannot be measured. The message says to give
// --center (its old advice, --head-length, put the hairline across a MakeHuman body's eyebrows),
// and with a centre inside the head the same scalp gets its hairline.
TEST(Hairline, OnABodyItAsksForACentreInsideTheHead)
{
    const AnalyticSphere head({0, 0, 0}, 1.0f);
    Bounds3 body;  // the head's top at y = 1, the feet at y = -11
    body.extend(float3(-1, -11, -1));
    body.extend(float3(1, 1, 1));
    HairlineParams p;
    try {
        make_hairline(head, body, p);
        ADD_FAILURE() << "measured a head from the middle of the body";
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("give --center inside the head"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("middle of the scalp's bounds, 0,-5,0"), std::string::npos) << e.what();
    }
    p.center = {0, 0, 0};
    p.has_center = true;
    EXPECT_EQ(make_hairline(head, body, p).num_curves(), 1u);
}

TEST(Hairline, RejectsBadParams)
{
    const AnalyticSphere sphere({0, 0, 0}, 1);
    Bounds3 box;
    box.extend({-1, -1, -1});
    box.extend({1, 1, 1});
    HairlineParams p;
    p.forward = {0, 2, 0};  // parallel to up
    EXPECT_THROW(make_hairline(sphere, box, p), InvalidParam);
    p = {};
    p.nape = 2.5f;
    try {
        make_hairline(sphere, box, p);
        FAIL();
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`nape`"), std::string::npos) << e.what();
    }
    p = {};
    p.points = 4;
    EXPECT_THROW(make_hairline(sphere, box, p), InvalidParam);
    // No scalp above the centre.
    p = {};
    p.center = {5, 0, 0};
    p.has_center = true;
    EXPECT_THROW(make_hairline(sphere, box, p), InvalidGeometry);
}
