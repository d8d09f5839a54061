// Which prims are geometry (UsdPrimDefaultPredicate): `active = false` prims and their descendants
// are left out, a prim only `over`ed is not defined, a `class` is abstract; an `over` composed onto a
// `def` (through a reference) is read with the def.
#include "tests/kernel/usda_test_util.h"

using namespace groom;
using groom::test::read_usda_text;

namespace {

std::string curve(const std::string& spec, const std::string& name, float x, const std::string& meta = "")
{
    return spec + " BasisCurves \"" + name + "\" " + meta + "{\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n point3f[] points = [(" +
           std::to_string(x) + ",0,0), (" + std::to_string(x) + ",1,0)]\n}\n";
}

}  // namespace

TEST(UsdaActivity, InactiveOverAndClassPrimsAreNotGeometry)
{
    const auto r = read_usda_text("#usda 1.0\n" + curve("def", "kept", 1) + curve("def", "off", 2, "(active = false) ") +
                                  "def Xform \"offParent\" (\n active = false\n) {\n" + curve("def", "child", 3) + "}\n" + curve("over", "onlyOver", 4) +
                                  curve("class", "aClass", 5) + "class Xform \"classParent\" {\n" + curve("def", "underClass", 6) + "}\n" +
                                  "over \"overParent\" {\n" + curve("def", "underOver", 7) + "}\n" + curve("def", "alsoKept", 8, "(active = true) "));
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 2u);
    EXPECT_EQ(cs.positions()[0].x, 1.0f);
    EXPECT_EQ(cs.positions()[2].x, 8.0f);
}

TEST(UsdaActivity, OverComposedOntoADefIsRead)
{
    // The instance references a class prototype and `over`s its child: the child's points come from
    // the over (stronger), its type and counts from the def. The class itself is not geometry.
    const auto r = read_usda_text(R"(#usda 1.0
class Xform "proto" {
    def BasisCurves "c" {
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(0,0,0), (0,1,0)]
    }
}
def Xform "inst" (references = </proto>) {
    over "c" {
        point3f[] points = [(5,0,0), (5,2,0)]
    }
}
)");
    ASSERT_EQ(r.curves.num_curves(), 1u);
    EXPECT_EQ(r.curves.positions()[1].x, 5.0f);
    EXPECT_EQ(r.curves.positions()[1].y, 2.0f);
}

TEST(UsdaActivity, ActiveComposesThroughArcs)
{
    // `active` is metadata: a reference to an inactive prim makes the referencing prim inactive too.
    const auto r = read_usda_text(R"(#usda 1.0
def Xform "off" (active = false) {
    def BasisCurves "c" {
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(0,0,0), (0,1,0)]
    }
}
def Xform "inst" (references = </off>) {
}
def Xform "on" (active = true; references = </off>) {
}
)");
    ASSERT_EQ(r.curves.num_curves(), 1u);  // only /on, whose own opinion is stronger
}
