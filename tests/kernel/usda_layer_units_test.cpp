// The layer's upAxis and metersPerUnit become the curves' `up_axis` and `units` (what `groom
// transform` converts from) and are written back to the layer, not as primvars: a Z-up file, as
// Blender writes, had been written out Y-up without a word (a trial).
#include "tests/kernel/usda_test_util.h"

#include "kernel/io/curve_io.h"
#include "kernel/error.h"

#include <cmath>

using namespace groom;
using groom::test::read_bytes;
using groom::test::read_usda_text;
using groom::test::TempDir;

namespace {

std::string layer(const std::string& metadata)
{
    return "#usda 1.0\n(\n" + metadata + ")\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
           " point3f[] points = [(0,0,0),(0,0,1)]\n}\n";
}

}  // namespace

TEST(UsdaLayerUnits, UpAxisAndMetersPerUnitAreKeptThroughReadAndWrite)
{
    const auto z = read_usda_text(layer("    metersPerUnit = 1\n    upAxis = \"Z\"\n"));
    EXPECT_EQ(z.curves.detail_string("up_axis"), "Z");
    EXPECT_EQ(z.curves.detail_string("units"), "m");
    TempDir dir;
    write_curves(z.curves, dir.file("out.usda"));
    const std::string out = read_bytes(dir.file("out.usda"));
    EXPECT_NE(out.find("upAxis = \"Z\""), std::string::npos) << out;
    EXPECT_NE(out.find("metersPerUnit = 1\n"), std::string::npos) << out;
    EXPECT_EQ(out.find("primvars:up_axis"), std::string::npos) << out;
    EXPECT_EQ(out.find("primvars:units"), std::string::npos) << out;
    // Read back and written again: the same bytes.
    write_curves(read_curves(dir.file("out.usda")), dir.file("again.usda"));
    EXPECT_EQ(read_bytes(dir.file("again.usda")), out);
    // Each unit groom names, within float rounding of its metres.
    for (const auto& [mpu, name] : {std::pair<std::string, std::string>{"0.001", "mm"}, {"0.01", "cm"}, {"0.0254", "in"}, {"0.009999999776", "cm"}}) {
        EXPECT_EQ(read_usda_text(layer("    metersPerUnit = " + mpu + "\n")).curves.detail_string("units"), name) << mpu;
    }
}

TEST(UsdaLayerUnits, YUpSetsNothingAndOtherUnitsAreKeptAsNumbers)
{
    // Y-up and no unit: nothing (files groom writes say Y and read back must write the same bytes).
    const auto y = read_usda_text(layer("    upAxis = \"Y\"\n"));
    EXPECT_TRUE(y.curves.detail_string("up_axis").empty());
    EXPECT_TRUE(y.curves.detail_string("units").empty());
    // A unit no name fits is kept as its number of metres, written back, and converted from by
    // transform: feet had been dropped, the file written without a unit read as cm, 30x off (a trial).
    const auto ft = read_usda_text(layer("    metersPerUnit = 0.3048\n"));
    EXPECT_EQ(ft.curves.detail_string("units"), "0.3048");
    TempDir feet;
    write_curves(ft.curves, feet.file("ft.usda"));
    EXPECT_NE(read_bytes(feet.file("ft.usda")).find("metersPerUnit = 0.3048\n"), std::string::npos) << read_bytes(feet.file("ft.usda"));
    EXPECT_EQ(read_curves(feet.file("ft.usda")).detail_string("units"), "0.3048");  // (transform converts from it: TransformTest)
    // Malformed, refused by line, as USD's parser refuses them (they had been skipped: an unquoted Z
    // read as Y-up).
    EXPECT_NE(test::usda_error(layer("    upAxis = Z\n")).find("expected upAxis = \"Y\" or \"Z\" (a quoted token)"), std::string::npos);
    EXPECT_NE(test::usda_error(layer("    upAxis = 1\n")).find("expected upAxis"), std::string::npos);
    for (const char* bad : {"nan", "inf", "\"cm\"", "0"}) {
        const std::string e = test::usda_error(layer(std::string("    metersPerUnit = ") + bad + "\n"));
        EXPECT_NE(e.find(":3:"), std::string::npos) << bad << ": " << e;
        EXPECT_NE(e.find("expected metersPerUnit > 0, a finite number"), std::string::npos) << bad << ": " << e;
    }
    // An up_axis said Y (by transform) is kept through a write and a read (a review: it was dropped).
    CurveSet said = read_usda_text(layer("")).curves;
    said.set_detail_string("up_axis", "Y");
    TempDir dir;
    write_curves(said, dir.file("y.usda"));
    EXPECT_EQ(read_curves(dir.file("y.usda")).detail_string("up_axis"), "Y");
    const auto x = read_usda_text(layer("    upAxis = \"X\"\n"));
    EXPECT_TRUE(x.warned("upAxis 'X' is neither Y nor Z"));
    EXPECT_NE(test::usda_error(layer("    metersPerUnit = -1\n")).find("expected metersPerUnit > 0"), std::string::npos);
}

// Numbers past float's range were read as inf without a word, in USD primvars and in the detail
// comments of .obj and .ply (a trial); `inf` written as such stays inf. A malformed detail comment
// names its line.
TEST(UsdaLayerUnits, NumbersPastFloatsRangeAreRefused)
{
    const std::string prim = "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
                             " point3f[] points = [(0,0,0),(0,0,1)]\n";
    EXPECT_NE(test::usda_error(prim + " float[] primvars:w = [1, 1e40] (interpolation = \"vertex\")\n}\n").find("expected a number within float's range"),
              std::string::npos);
    EXPECT_TRUE(std::isinf(read_usda_text(prim + " float[] primvars:w = [1, inf] (interpolation = \"vertex\")\n}\n").curves.find<float>(Domain::Point, "w")[1]));
    TempDir dir;
    test::write_text(dir.file("d.obj"), "v 0 0 0\nv 0 0 1\n# groom detail foo float 1e40\nl 1 2\n");
    try {
        read_curves(dir.file("d.obj"));
        ADD_FAILURE() << "a detail of 1e40 was read";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("d.obj:3: malformed '# groom detail foo float 1e40'"), std::string::npos) << e.what();
    }
}
