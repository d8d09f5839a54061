// The CLI side of the USD reader: --prim on the commands that read curves, the reader's warnings on
// stderr, a crate file refused with the command that converts it, no output left on failure.
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>

using groom::test::TempDir;
using groom::test::run_groom;
using groom::test::write_text;

namespace {

const char* kFile = R"(#usda 1.0
def Xform "left" {
    double3 xformOp:translate = (10, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
    def BasisCurves "a" {
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(0,0,0), (0,1,0)]
    }
}
def Xform "right" {
    def BasisCurves "b" {
        uniform token type = "linear"
        int[] curveVertexCounts = [3, 2]
        point3f[] points = [(0,0,0), (0,1,0), (0,2,0), (1,0,0), (1,1,0)]
    }
    def BasisCurves "broken" {
        uniform token type = "linear"
        int[] curveVertexCounts = [9]
        point3f[] points = [(0,0,0)]
    }
}
)";

}  // namespace

TEST(UsdPrimCli, PrimPicksPrimsAndWarningsReachStderr)
{
    TempDir dir;
    write_text(dir.file("g.usda"), kFile);
    auto r = run_groom({"info", dir.file("g.usda"), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("\"curves\": 3"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("warning: "), std::string::npos);
    EXPECT_NE(r.err.find("g.usda:19: curveVertexCounts sum to 9 but 'points' (line 20) has 1 points; prim </right/broken> skipped"), std::string::npos) << r.err;

    r = run_groom({"info", dir.file("g.usda"), "--json", "--prim", "/left"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("\"curves\": 1"), std::string::npos) << r.out;
    EXPECT_EQ(r.err, "");
    // The translate of /left applies: x = 10.
    r = run_groom({"convert", dir.file("g.usda"), "--prim", "/left/", "--prim", "/right/b", "-o", dir.file("o.obj"), "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string obj = groom::test::read_bytes(dir.file("o.obj"));
    EXPECT_EQ(obj.find("v 10 0 0\nv 10 1 0\n"), obj.find("v ")) << obj;

    r = run_groom({"convert", dir.file("g.usda"), "--prim", "/nope", "-o", dir.file("p.obj")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--prim /nope: no such prim in the file"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("p.obj")));
    r = run_groom({"convert", dir.file("g.usda"), "--prim", "left", "-o", dir.file("p.obj")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--prim left: expected an absolute prim path"), std::string::npos) << r.err;
    r = run_groom({"convert", dir.file("o.obj"), "--prim", "/left", "-o", dir.file("p.obj")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--prim picks prims of a USD file"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("p.obj")));
}

TEST(UsdPrimCli, CrateFilesAreRefusedWithTheConversionCommand)
{
    TempDir dir;
    write_text(dir.file("c.usd"), std::string("PXR-USDC") + std::string(64, '\0'));
    const auto r = run_groom({"info", dir.file("c.usd")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("c.usd: a binary USD crate file"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("usdcat " + dir.file("c.usd") + " -o " + dir.file("c.usd") + "a"), std::string::npos) << r.err;
}
