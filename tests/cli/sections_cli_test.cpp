#include "kernel/io/curve_io.h"
#include "ops/hair_region.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace groom;
using groom::test::run_groom;

TEST(SectionsCli, BoxBraidGuidesPartingsAndRootsOnTheDefaultHead)
{
    test::TempDir dir;
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "32"}).exit_code, 0);
    ASSERT_EQ(run_groom({"hairline", "--scalp", dir.file("head.obj"), "-o", dir.file("hl.usda")}).exit_code, 0);
    // No partings: the region reads only the hairline, never the surface.
    const HairRegion region(AnalyticSphere({0, 0, 0}, 1), read_curves(dir.file("hl.usda")), CurveSet(), HairRegionParams{});
    const auto r = run_groom({"sections", "--scalp", dir.file("head.obj"), "-o", dir.file("g.usda"), "--partings-out", dir.file("p.usda"),
                              "--roots-out", dir.file("r.usda"), "--roots", "500", "--cols", "6", "--length", "10", "--points", "12"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("sections in 6 bands (grid)"), std::string::npos) << r.err;
    const CurveSet g = read_curves(dir.file("g.usda"));
    const CurveSet p = read_curves(dir.file("p.usda"));
    const CurveSet roots = read_curves(dir.file("r.usda"));
    ASSERT_GE(g.num_curves(), 20u);
    EXPECT_GE(p.num_curves(), 5u + 14u);  // the 5 borders between bands and at least one cut per band
    EXPECT_EQ(roots.num_curves(), 500u);
    const auto section = g.find<int32_t>(Domain::Curve, "section");
    const auto root_section = roots.find<int32_t>(Domain::Curve, "section");
    ASSERT_EQ(section.size(), g.num_curves());
    ASSERT_EQ(root_section.size(), 500u);
    for (size_t c = 0; c < g.num_curves(); ++c) {
        EXPECT_EQ(section[c], int32_t(c));
        EXPECT_EQ(g.points_of(c).size(), 12u);
        // Roots inside the default hairline (the one `groom hairline` writes), tips hanging below them.
        const float3 root = g.positions()[g.points_of(c).begin], tip = g.positions()[g.points_of(c).end - 1];
        EXPECT_TRUE(region.inside_hairline(root)) << "guide " << c;
        EXPECT_LT(tip.y, root.y - 3.0f);
    }
    for (size_t i = 0; i < roots.num_curves(); ++i) {
        EXPECT_LT(size_t(root_section[i]), g.num_curves());
        EXPECT_TRUE(region.inside_hairline(roots.positions()[roots.points_of(i).begin]));
    }
}

TEST(SectionsCli, HairlineFileRowsAndRadial)
{
    test::TempDir dir;
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "32"}).exit_code, 0);
    ASSERT_EQ(run_groom({"hairline", "--scalp", dir.file("head.obj"), "-o", dir.file("hl.usda")}).exit_code, 0);
    const auto rows = run_groom({"sections", "--scalp", dir.file("head.obj"), "--hairline", dir.file("hl.usda"), "-o", dir.file("rows.usda"),
                                 "--layout", "rows", "--rows", "5"});
    ASSERT_EQ(rows.exit_code, 0) << rows.err;
    EXPECT_EQ(read_curves(dir.file("rows.usda")).num_curves(), 5u);
    const auto radial = run_groom({"sections", "--scalp", dir.file("head.obj"), "-o", dir.file("radial.usda"), "--layout", "radial",
                                   "--wedges", "9"});
    ASSERT_EQ(radial.exit_code, 0) << radial.err;
    EXPECT_EQ(read_curves(dir.file("radial.usda")).num_curves(), 9u);
}

// Scene units: the default head in millimetres (scaled by 10) with --units-per-cm 10 gets the
// guides of the centimetre head, scaled by 10 (every default length is centimetres: the 30 cm free
// length hung 30 units below a head in millimetres before); typed lengths stay scene units.
TEST(SectionsCli, UnitsPerCmScalesTheDefaultLengths)
{
    test::TempDir dir;
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "32"}).exit_code, 0);
    ASSERT_EQ(run_groom({"head", "-o", dir.file("mm.obj"), "--resolution", "32", "--scale", "10"}).exit_code, 0);
    auto sections = [&](const std::string& scalp, const std::string& out, std::vector<std::string> extra) {
        std::vector<std::string> args{"sections", "--scalp", scalp, "-o", dir.file(out), "--cols", "4", "--points", "8", "-q"};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return read_curves(dir.file(out));
    };
    const CurveSet cm = sections(dir.file("head.obj"), "cm.usda", {});
    const CurveSet mm = sections(dir.file("mm.obj"), "mm.usda", {"--units-per-cm", "10"});
    ASSERT_EQ(cm.num_curves(), mm.num_curves());
    double worst = 0.0, reach = 0.0;
    for (size_t c = 0; c < cm.num_curves(); ++c) {
        const float3 a = cm.positions()[cm.points_of(c).end - 1] * 10.0f, b = mm.positions()[mm.points_of(c).end - 1];
        worst = std::max(worst, double(distance(a, b)));
        reach = std::max(reach, double(distance(mm.positions()[mm.points_of(c).begin], b)));
    }
    EXPECT_GT(reach, 100.0);        // the free part hangs 30 cm = 300 mm below (more than 100 mm)
    EXPECT_LT(worst, 0.02 * reach);  // the same guides, up to the two level sets' voxels
    // What the user typed is scene units: --length 50 in the millimetre head is 50 mm.
    const CurveSet typed = sections(dir.file("mm.obj"), "typed.usda", {"--units-per-cm", "10", "--length", "50"});
    double longest = 0.0;
    for (size_t c = 0; c < typed.num_curves(); ++c) {
        longest = std::max(longest, double(distance(typed.positions()[typed.points_of(c).begin], typed.positions()[typed.points_of(c).end - 1])));
    }
    EXPECT_LT(longest, 120.0);
    const auto bad = run_groom({"sections", "--scalp", dir.file("head.obj"), "-o", dir.file("x.usda"), "--units-per-cm", "0"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--units-per-cm must be a finite number > 0 (got 0)"), std::string::npos) << bad.err;
}

TEST(SectionsCli, BadOptionsAreUsageErrorsNamingTheOption)
{
    test::TempDir dir;
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "16"}).exit_code, 0);
    const std::string head = dir.file("head.obj"), out = dir.file("g.usda");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"--layout", "rows", "--cols", "3"}, "--cols applies to the grid layout only (got 3 with --layout rows)"},
        {{"--layout", "hex"}, "--layout must be grid, rows or radial (got 'hex')"},
        {{"--wedges", "5"}, "--wedges applies to the radial layout only"},
        {{"--parting-gap", "0"}, "--parting-gap must be a finite number > 0 (got 0)"},
        {{"--points", "2"}, "--points must be in [4, 100000] (got 2)"},
        {{"--jitter", "90"}, "--jitter must be in [0, 45] degrees (got 90)"},
        {{"--guide", "sideways"}, "--guide must be auto, hang or along (got 'sideways')"},
        {{"--roots", "10"}, "--roots needs --roots-out"},
        {{"--hang", "0,-1"}, "--hang"},
    };
    for (const auto& [extra, message] : cases) {
        std::vector<std::string> args{"sections", "--scalp", head, "-o", out};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 2) << extra[0] << ": " << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << extra[0];
    }
    // A hairline file that is not one closed curve: a failure naming it, no output.
    test::write_text(dir.file("two.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nl 1 2\nl 3 4\n");
    const auto bad = run_groom({"sections", "--scalp", head, "-o", out, "--hairline", dir.file("two.obj")});
    EXPECT_EQ(bad.exit_code, 1) << bad.err;
    EXPECT_NE(bad.err.find("hairline"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // A hairline made on another head (a small one below this one's chin): named, with why.
    std::string other_obj;
    for (int i = 0; i < 16; ++i) {
        const double a = 6.283185307179586 * i / 16.0;
        other_obj += "v " + std::to_string(std::cos(a)) + " -30 " + std::to_string(std::sin(a)) + "\n";
    }
    other_obj += "l";
    for (int i = 1; i <= 16; ++i) other_obj += " " + std::to_string(i);
    test::write_text(dir.file("other.obj"), other_obj + " 1\n");
    const auto other = run_groom({"sections", "--scalp", head, "-o", out, "--hairline", dir.file("other.obj")});
    EXPECT_EQ(other.exit_code, 1) << other.err;
    EXPECT_NE(other.err.find("other.obj: sections: the hairline's centroid"), std::string::npos) << other.err;
    EXPECT_NE(other.err.find("made on another head"), std::string::npos) << other.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // Two outputs on one file.
    const auto same = run_groom({"sections", "--scalp", head, "-o", out, "--partings-out", out});
    EXPECT_EQ(same.exit_code, 2) << same.err;
}
