#include "kernel/io/curve_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace groom;
using groom::test::run_groom;

TEST(CornrowGuidesCli, GuidesAndTailsOnTheDefaultHead)
{
    test::TempDir dir;
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "32"}).exit_code, 0);
    const auto r = run_groom({"cornrow-guides", "--scalp", dir.file("head.obj"), "-o", dir.file("g.usda"), "--count", "6", "--samples",
                              "20", "--tails-out", dir.file("t.usda"), "--tail-length", "8"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet g = read_curves(dir.file("g.usda"));
    const CurveSet t = read_curves(dir.file("t.usda"));
    EXPECT_EQ(g.num_curves(), 6u);
    EXPECT_EQ(g.num_points(), 120u);
    EXPECT_EQ(t.num_curves(), 6u);
    // Roots at the front (the face looks along +Z), tips at the back, all above the ears.
    for (size_t c = 0; c < g.num_curves(); ++c) {
        const IndexRange pts = g.points_of(c);
        EXPECT_GT(g.positions()[pts.begin].z, 3.0f);
        EXPECT_LT(g.positions()[pts.end - 1].z, -3.0f);
        EXPECT_EQ(t.positions()[t.points_of(c).begin], g.positions()[pts.end - 1]);
    }
}

TEST(CornrowGuidesCli, BadOptionsAreUsageErrors)
{
    test::TempDir dir;
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "16"}).exit_code, 0);
    const auto r = run_groom({"cornrow-guides", "--scalp", dir.file("head.obj"), "-o", dir.file("g.usda"), "--count", "0"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--count must be in [1, 256] (got 0)"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("g.usda")));
    const auto onto_input = run_groom({"cornrow-guides", "--scalp", dir.file("head.obj"), "-o", dir.file("head.obj")});
    EXPECT_EQ(onto_input.exit_code, 2) << onto_input.err;
}
