// USD NurbsCurves (what Maya writes): order, knots, ranges and rational pointWeights evaluated to
// polylines. A rational quadratic circle lies on the circle; a clamped cubic with one span is the
// Bernstein (bezier) curve; order 2 is the control polygon.
#include "tests/kernel/usda_test_util.h"

#include <cmath>

using namespace groom;
using groom::test::read_usda_text;
using groom::test::usda_error;

TEST(UsdaNurbs, RationalCircleLiesOnTheCircle)
{
    // The textbook 9-point quadratic circle of radius 2 (The NURBS Book, ex. 7.2), in the plane z = 1.
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 16;
    const auto r = read_usda_text(R"(#usda 1.0
def NurbsCurves "circle" {
    int[] curveVertexCounts = [9]
    int[] order = [3]
    double[] knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]
    point3f[] points = [(2,0,1), (2,2,1), (0,2,1), (-2,2,1), (-2,0,1), (-2,-2,1), (0,-2,1), (2,-2,1), (2,0,1)]
    double[] pointWeights = [1, 0.70710678118654752, 1, 0.70710678118654752, 1, 0.70710678118654752, 1, 0.70710678118654752, 1]
    float[] widths = [0.1] (interpolation = "constant")
}
)", opt);
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 1u);
    ASSERT_EQ(cs.num_points(), 4u * 16 + 1);  // 4 non-empty spans
    auto P = cs.positions();
    double worst = 0;
    for (size_t i = 0; i < cs.num_points(); ++i) {
        worst = std::max(worst, std::abs(std::hypot(double(P[i].x), double(P[i].y)) - 2.0));
        EXPECT_EQ(P[i].z, 1.0f);
    }
    EXPECT_LT(worst, 2e-6);  // float points: the radius to float precision
    // The span ends are the even control points (weight 1, on the circle), and the quarter points land on 45 degrees.
    EXPECT_NEAR(P[16].x, 0.0f, 1e-6f);
    EXPECT_NEAR(P[16].y, 2.0f, 1e-6f);
    EXPECT_NEAR(P[8].x, P[8].y, 1e-6f);
    EXPECT_NEAR(distance(P[0], P[64]), 0.0f, 1e-6f);
    EXPECT_NEAR(cs.find<float>(Domain::Point, attr::width)[5], 0.1f, 1e-7f);
}

TEST(UsdaNurbs, ClampedCubicIsBernsteinAndRangesCutIt)
{
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 4;
    const auto r = read_usda_text(R"(#usda 1.0
def NurbsCurves "n" {
    int[] curveVertexCounts = [4, 4, 3]
    int[] order = [4, 4, 2]
    double[] knots = [0,0,0,0,1,1,1,1,  0,0,0,0,1,1,1,1,  0,0,1,2,2]
    double2[] ranges = [(0, 1), (0.25, 0.75), (0, 2)]
    point3f[] points = [(0,0,0), (1,2,0), (3,2,0), (4,0,0),  (0,0,0), (1,2,0), (3,2,0), (4,0,0),  (0,0,0), (1,1,0), (2,0,0)]
}
)", opt);
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 3u);
    auto P = cs.positions();
    auto bez = [](double t) {
        const double s = 1 - t;
        return float3{float(3 * t * s * s * 1 + 3 * t * t * s * 3 + t * t * t * 4), float(3 * t * s * s * 2 + 3 * t * t * s * 2), 0.0f};
    };
    ASSERT_EQ(cs.points_in(0), 5);
    for (int j = 0; j <= 4; ++j) EXPECT_NEAR(distance(P[j], bez(j / 4.0)), 0.0f, 1e-6f) << j;
    ASSERT_EQ(cs.points_in(1), 5);
    for (int j = 0; j <= 4; ++j) EXPECT_NEAR(distance(P[5 + j], bez(0.25 + 0.5 * j / 4.0)), 0.0f, 1e-6f) << j;
    // Order 2: straight spans, the control polygon itself.
    ASSERT_EQ(cs.points_in(2), 3);
    EXPECT_NEAR(distance(P[11], float3{1, 1, 0}), 0.0f, 1e-6f);
    EXPECT_NEAR(distance(P[12], float3{2, 0, 0}), 0.0f, 1e-6f);
}

TEST(UsdaNurbs, BadKnotsAndOrdersAreNamedWithTheirLine)
{
    const std::string head = "#usda 1.0\ndef NurbsCurves \"n\" {\n int[] curveVertexCounts = [4]\n point3f[] points = [(0,0,0),(1,0,0),(2,0,0),(3,0,0)]\n";
    EXPECT_NE(usda_error(head + " int[] order = [4]\n double[] knots = [0,0,0,1,1,1]\n}\n").find("bad.usda:6: knots has 6 values; the curves need 8"), std::string::npos);
    EXPECT_NE(usda_error(head + " int[] order = [5]\n double[] knots = [0,0,0,0,0,1,1,1,1]\n}\n").find("bad.usda:5: curve 0 has order 5 and 4 points"), std::string::npos);
    EXPECT_NE(usda_error(head + " int[] order = [4]\n double[] knots = [0,0,0,1,0,1,1,1]\n}\n").find("bad.usda:6: knots of curve 0 decrease"), std::string::npos);
    EXPECT_NE(usda_error(head + " double[] knots = [0,0,0,0,1,1,1,1]\n}\n").find("has no 'int[] order'"), std::string::npos);
}

TEST(UsdaNurbs, WidthsPerSpanEndAreVaryingEvenUnauthored)
{
    // One span (clamped cubic): 2 widths, no interpolation written: only `varying` (span ends) fits.
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 4;
    const auto r = read_usda_text(R"(#usda 1.0
def NurbsCurves "n" {
    point3f[] points = [(0,0,0), (1,1,0), (2,0,0), (3,1,0)]
    int[] curveVertexCounts = [4]
    int[] order = [4]
    double[] knots = [0, 0, 0, 0, 1, 1, 1, 1]
    float[] widths = [0.1, 0.3]
}
)", opt);
    auto w = r.curves.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), 5u);
    for (int j = 0; j <= 4; ++j) EXPECT_NEAR(w[j], 0.1f + 0.05f * j, 1e-6f);
}
