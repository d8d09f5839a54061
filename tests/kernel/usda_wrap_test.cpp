// USD `wrap` for linear, bspline and catmullRom curves: periodic curves are closed (their first point
// repeated at the end) and follow the basis over the wrapped control points; pinned curves reach their
// end control points. Checked against the bases' closed forms.
#include "tests/kernel/usda_test_util.h"

#include <cmath>

using namespace groom;
using groom::test::read_usda_text;

namespace {

const char* kSquare = "[(1,0,0), (0,1,0), (-1,0,0), (0,-1,0)]";

std::string prim(const std::string& name, const std::string& type, const std::string& basis, const std::string& wrap, const std::string& extra = "")
{
    return "def BasisCurves \"" + name + "\" {\n uniform token type = \"" + type + "\"\n uniform token basis = \"" + basis +
           "\"\n uniform token wrap = \"" + wrap + "\"\n int[] curveVertexCounts = [4]\n point3f[] points = " + kSquare + "\n" + extra + "}\n";
}

const float3 kP[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};

}  // namespace

TEST(UsdaWrap, PeriodicLinearBsplineAndCatmullRomAreClosed)
{
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 2;
    // Varying widths: one per segment on every periodic curve here (4; linear: one per point).
    const std::string widths = " float[] widths = [1,2,3,4] (interpolation = \"varying\")\n";
    const auto r = read_usda_text("#usda 1.0\n" + prim("l", "linear", "bezier", "periodic", widths) + prim("b", "cubic", "bspline", "periodic", widths) +
                                      prim("c", "cubic", "catmullRom", "periodic", widths),
                                  opt);
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 3u);
    auto P = cs.positions();
    // Linear: the 4 corners and back to the first.
    ASSERT_EQ(cs.points_in(0), 5);
    for (int j = 0; j < 5; ++j) EXPECT_EQ(distance(P[j], kP[j % 4]), 0.0f);
    // B-spline: 4 segments (n / vstep) x 2 + 1; at each segment start (p_i + 4 p_{i+1} + p_{i+2}) / 6.
    ASSERT_EQ(cs.points_in(1), 9);
    const int64_t b = cs.points_of(1).begin;
    for (int s = 0; s < 4; ++s) {
        const float3 want = (kP[s] + 4.0f * kP[(s + 1) % 4] + kP[(s + 2) % 4]) / 6.0f;
        EXPECT_NEAR(distance(P[b + 2 * s], want), 0.0f, 1e-6f) << s;
    }
    EXPECT_NEAR(distance(P[b], P[b + 8]), 0.0f, 1e-6f);
    // Varying widths on a periodic curve: one per segment (4), the last segment blending back to the first.
    auto w = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), cs.num_points());
    EXPECT_EQ(w[4], 1.0f);  // the linear curve's closing point takes the first point's value
    EXPECT_NEAR(w[b + 1], 1.5f, 1e-6f);
    EXPECT_NEAR(w[b + 7], 2.5f, 1e-6f);  // 4 -> 1 half way
    // Catmull-Rom: interpolates p_{i+1} at each segment start; closed.
    ASSERT_EQ(cs.points_in(2), 9);
    const int64_t c = cs.points_of(2).begin;
    for (int s = 0; s < 4; ++s) EXPECT_NEAR(distance(P[c + 2 * s], kP[(s + 1) % 4]), 0.0f, 1e-6f) << s;
    // Half way along segment 0 (p1 -> p2), Catmull-Rom of p0..p3 at t = 1/2: (-p0 + 9 p1 + 9 p2 - p3) / 16.
    const float3 half = (-1.0f * kP[0] + 9.0f * kP[1] + 9.0f * kP[2] - kP[3]) / 16.0f;
    EXPECT_NEAR(distance(P[c + 1], half), 0.0f, 1e-6f);
    EXPECT_NEAR(distance(P[c], P[c + 8]), 0.0f, 1e-6f);
}

TEST(UsdaWrap, PinnedCubicCurvesReachTheirEnds)
{
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 3;
    const auto r = read_usda_text("#usda 1.0\n" + prim("b", "cubic", "bspline", "pinned") + prim("c", "cubic", "catmullRom", "pinned"),
                                  opt);
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 2u);
    auto P = cs.positions();
    for (size_t c = 0; c < 2; ++c) {
        const IndexRange rg = cs.points_of(c);
        ASSERT_EQ(rg.size(), 3 * 3 + 1);  // (n - 2) / 1 + 1 = 3 segments
        EXPECT_NEAR(distance(P[rg.begin], kP[0]), 0.0f, 1e-6f);
        EXPECT_NEAR(distance(P[rg.end - 1], kP[3]), 0.0f, 1e-6f);
    }
    // B-spline pinned, second segment start: over (p0, p1, p2, p3) without phantoms: (p0 + 4 p1 + p2) / 6.
    const float3 want = (kP[0] + 4.0f * kP[1] + kP[2]) / 6.0f;
    EXPECT_NEAR(distance(P[3], want), 0.0f, 1e-6f);
}

TEST(UsdaWrap, PinnedVaryingCountIsSegmentsPlusOne)
{
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 2;
    const auto ok = read_usda_text("#usda 1.0\n" + prim("b", "cubic", "bspline", "pinned", " float[] widths = [1,2,3,4] (interpolation = \"varying\")\n"), opt);
    auto w = ok.curves.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), 7u);
    for (int j = 0; j < 7; ++j) EXPECT_NEAR(w[j], 1.0f + j / 2.0f, 1e-6f);
    EXPECT_NE(groom::test::usda_error("#usda 1.0\n" + prim("b", "cubic", "bspline", "pinned", " float[] widths = [1,2,3,4,5] (interpolation = \"varying\")\n"))
                  .find("widths has 5 values but interpolation 'varying' needs 4"),
              std::string::npos);
}

TEST(UsdaWrap, CatmullRomWidthOvershootIsClampedAtZero)
{
    // Widths 0,0,1,0,0,0 through Catmull-Rom: on the third segment (control values 1,0,0,0) the basis
    // gives -t(1-t)^2/2 < 0, which is overshoot, not a width: read as 0. Elsewhere the closed form.
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 4;
    const auto r = read_usda_text(R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "cubic"
    uniform token basis = "catmullRom"
    int[] curveVertexCounts = [6]
    point3f[] points = [(0,0,0), (1,0,0), (2,0,0), (3,0,0), (4,0,0), (5,0,0)]
    float[] widths = [0, 0, 1, 0, 0, 0] (interpolation = "vertex")
}
)", opt);
    auto w = r.curves.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), 13u);
    for (int j = 0; j <= 4; ++j) {
        const double t = j / 4.0;
        EXPECT_NEAR(w[j], 0.5 * (t + 4 * t * t - 3 * t * t * t), 1e-6) << j;  // control values 0,0,1,0
    }
    for (int j = 9; j < 12; ++j) EXPECT_EQ(w[j], 0.0f) << j;
}
