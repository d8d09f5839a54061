// Variant sets: the selected variant's body is composed into its prim (properties and child prims);
// a set with no selection contributes nothing, as in USD, with a warning naming it.
#include "tests/kernel/usda_test_util.h"

using namespace groom;
using groom::test::read_usda_text;

namespace {

const char* kFile = R"(#usda 1.0
def Xform "groom" (
    variants = {
        string density = "%s"
    }
    prepend variantSets = ["density", "length"]
) {
    variantSet "density" = {
        "sparse" {
            def BasisCurves "hair" {
                uniform token type = "linear"
                int[] curveVertexCounts = [2]
                point3f[] points = [(0,0,0), (0,1,0)]
            }
        }
        "dense" (doc = "two hairs") {
            def BasisCurves "hair" {
                uniform token type = "linear"
                int[] curveVertexCounts = [2, 2]
                point3f[] points = [(0,0,0), (0,1,0), (1,0,0), (1,1,0)]
            }
            double3 xformOp:translate = (0, 0, 7)
            uniform token[] xformOpOrder = ["xformOp:translate"]
        }
    }
    variantSet "length" = {
        "long" {
            def BasisCurves "extra" {
                uniform token type = "linear"
                int[] curveVertexCounts = [2]
                point3f[] points = [(0,0,0), (0,9,0)]
            }
        }
    }
}
)";

std::string with_selection(const std::string& selection)
{
    std::string s = kFile;
    s.replace(s.find("%s"), 2, selection);
    return s;
}

}  // namespace

TEST(UsdaVariants, TheSelectedVariantIsRead)
{
    const auto sparse = read_usda_text(with_selection("sparse"));
    EXPECT_EQ(sparse.curves.num_curves(), 1u);
    const auto dense = read_usda_text(with_selection("dense"));
    ASSERT_EQ(dense.curves.num_curves(), 2u);
    EXPECT_EQ(dense.curves.positions()[3].z, 7.0f);  // the variant's xform ops apply to its prim
    // "length" has no selection: nothing from it, and a warning saying so.
    EXPECT_TRUE(dense.warned("t.usda:2: variantSet \"length\" of </groom> has no selection; as in USD, none of its variants is read"));
}

TEST(UsdaVariants, AnUnknownSelectionIsWarnedAbout)
{
    const auto r = read_usda_text(with_selection("sparse") + "def BasisCurves \"other\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (0,1,0)]\n}\n");
    EXPECT_EQ(r.curves.num_curves(), 2u);
    const auto bad = read_usda_text(with_selection("huge") + "def BasisCurves \"other\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (0,1,0)]\n}\n");
    EXPECT_EQ(bad.curves.num_curves(), 1u);
    EXPECT_TRUE(bad.warned("has no variant \"huge\""));
}
