// USD xform ops applied to points, composed down the prim hierarchy (UsdGeomXformable): a
// translate/rotate/scale stack on a known point, every rotation order, orient, transform, !invert!,
// !resetXformStack!, widths scaled by the uniform part; malformed ops named by file and line.
#include "tests/kernel/usda_test_util.h"

#include <cmath>

using namespace groom;
using groom::test::read_usda_text;
using groom::test::usda_error;

namespace {

/// A linear curve (1,0,0) -> (0,1,0) under the given xform lines.
std::string curve(const std::string& name, const std::string& ops)
{
    return "def BasisCurves \"" + name + "\" {\n" + ops +
           "\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n point3f[] points = [(1,0,0), (0,1,0)]\n float[] widths = [0.5, 0.5]\n}\n";
}

void expect_point(const CurveSet& cs, size_t curve, int i, float3 want, const char* what)
{
    const float3 p = cs.positions()[cs.points_of(curve).begin + i];
    EXPECT_NEAR(distance(p, want), 0.0f, 1e-5f) << what << ": got (" << p.x << ", " << p.y << ", " << p.z << ")";
}

}  // namespace

TEST(UsdaXform, TranslateRotateScaleStackUnderATransformedParent)
{
    // Point (1,0,0): scale 2 -> (2,0,0), rotateZ 90 -> (0,2,0), translate (1,2,3) -> (1,4,3); the parent adds (10,0,0).
    const auto r = read_usda_text("#usda 1.0\ndef Xform \"parent\" {\n double3 xformOp:translate = (10, 0, 0)\n uniform token[] xformOpOrder = [\"xformOp:translate\"]\n" +
                                  curve("c", " double3 xformOp:translate = (1, 2, 3)\n float3 xformOp:rotateXYZ = (0, 0, 90)\n float3 xformOp:scale = (2, 2, 2)\n"
                                             " uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateXYZ\", \"xformOp:scale\"]") +
                                  "}\n");
    expect_point(r.curves, 0, 0, {11, 4, 3}, "T R S");
    expect_point(r.curves, 0, 1, {10 + 1 - 2, 2, 3}, "T R S second point");  // (0,1,0) -> (0,2,0) -> (-2,0,0) -> (-1,2,3)
    // widths times the uniform scale (2)
    EXPECT_NEAR(r.curves.find<float>(Domain::Point, attr::width)[0], 1.0f, 1e-6f);
}

TEST(UsdaXform, EveryRotationOrderOrientTransformAndInvert)
{
    const std::string order = " uniform token[] xformOpOrder = [\"xformOp:";
    const auto r = read_usda_text("#usda 1.0\n" +
                                  curve("xyz", " float3 xformOp:rotateXYZ = (90, 90, 0)\n" + order + "rotateXYZ\"]") +     // X then Y
                                  curve("zyx", " float3 xformOp:rotateZYX = (90, 90, 0)\n" + order + "rotateZYX\"]") +     // Z, Y, then X
                                  curve("yzx", " float3 xformOp:rotateYZX = (0, 90, 90)\n" + order + "rotateYZX\"]") +     // Y, Z, then X
                                  curve("rx", " double xformOp:rotateX = 90\n" + order + "rotateX\"]") +
                                  curve("orient", " quatf xformOp:orient = (0.70710678, 0, 0, 0.70710678)\n" + order + "orient\"]") +
                                  curve("m", " matrix4d xformOp:transform = ( (0, 1, 0, 0), (-1, 0, 0, 0), (0, 0, 1, 0), (5, 6, 7, 1) )\n" + order + "transform\"]") +
                                  curve("inv", " double3 xformOp:translate:pivot = (1, 1, 1)\n uniform token[] xformOpOrder = [\"!invert!xformOp:translate:pivot\"]") +
                                  curve("two", " double3 xformOp:translate = (0, 0, 1)\n double3 xformOp:translate:pivot = (1, 0, 0)\n float xformOp:rotateZ = 90\n"
                                               " uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:translate:pivot\", \"xformOp:rotateZ\", \"!invert!xformOp:translate:pivot\"]"));
    const CurveSet& cs = r.curves;
    ASSERT_EQ(cs.num_curves(), 8u);
    expect_point(cs, 0, 0, {0, 0, -1}, "rotateXYZ (90,90,0) of (1,0,0)");  // X: (1,0,0); Y 90: (0,0,-1)
    expect_point(cs, 0, 1, {1, 0, 0}, "rotateXYZ (90,90,0) of (0,1,0)");   // X 90: (0,0,1); Y 90: (1,0,0)
    expect_point(cs, 1, 0, {0, 1, 0}, "rotateZYX (90,90,0) of (1,0,0)");   // Y 90: (0,0,-1); X 90: (0,1,0)
    expect_point(cs, 2, 0, {0, 0, -1}, "rotateYZX (0,90,90) of (1,0,0)");  // Y 90: (0,0,-1); Z 90: same; X 0
    expect_point(cs, 3, 1, {0, 0, 1}, "rotateX 90 of (0,1,0)");
    expect_point(cs, 4, 0, {0, 1, 0}, "orient 90 about z of (1,0,0)");
    // Row-vector matrix: (1,0,0) * M = first row (0,1,0) + translation row (5,6,7).
    expect_point(cs, 5, 0, {5, 7, 7}, "transform");
    expect_point(cs, 6, 0, {0, -1, -1}, "!invert! translate");
    // Rotation about the pivot (1,0,0) then up 1: (1,0,0) stays, (0,1,0) -> (1-1, -1, 0) + (0,0,1).
    expect_point(cs, 7, 0, {1, 0, 1}, "pivot");
    expect_point(cs, 7, 1, {0, -1, 1}, "pivot second point");
}

TEST(UsdaXform, ResetXformStackIgnoresParentsAndOpsOutsideTheOrderAreIgnored)
{
    const auto r = read_usda_text("#usda 1.0\ndef Xform \"p\" {\n double3 xformOp:translate = (10, 0, 0)\n uniform token[] xformOpOrder = [\"xformOp:translate\"]\n" +
                                  curve("reset", " double3 xformOp:translate = (0, 0, 1)\n uniform token[] xformOpOrder = [\"!resetXformStack!\", \"xformOp:translate\"]") +
                                  curve("unordered", " double3 xformOp:translate = (0, 0, 5)") + "}\n");
    expect_point(r.curves, 0, 0, {1, 0, 1}, "reset");
    expect_point(r.curves, 1, 0, {11, 0, 0}, "an op not in xformOpOrder does nothing");
}

TEST(UsdaXform, MalformedOpsAreNamedByFileAndLine)
{
    const std::string ok = curve("fine", "");
    // Wrong arity (line 4), unknown op type, an order naming a missing op: the prim is skipped with a
    // warning; with no other prim the read fails with the same text.
    EXPECT_NE(usda_error("#usda 1.0\ndef Xform \"x\" {\n uniform token[] xformOpOrder = [\"xformOp:translate\"]\n double3 xformOp:translate = (1, 2)\n" + ok + "}\n")
                  .find("bad.usda:4: xform op 'xformOp:translate' of </x>: expected a 3-vector (3 numbers), found 2 numbers"),
              std::string::npos);
    EXPECT_NE(usda_error("#usda 1.0\n" + curve("c", " double3 xformOp:shear = (1, 2, 3)\n uniform token[] xformOpOrder = [\"xformOp:shear\"]"))
                  .find("bad.usda:3: xform op 'xformOp:shear' of </c>: unknown op type 'shear'"),
              std::string::npos);
    EXPECT_NE(usda_error("#usda 1.0\n" + curve("c", " uniform token[] xformOpOrder = [\"xformOp:scale\"]"))
                  .find("bad.usda:3: xformOpOrder of </c> names 'xformOp:scale', which the prim does not have"),
              std::string::npos);
    // Next to a good prim, the bad one is skipped and named.
    const auto r = read_usda_text("#usda 1.0\n" + curve("c", " double3 xformOp:shear = (1, 2, 3)\n uniform token[] xformOpOrder = [\"xformOp:shear\"]") + ok);
    EXPECT_EQ(r.curves.num_curves(), 1u);
    EXPECT_TRUE(r.warned("t.usda:3: xform op 'xformOp:shear' of </c>: unknown op type 'shear'"));
    EXPECT_TRUE(r.warned("; skipped </c> and the prims under it"));
}
