// The curl cross-section dictionary against each shape's closed form (talk, Sec. 3.1, eq. 1).
#include "ops/curl_shapes.h"

#include "kernel/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

using namespace groom;

namespace {

constexpr int kSteps = 2000;
constexpr float kPi = std::numbers::pi_v<float>;

/// Distance from (x, y) to the segment a-b.
float segment_distance(float x, float y, float ax, float ay, float bx, float by)
{
    const float vx = bx - ax, vy = by - ay;
    const float f = std::clamp(((x - ax) * vx + (y - ay) * vy) / (vx * vx + vy * vy), 0.0f, 1.0f);
    return std::hypot(x - (ax + f * vx), y - (ay + f * vy));
}

}  // namespace

TEST(CurlShapes, LameCurveSatisfiesItsEquation)
{
    for (float n : {0.6f, 1.0f, 2.0f, 2.5f, 4.0f, 10.0f}) {
        ShapeParams p;
        p.lame_exponent = n;
        for (int i = 0; i < kSteps; ++i) {
            const ShapePoint q = curl_shape_point(kLame, p, float(i) / kSteps);
            // |x/a|^n + |y/b|^n = 1 with a = b = 1 (unit scale).
            ASSERT_NEAR(std::pow(std::fabs(q.x), n) + std::pow(std::fabs(q.y), n), 1.0f, 2e-4f) << "n " << n << " step " << i;
        }
    }
}

TEST(CurlShapes, PolygonPointsLieOnItsEdgesAndVisitEveryEdge)
{
    for (int sides : {3, 4, 5, 8, 17}) {
        ShapeParams p;
        p.polygon_sides = sides;
        std::vector<int> hits(size_t(sides), 0);
        for (int i = 0; i < kSteps; ++i) {
            const ShapePoint q = curl_shape_point(kPolygon, p, float(i) / kSteps);
            float best = INFINITY;
            int best_edge = -1;
            for (int e = 0; e < sides; ++e) {
                // Circumradius 1, vertices at angles 2 pi (j + 1/2) / N.
                const float a0 = 2.0f * kPi * (float(e) - 0.5f) / float(sides), a1 = 2.0f * kPi * (float(e) + 0.5f) / float(sides);
                const float dd = segment_distance(q.x, q.y, std::cos(a0), std::sin(a0), std::cos(a1), std::sin(a1));
                if (dd < best) best = dd, best_edge = e;
            }
            ASSERT_LT(best, 2e-5f) << sides << " sides, step " << i;
            ++hits[size_t(best_edge)];
        }
        for (int e = 0; e < sides; ++e) EXPECT_GT(hits[size_t(e)], 0) << "edge " << e << " of " << sides << " never visited";
    }
}

TEST(CurlShapes, EllipseAndCircleSatisfyTheirEquations)
{
    ShapeParams p;
    for (float aspect : {0.2f, 0.5f, 1.0f}) {
        p.ellipse_aspect = aspect;
        for (int i = 0; i < kSteps; ++i) {
            const ShapePoint q = curl_shape_point(kEllipse, p, float(i) / kSteps);
            ASSERT_NEAR(q.x * q.x + (q.y / aspect) * (q.y / aspect), 1.0f, 1e-5f);
        }
    }
    for (int i = 0; i < kSteps; ++i) {
        const ShapePoint q = curl_shape_point(kCircle, p, float(i) / kSteps);
        ASSERT_NEAR(std::hypot(q.x, q.y), 1.0f, 1e-6f);
        // Counter-clockwise at constant speed: the polar angle is 2 pi t.
        const float a = std::atan2(q.y, q.x), want = 2.0f * kPi * float(i) / kSteps;
        ASSERT_NEAR(std::remainder(a - want, 2.0f * kPi), 0.0f, 1e-5f);
    }
}

TEST(CurlShapes, RoseSatisfiesPolarEquationAndHasItsPetals)
{
    for (int k : {1, 2, 3, 5, 6}) {
        ShapeParams p;
        p.rose_petals = k;
        std::vector<float> radius;
        for (int i = 0; i < kSteps; ++i) {
            const ShapePoint q = curl_shape_point(kRose, p, float(i) / kSteps);
            const float r = std::hypot(q.x, q.y), theta = std::atan2(q.y, q.x);
            // r = cos(k theta); a negative r is drawn at theta + pi, which |cos| absorbs for any k.
            ASSERT_NEAR(r, std::fabs(std::cos(float(k) * theta)), 2e-4f) << "k " << k << " step " << i;
            radius.push_back(r);
        }
        // One cycle traces the whole rose once: k petals for odd k, 2k for even k. Petal tips are
        // the (cyclic) local maxima of r.
        int tips = 0;
        for (int i = 0; i < kSteps; ++i) {
            const float r = radius[size_t(i)], before = radius[size_t((i + kSteps - 1) % kSteps)], after = radius[size_t((i + 1) % kSteps)];
            if (r > 0.99f && r >= before && r > after) ++tips;
        }
        EXPECT_EQ(tips, k % 2 ? k : 2 * k) << "k " << k;
    }
}

TEST(CurlShapes, EveryShapeIsClosedAndSmoothWhereCyclesJoin)
{
    ShapeParams p;
    p.lame_exponent = 0.7f;  // the star-like Lame curve has cusps on its axes, never at t = 0
    for (int s = 0; s < curl_shape_count(); ++s) {
        const ShapePoint a = curl_shape_point(s, p, 0.0f), b = curl_shape_point(s, p, 1.0f), c = curl_shape_point(s, p, 3.0f);
        EXPECT_NEAR(a.x, b.x, 1e-5f) << curl_shape_name(s);
        EXPECT_NEAR(a.y, b.y, 1e-5f) << curl_shape_name(s);
        EXPECT_NEAR(a.x, c.x, 1e-5f) << curl_shape_name(s);
        // One-sided difference quotients agree at the join: the tangent is continuous there.
        const float h = 1e-3f;
        const ShapePoint m = curl_shape_point(s, p, -h), pl = curl_shape_point(s, p, h);
        const float lx = (a.x - m.x) / h, ly = (a.y - m.y) / h, rx = (pl.x - a.x) / h, ry = (pl.y - a.y) / h;
        EXPECT_GT(std::hypot(lx, ly), 0.1f) << curl_shape_name(s) << " stalls at t = 0";
        EXPECT_NEAR(lx, rx, 0.05f * std::hypot(lx, ly)) << curl_shape_name(s);
        EXPECT_NEAR(ly, ry, 0.05f * std::hypot(lx, ly)) << curl_shape_name(s);
    }
}

// The curl op evaluates many points at once; a point must not depend on the run it came in (the
// op's output would then depend on where a curve is cut into chunks).
TEST(CurlShapes, ManyPointsAtOnceAreEachPointOnItsOwn)
{
    ShapeParams p;
    p.polygon_sides = 7;
    p.rose_petals = 4;
    const ShapeTable table(p);
    std::vector<float> t;
    for (int i = -300; i < 700; ++i) t.push_back(0.00731f * float(i));
    for (int s = 0; s < curl_shape_count(); ++s) {
        std::vector<float> x(t.size()), y(t.size());
        curl_shape_points(s, table, t.data(), t.size(), x.data(), y.data());
        for (size_t i = 0; i < t.size(); ++i) {
            const ShapePoint q = curl_shape_point(s, p, t[i]);
            ASSERT_EQ(q.x, x[i]) << curl_shape_name(s) << " t " << t[i];
            ASSERT_EQ(q.y, y[i]) << curl_shape_name(s) << " t " << t[i];
        }
    }
}

TEST(CurlShapes, NamesAndNumbersFollowTheTalk)
{
    ASSERT_EQ(curl_shape_count(), 5);
    const char* names[] = {"lame", "polygon", "ellipse", "circle", "rose"};
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(curl_shape_name(i), names[i]);
    }
    EXPECT_EQ(curl_shape_list(), "0 lame, 1 polygon, 2 ellipse, 3 circle, 4 rose");
}

TEST(CurlShapes, RejectsInvalidShapeParameters)
{
    auto expect_reject = [](ShapeParams p, const char* option) {
        try {
            p.validate();
            ADD_FAILURE() << option << " accepted";
        }
        catch (const InvalidParam& e) {
            EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
        }
    };
    ShapeParams p;
    EXPECT_NO_THROW(p.validate());
    p.lame_exponent = 0.0f;
    expect_reject(p, "`lame_exponent`");
    p = {};
    p.lame_exponent = NAN;
    expect_reject(p, "`lame_exponent`");
    p = {};
    p.polygon_sides = 2;
    expect_reject(p, "`polygon_sides`");
    p = {};
    p.ellipse_aspect = 1.5f;
    expect_reject(p, "`ellipse_aspect`");
    p = {};
    p.ellipse_aspect = 0.0f;
    expect_reject(p, "`ellipse_aspect`");
    p = {};
    p.rose_petals = 0;
    expect_reject(p, "`rose_petals`");
}
