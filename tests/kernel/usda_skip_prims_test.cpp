// Prims that cannot be read are skipped with a warning naming each (file, line, prim path); the
// read fails only when no curves remain. Choosing prims (CurveReadOptions::prims, the CLI's --prim):
// a prim and its descendants, several at once, an unknown path refused by name.
#include "kernel/error.h"
#include "tests/kernel/usda_test_util.h"

using namespace groom;
using groom::test::read_usda_text;
using groom::test::usda_error;

namespace {

std::string good(const std::string& name, float x)
{
    return "def BasisCurves \"" + name + "\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n point3f[] points = [(" + std::to_string(x) +
           ",0,0), (" + std::to_string(x) + ",1,0)]\n}\n";
}

const std::string kBad = "def BasisCurves \"bad\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [3]\n point3f[] points = [(0,0,0), (0,1,0)]\n}\n";
const std::string kEmpty = "def BasisCurves \"empty\" {\n}\n";
const std::string kOdd = "def BasisCurves \"odd\" {\n uniform token type = \"quintic\"\n int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (0,1,0)]\n}\n";

}  // namespace

TEST(UsdaSkipPrims, BadPrimsAreSkippedAndNamed)
{
    const auto r = read_usda_text("#usda 1.0\n" + good("a", 1) + kBad + kEmpty + kOdd + good("b", 2));
    ASSERT_EQ(r.curves.num_curves(), 2u);
    EXPECT_EQ(r.curves.positions()[2].x, 2.0f);
    EXPECT_TRUE(r.warned("t.usda:9: curveVertexCounts sum to 3 but 'points' (line 10) has 2 points; prim </bad> skipped"));
    EXPECT_TRUE(r.warned("t.usda:12: BasisCurves </empty> has no 'points'; prim </empty> skipped"));
    EXPECT_TRUE(r.warned("curve type 'quintic' is not supported (expected linear or cubic); prim </odd> skipped"));
    EXPECT_EQ(r.warnings.size(), 3u);
}

TEST(UsdaSkipPrims, NoCurvesLeftIsAnErrorListingThem)
{
    const std::string e = usda_error("#usda 1.0\n" + kBad + kEmpty);
    EXPECT_NE(e.find("bad.usda: no curves prim could be read (2 skipped): "), std::string::npos) << e;
    EXPECT_NE(e.find("bad.usda:4: curveVertexCounts sum to 3"), std::string::npos) << e;
    EXPECT_NE(e.find("BasisCurves </empty> has no 'points'"), std::string::npos) << e;
}

TEST(UsdaSkipPrims, PrimOptionPicksPrimsAndTheirDescendants)
{
    const std::string text = "#usda 1.0\ndef Xform \"left\" {\n" + good("a", 1) + "def Xform \"inner\" {\n" + good("b", 2) + "}\n}\ndef Xform \"right\" {\n" + good("c", 3) +
                             kBad + "}\n";
    CurveReadOptions opt;
    opt.prims = {"/left"};
    auto r = read_usda_text(text, opt);
    ASSERT_EQ(r.curves.num_curves(), 2u);
    EXPECT_EQ(r.curves.positions()[2].x, 2.0f);
    EXPECT_TRUE(r.warnings.empty());  // the bad prim under /right is not read at all
    opt.prims = {"/left/inner/b", "/right/c"};
    r = read_usda_text(text, opt);
    ASSERT_EQ(r.curves.num_curves(), 2u);
    EXPECT_EQ(r.curves.positions()[0].x, 2.0f);
    EXPECT_EQ(r.curves.positions()[2].x, 3.0f);
    opt.prims = {"/lef"};  // a prefix of a name is not a prim
    EXPECT_NE(usda_error(text, opt).find("--prim /lef: no such prim in the file"), std::string::npos);
    opt.prims = {"/right/bad"};
    EXPECT_NE(usda_error(text, opt).find("no curves prim could be read (1 skipped)"), std::string::npos);
}

TEST(UsdaSkipPrims, APrimWhoseTransformOverflowsIsSkippedNotTheFile)
{
    const auto r = read_usda_text("#usda 1.0\ndef Xform \"huge\" {\n float3 xformOp:scale = (1e30, 1e30, 1e30)\n uniform token[] xformOpOrder = [\"xformOp:scale\"]\n"
                                  "def BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (1e10,1,0)]\n}\n}\n" +
                                  good("ok", 1));
    EXPECT_EQ(r.curves.num_curves(), 1u);
    EXPECT_TRUE(r.warned("non-finite position"));
    EXPECT_TRUE(r.warned("prim </huge/c> skipped"));
}

TEST(UsdaTimeSamples, AnimatedPointsReadTheEarliestSampleAndSaySo)
{
    // Samples written out of order: the earliest time (1) is read, whatever the order; a default
    // value beside the samples is what USD gives with no time, but a groom frame is a time, so the
    // samples win. The warning names the property, prim, count and time, and the way to animate.
    const test::UsdaRead r = test::read_usda_text(R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points = [(5, 0, 0), (5, 1, 0)]
    point3f[] points.timeSamples = {
        2: [(2, 0, 0), (2, 1, 0)],
        1: [(1, 0, 0), (1, 1, 0)],
        3: [(3, 0, 0), (3, 1, 0)],
    }
}
)");
    ASSERT_EQ(r.curves.num_points(), 2u);
    EXPECT_EQ(r.curves.positions()[0], float3(1, 0, 0));
    EXPECT_EQ(r.curves.positions()[1], float3(1, 1, 0));
    EXPECT_TRUE(r.warned("points of </c> has 3 time samples; read the earliest (time 1)")) << (r.warnings.empty() ? "" : r.warnings[0]);
    EXPECT_TRUE(r.warned("guides.####.usda with --frames"));
    // One sample is a still frame: nothing to say.
    const test::UsdaRead still = test::read_usda_text(R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points.timeSamples = { 7: [(1, 0, 0), (1, 1, 0)] }
}
)");
    EXPECT_TRUE(still.warnings.empty());
}
