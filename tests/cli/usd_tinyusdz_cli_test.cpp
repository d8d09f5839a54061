// groom's USD reader against an independent implementation (tinyusdz, scripts/check-usd-tinyusdz.sh):
// the same world matrices for every xform op, the same curves from a composed file as from
// tinyusdz's flattening of it. Skipped where node or a cached tinyusdz is absent (no network).
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <sys/wait.h>

using groom::test::TempDir;
using groom::test::read_bytes;
using groom::test::write_text;

namespace {

int check(const std::string& args, const std::string& log)
{
    const std::string cmd = "GROOM='" GROOM_BINARY "' bash '" GROOM_SOURCE_DIR "/scripts/check-usd-tinyusdz.sh' " + args + " > '" + log + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(UsdTinyusdz, XformOpsGiveTheSameWorldMatricesAsTinyusdz)
{
    TempDir dir;
    const int rc = check("xforms", dir.file("log"));
    if (rc == 77) GTEST_SKIP() << read_bytes(dir.file("log"));
    EXPECT_EQ(rc, 0) << read_bytes(dir.file("log"));
    EXPECT_NE(read_bytes(dir.file("log")).find("17 transforms"), std::string::npos) << read_bytes(dir.file("log"));
}

TEST(UsdTinyusdz, ComposedFileReadsLikeTinyusdzsFlattening)
{
    TempDir dir;
    write_text(dir.file("arcs.usda"), R"(#usda 1.0
class Xform "Prototypes" {
    def Xform "Groom" {
        float3 xformOp:scale = (1, 2, 1)
        uniform token[] xformOpOrder = ["xformOp:scale"]
        def BasisCurves "hair" {
            int[] curveVertexCounts = [4, 4]
            point3f[] points = [(0,0,0), (0,1,0), (1,1,0), (1,2,0), (1,0,0), (1,1,0), (2,1,0), (2,2,0)]
        }
    }
}
def Xform "inst0" (instanceable = true; references = </Prototypes/Groom>) {
}
def Xform "inst1" (instanceable = true; prepend references = </Prototypes/Groom>) {
    double3 xformOp:translate = (10, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def Xform "inst2" (instanceable = true; payload = </Prototypes/Groom>) {
    double3 xformOp:translate = (20, 0, 0)
    float xformOp:rotateZ = 90
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateZ"]
    over "hair" {
        point3f[] points = [(0,0,1), (0,1,1), (1,1,1), (1,2,1), (1,0,1), (1,1,1), (2,1,1), (2,2,1)]
    }
}
def Xform "groom" (
    variants = {
        string density = "dense"
    }
    prepend variantSets = "density"
) {
    variantSet "density" = {
        "sparse" {
            def BasisCurves "hair" {
                uniform token type = "linear"
                int[] curveVertexCounts = [2]
                point3f[] points = [(0,0,0), (0,1,0)]
            }
        }
        "dense" {
            def BasisCurves "hair" {
                uniform token type = "linear"
                int[] curveVertexCounts = [2, 2]
                point3f[] points = [(0,0,5), (0,1,5), (1,0,5), (1,1,5)]
            }
        }
    }
}
class "I" {
    uniform token type = "linear"
}
def BasisCurves "inh" (inherits = </I>) {
    int[] curveVertexCounts = [2]
    point3f[] points = [(0,0,9), (0,1,9)]
}
)");
    const int rc = check("compose '" + dir.file("arcs.usda") + "'", dir.file("log"));
    if (rc == 77) GTEST_SKIP() << read_bytes(dir.file("log"));
    EXPECT_EQ(rc, 0) << read_bytes(dir.file("log"));
    EXPECT_NE(read_bytes(dir.file("log")).find("9 curves from the file, 9 from tinyusdz's flattening: same"), std::string::npos) << read_bytes(dir.file("log"));
}
