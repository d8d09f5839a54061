// In-file composition arcs flattened: references (and instanceable instances), inherits, specializes,
// payloads, with LIVRPS strength (local > inherits > variants > references > specializes); arcs to
// other files and cycles warned about, never followed.
#include "tests/kernel/usda_test_util.h"

using namespace groom;
using groom::test::read_usda_text;

TEST(UsdaArcs, FourInstancesReadAsFourTransformedSets)
{
    const auto r = read_usda_text(R"(#usda 1.0
class Xform "Prototypes" {
    def Xform "Groom" {
        def BasisCurves "hair" {
            uniform token type = "linear"
            int[] curveVertexCounts = [2, 2]
            point3f[] points = [(0,0,0), (0,1,0), (1,0,0), (1,1,0)]
        }
    }
}
def Xform "inst0" (instanceable = true; references = </Prototypes/Groom>) {
    double3 xformOp:translate = (0, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def Xform "inst1" (instanceable = true; prepend references = </Prototypes/Groom>) {
    double3 xformOp:translate = (10, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def Xform "inst2" (instanceable = true; references = [</Prototypes/Groom>]) {
    double3 xformOp:translate = (20, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def Xform "inst3" (
    instanceable = true
    payload = </Prototypes/Groom>
) {
    double3 xformOp:translate = (30, 0, 0)
    float3 xformOp:scale = (2, 2, 2)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:scale"]
}
)");
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 8u);
    auto P = cs.positions();
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(P[4 * i].x, 10.0f * i);
        EXPECT_EQ(P[4 * i + 2].x, 10.0f * i + 1);
    }
    EXPECT_EQ(P[12].x, 30.0f);
    EXPECT_EQ(P[14].x, 32.0f);  // scaled 2 then moved
    EXPECT_EQ(P[15].y, 2.0f);
}

TEST(UsdaArcs, StrengthOrderLocalInheritsReferencesSpecializes)
{
    // Every prim gets type/counts/points from a reference; widths come from the strongest arc that has them.
    const auto r = read_usda_text(R"(#usda 1.0
class "Base" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points = [(0,0,0), (0,1,0)]
    float[] widths = [4] (interpolation = "constant")
}
class "I" { float[] widths = [1] (interpolation = "constant") }
class "S" { float[] widths = [3] (interpolation = "constant") }
def BasisCurves "local" (inherits = </I>; references = </Base>) { float[] widths = [0.5] (interpolation = "constant") }
def BasisCurves "inherit" (references = </Base>; inherits = </I>; specializes = </S>) { }
def BasisCurves "reference" (references = </Base>; specializes = </S>) { }
def BasisCurves "specialized" (specializes = </S>) {
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points = [(0,0,0), (0,1,0)]
}
)");
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 4u) << (r.warnings.empty() ? "" : r.warnings[0]);
    auto w = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), 8u);
    EXPECT_EQ(w[0], 0.5f);  // local
    EXPECT_EQ(w[2], 1.0f);  // inherits beat references and specializes
    EXPECT_EQ(w[4], 4.0f);  // references beat specializes
    EXPECT_EQ(w[6], 3.0f);  // specializes, when nothing stronger speaks
}

TEST(UsdaArcs, OtherFilesAndCyclesAreWarnedAboutNotFollowed)
{
    const auto r = read_usda_text(R"(#usda 1.0
def Xform "ext" (references = @./other.usda@</Groom>) {
    def BasisCurves "local" {
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(0,0,0), (0,1,0)]
    }
}
def Xform "a" (references = </b>) { }
def Xform "b" (inherits = </a>) { }
def Xform "missing" (references = </nowhere>) { }
)");
    EXPECT_EQ(r.curves.num_curves(), 1u);
    EXPECT_TRUE(r.warned("t.usda:2: </ext> refers to another file (@./other.usda@</Groom>); other files are not read"));
    EXPECT_TRUE(r.warned("a cycle"));
    EXPECT_TRUE(r.warned("t.usda:11: </missing> refers to </nowhere>, which is not in the file"));
}
