// The `.usd` extension holds either encoding: text (sniffed by its `#usda` header) is read like
// .usda; a binary crate file (`PXR-USDC`) is refused by name with the command that converts it.
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace groom;
using groom::test::TempDir;
using groom::test::write_text;

TEST(UsdExtension, TextUsdIsReadAndCrateIsRefusedByName)
{
    TempDir dir;
    write_text(dir.file("text.usd"), "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
                                     " point3f[] points = [(0,0,0), (0,1,0)]\n}\n");
    EXPECT_EQ(read_curves(dir.file("text.usd")).num_curves(), 1u);
    write_text(dir.file("crate.usd"), std::string("PXR-USDC") + std::string(80, '\0'));
    try {
        read_curves(dir.file("crate.usd"));
        FAIL() << "a crate file was read";
    }
    catch (const ParseError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("crate.usd: a binary USD crate file"), std::string::npos) << m;
        EXPECT_NE(m.find("no OpenUSD package"), std::string::npos) << m;
        EXPECT_NE(m.find("usdcat " + dir.file("crate.usd") + " -o "), std::string::npos) << m;
    }
    write_text(dir.file("crate.usdc"), std::string("PXR-USDC") + std::string(80, '\0'));
    try {
        read_curves(dir.file("crate.usdc"));
        FAIL() << "a .usdc file was read";
    }
    catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("usdcat FILE.usdc -o FILE.usda"), std::string::npos) << e.what();
    }
}
