// USD BasisCurves with the bezier basis, USD's default when a file writes neither `type` nor `basis`:
// points against the Bernstein form, the 3n+1 rule, varying and vertex primvar counts
// (UsdGeomBasisCurves: varying = segments + 1, or segments when periodic), periodic and pinned.
#include "kernel/error.h"
#include "tests/kernel/usda_test_util.h"

#include <cmath>

using namespace groom;
using groom::test::read_usda_text;
using groom::test::usda_error;

namespace {

float3 bernstein(const float3 p[4], double t)
{
    const double s = 1 - t;
    const double w[4] = {s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
    double x = 0, y = 0, z = 0;
    for (int i = 0; i < 4; ++i) x += w[i] * p[i].x, y += w[i] * p[i].y, z += w[i] * p[i].z;
    return {float(x), float(y), float(z)};
}

const float3 kCvs[7] = {{0, 0, 0}, {1, 2, 0}, {3, 2, 1}, {4, 0, 1}, {5, -2, 1}, {7, -1, 0}, {8, 0, 0}};

}  // namespace

TEST(UsdaBezier, DefaultBasisIsCubicBezierMatchingBernstein)
{
    // No type, no basis: the schema defaults (cubic, bezier). 7 points = 2 segments.
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 5;
    const auto r = read_usda_text(R"(#usda 1.0
def BasisCurves "b" {
    int[] curveVertexCounts = [7]
    point3f[] points = [(0,0,0), (1,2,0), (3,2,1), (4,0,1), (5,-2,1), (7,-1,0), (8,0,0)]
    float[] widths = [1, 2, 3] (interpolation = "varying")
    float[] primvars:v = [0, 1, 2, 3, 4, 5, 6] (interpolation = "vertex")
}
)", opt);
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 1u);
    ASSERT_EQ(cs.num_points(), 11u);  // 2 segments x 5 + 1
    auto P = cs.positions();
    auto w = cs.find<float>(Domain::Point, attr::width);
    auto v = cs.find<float>(Domain::Point, "v");
    ASSERT_EQ(w.size(), 11u);
    ASSERT_EQ(v.size(), 11u);
    for (int j = 0; j <= 10; ++j) {
        const int seg = std::min(j / 5, 1);
        const double t = (j - seg * 5) / 5.0;
        const float3 want = bernstein(kCvs + 3 * seg, t);
        EXPECT_NEAR(P[j].x, want.x, 1e-5f) << j;
        EXPECT_NEAR(P[j].y, want.y, 1e-5f) << j;
        EXPECT_NEAR(P[j].z, want.z, 1e-5f) << j;
        // varying widths (segments + 1 = 3 values) are linear along each segment
        EXPECT_NEAR(w[j], 1.0 + seg + t, 1e-6) << j;
        // a vertex primvar goes through the same basis: Bernstein of 3s..3s+3 is linear here
        // because the values are linear in the index (the Bernstein basis reproduces lines)
        EXPECT_NEAR(v[j], 3 * seg + 3 * t, 1e-5) << j;
    }
    // The curve interpolates its segment ends exactly.
    EXPECT_EQ(P[0].x, 0.0f);
    EXPECT_NEAR(P[5].x, 4.0f, 1e-6f);
    EXPECT_NEAR(P[10].x, 8.0f, 1e-6f);
}

TEST(UsdaBezier, PeriodicBezierIsClosedAndPinnedIsNonperiodic)
{
    // Periodic: 6 points = 2 segments, the second ending on the first point.
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 4;
    const auto r = read_usda_text(R"(#usda 1.0
def BasisCurves "p" {
    uniform token type = "cubic"
    uniform token wrap = "periodic"
    int[] curveVertexCounts = [6]
    point3f[] points = [(0,0,0), (1,2,0), (3,2,1), (4,0,1), (5,-2,1), (7,-1,0)]
    float[] widths = [1, 3] (interpolation = "varying")
}
def BasisCurves "q" {
    uniform token wrap = "pinned"
    int[] curveVertexCounts = [4]
    point3f[] points = [(0,0,0), (1,2,0), (3,2,1), (4,0,1)]
    float[] widths = [1, 3] (interpolation = "varying")
}
)", opt);
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 2u);
    ASSERT_EQ(cs.points_in(0), 9);  // 2 x 4 + 1: closed by repeating the start
    auto P = cs.positions();
    const float3 second[4] = {kCvs[3], kCvs[4], {7, -1, 0}, kCvs[0]};
    for (int j = 4; j <= 8; ++j) {
        const float3 want = bernstein(second, (j - 4) / 4.0);
        EXPECT_NEAR(P[j].x, want.x, 1e-5f);
        EXPECT_NEAR(P[j].y, want.y, 1e-5f);
    }
    EXPECT_NEAR(distance(P[0], P[8]), 0.0f, 1e-6f);
    auto w = cs.find<float>(Domain::Point, attr::width);
    EXPECT_NEAR(w[2], 2.0f, 1e-6f);   // half way along segment 0: 1 -> 3
    EXPECT_NEAR(w[6], 2.0f, 1e-6f);   // half way along segment 1: 3 -> 1 (wraps)
    EXPECT_NEAR(w[8], 1.0f, 1e-6f);
    // Pinned bezier is the same as nonperiodic: 1 segment, Bernstein.
    ASSERT_EQ(cs.points_in(1), 5);
    const float3 want = bernstein(kCvs, 0.5);
    EXPECT_NEAR(P[9 + 2].x, want.x, 1e-5f);
    EXPECT_NEAR(P[9 + 2].y, want.y, 1e-5f);
}

TEST(UsdaBezier, CountsOffTheRulesAreNamed)
{
    // 5 points is not 3n+1; a varying primvar with the vertex count is a count error.
    EXPECT_NE(usda_error("#usda 1.0\ndef BasisCurves \"c\" {\n int[] curveVertexCounts = [5]\n point3f[] points = [(0,0,0),(1,0,0),(2,0,0),(3,0,0),(4,0,0)]\n}\n")
                  .find("bad.usda:2: BasisCurves </c>: cubic bezier nonperiodic curve 0 has 5 points; bezier needs 3 per segment plus 1"),
              std::string::npos);
    EXPECT_NE(usda_error("#usda 1.0\ndef BasisCurves \"c\" {\n int[] curveVertexCounts = [4]\n point3f[] points = [(0,0,0),(1,0,0),(2,0,0),(3,0,0)]\n"
                         " float[] widths = [1,2,3,4] (interpolation = \"varying\")\n}\n")
                  .find("bad.usda:5: widths has 4 values but interpolation 'varying' needs 2"),
              std::string::npos);
    EXPECT_NE(usda_error("#usda 1.0\ndef BasisCurves \"c\" {\n uniform token wrap = \"periodic\"\n int[] curveVertexCounts = [4]\n point3f[] points = [(0,0,0),(1,0,0),(2,0,0),(3,0,0)]\n}\n")
                  .find("periodic bezier needs a multiple of 3"),
              std::string::npos);
}
