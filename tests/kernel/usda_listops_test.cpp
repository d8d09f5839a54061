// Every list op (prepend, append, add, delete, reorder) on prim metadata, relationships and
// attributes: accepted, and applied where the reader uses the list (composition arcs).
#include "tests/kernel/usda_test_util.h"

using namespace groom;
using groom::test::read_usda_text;

TEST(UsdaListOps, AcceptedOnMetadataRelationshipsAndAttributes)
{
    const auto r = read_usda_text(R"(#usda 1.0
(
    prepend subLayers = []
)
def Material "M" { }
def BasisCurves "c" (
    prepend apiSchemas = ["MaterialBindingAPI"]
    append apiSchemas = ["SkelBindingAPI"]
    add apiSchemas = ["X"]
    delete apiSchemas = ["X"]
    reorder apiSchemas = ["SkelBindingAPI", "MaterialBindingAPI"]
) {
    prepend rel material:binding = </M>
    append rel proxyPrim = </M>
    add rel a = [</M>]
    delete rel b = </M>
    reorder rel c = [</M>]
    custom rel d
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points = [(0,0,0), (0,1,0)]
    prepend float e.connect = </M.out>
    reorder properties = ["points", "type"]
    reorder nameChildren = ["x"]
}
)");
    EXPECT_EQ(r.curves.num_curves(), 1u);
}

TEST(UsdaListOps, ArcListOpsEditTheList)
{
    // Explicit, then delete, prepend and append: the reference to </A> is deleted, </B> prepended.
    const auto r = read_usda_text(R"(#usda 1.0
class "A" { float[] widths = [1] (interpolation = "constant") }
class "B" { float[] widths = [2] (interpolation = "constant") }
class "Geo" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points = [(0,0,0), (0,1,0)]
}
def BasisCurves "c" (
    references = [</A>, </Geo>]
    delete references = </A>
    prepend references = </B>
    append references = </A>
) { }
def BasisCurves "d" (
    add inherits = </A>
    append references = </Geo>
) { }
)");
    ASSERT_EQ(r.curves.num_curves(), 2u);
    auto w = r.curves.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), 4u);
    EXPECT_EQ(w[0], 2.0f);  // </B> is first now: stronger than </A> appended after </Geo>
    EXPECT_EQ(w[2], 1.0f);
}
