// Primvars with elementSize > 1: N values per element. Three floats per element become a float3
// column; other shapes, and types no column holds (texCoord2f), are left out with a warning naming
// the primvar.
#include "tests/kernel/usda_test_util.h"

using namespace groom;
using groom::test::read_usda_text;
using groom::test::usda_error;

TEST(UsdaElementSize, ThreeFloatsPerElementAreAFloat3OthersAreLeftOutByName)
{
    const auto r = read_usda_text(R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2, 2]
    point3f[] points = [(0,0,0), (0,1,0), (1,0,0), (1,1,0)]
    float[] primvars:rgb = [0.1, 0.2, 0.3,  0.4, 0.5, 0.6] (interpolation = "uniform"; elementSize = 3)
    float[] primvars:pair = [1, 2, 3, 4, 5, 6, 7, 8] (interpolation = "vertex"; elementSize = 2)
    float[] primvars:k = [1, 2, 3, 4] (elementSize = 4)
    texCoord2f[] primvars:st = [(0, 0), (1, 1)] (interpolation = "uniform")
    int[] primvars:st:indices = [0, 1]
}
)");
    const CurveSet& cs = r.curves;
    auto rgb = cs.find<float3>(Domain::Curve, "rgb");
    ASSERT_EQ(rgb.size(), 2u);
    EXPECT_EQ(rgb[1].x, 0.4f);
    EXPECT_EQ(rgb[1].z, 0.6f);
    EXPECT_EQ(cs.attributes(Domain::Point).find("pair"), nullptr);
    EXPECT_TRUE(r.warned("t.usda:7: primvars:pair of </c> has elementSize 2 (float), which no attribute type holds; left out"));
    EXPECT_TRUE(r.warned("t.usda:8: primvars:k of </c> has elementSize 4"));  // constant, inferred from the count
    EXPECT_TRUE(r.warned("t.usda:9: primvars:st of </c> (texCoord2f[]) left out: no attribute type holds it"));
    EXPECT_EQ(r.warnings.size(), 3u);
}

TEST(UsdaElementSize, CountsMustBeElementsTimesSize)
{
    EXPECT_NE(usda_error(R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points = [(0,0,0), (0,1,0)]
    float[] primvars:rgb = [0.1, 0.2, 0.3] (interpolation = "vertex"; elementSize = 3)
}
)")
                  .find("bad.usda:6: primvars:rgb has 3 values but interpolation 'vertex' with elementSize 3 needs 6"),
              std::string::npos);
}
