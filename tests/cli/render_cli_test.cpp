#include "fields/scalp_field.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "kernel/io/png.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace groom;
using groom::test::run_groom;

namespace {
/// Three straight curves in front of the head's face, one per strand value.
std::string write_curves_file(const test::TempDir& dir)
{
    std::vector<int64_t> counts{4, 4, 4};
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    auto strand = c.add<int32_t>(Domain::Curve, "strand");
    for (int i = 0; i < 3; ++i) {
        strand[i] = i;
        for (int k = 0; k < 4; ++k) P[i * 4 + k] = {-4.0f + 4.0f * float(i), 10.0f - 4.0f * float(k), 15.0f};
    }
    const std::string path = dir.file("curves.usda");
    write_curves(c, path);
    return path;
}
}  // namespace

TEST(RenderCli, HeadThenRenderWritesAPictureOfTheRequestedSize)
{
    test::TempDir dir;
    const auto head = run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "24"});
    ASSERT_EQ(head.exit_code, 0) << head.err;
    const PolygonSoup mesh = read_mesh(dir.file("head.obj"));
    EXPECT_EQ(mesh.points.size(), 2u + 23u * 48u);
    const std::string curves = write_curves_file(dir);
    const auto r = run_groom({"render", curves, "--scalp", dir.file("head.obj"), "-o", dir.file("a.png"), "--size", "64x48",
                              "--color-by", "strand", "--view", "three-quarter"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const RgbImage im = read_png(dir.file("a.png"));
    EXPECT_EQ(im.width, 64);
    EXPECT_EQ(im.height, 48);
    const auto sheet = run_groom({"render", curves, "--scalp", dir.file("head.obj"), "-o", dir.file("s.png"), "--size", "50",
                                  "--views", "front,left,top", "--quiet"});
    ASSERT_EQ(sheet.exit_code, 0) << sheet.err;
    EXPECT_TRUE(sheet.err.empty()) << sheet.err;
    const RgbImage s = read_png(dir.file("s.png"));
    EXPECT_EQ(s.width, 150);
    EXPECT_EQ(s.height, 50);
}

TEST(RenderCli, BadSizeCameraAndOutputAreUsageErrorsWithNoFile)
{
    test::TempDir dir;
    const std::string curves = write_curves_file(dir);
    const std::string out = dir.file("x.png");
    struct Case {
        std::vector<std::string> extra;
        std::string needle;
    };
    const std::vector<Case> cases{
        {{"--size", "0x0"}, "at least 1x1"},
        {{"--size", "99999999x9"}, "out of range"},
        {{"--size", "20000x20000"}, "at most 16384"},
        {{"--size", "16000x16000"}, "samples, more than"},
        {{"--size", "12xq"}, "WxH"},
        {{"--camera", "1,2,3,1,2,3"}, "eye and target must differ"},
        {{"--camera", "0,0,10,0,0,nan"}, "--camera"},
        {{"--camera", "0,0,10,0,0,0", "--fov", "180"}, "--fov must be in (0, 170)"},
        {{"--camera", "0,0,10,0,0"}, "expected 6"},
        {{"--view", "sideways"}, "unknown view"},
        {{"--color-by", "colour"}, "unknown --color-by"},
        {{"--color", "2,0,0"}, "--color components"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args{"render", curves, "-o", out};
        args.insert(args.end(), c.extra.begin(), c.extra.end());
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 2) << c.needle << ": " << r.err;
        EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.needle;
    }
    const auto not_png = run_groom({"render", curves, "-o", dir.file("x.jpg")});
    EXPECT_EQ(not_png.exit_code, 2);
    EXPECT_NE(not_png.err.find(".png"), std::string::npos) << not_png.err;
    const auto nothing = run_groom({"render", "-o", out});
    EXPECT_EQ(nothing.exit_code, 2);
    EXPECT_NE(nothing.err.find("nothing to draw"), std::string::npos) << nothing.err;
    const auto missing = run_groom({"render", dir.file("missing.usda"), "-o", out});
    EXPECT_EQ(missing.exit_code, 1) << missing.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(RenderCli, HeadRejectsBadOptions)
{
    test::TempDir dir;
    const auto r = run_groom({"head", "-o", dir.file("h.obj"), "--resolution", "2"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--resolution must be in [8, 1024] (got 2)"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("h.obj")));
}

TEST(RenderCli, AScalpVdbIsDrawnLikeItsMesh)
{
    // The same head from its mesh and from the .vdb level set made of it: the silhouettes agree to
    // within a couple of pixels (the extracted surface is exact to about a voxel).
    test::TempDir dir;
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "32"}).exit_code, 0);
    write_scalp(build_scalp(read_mesh(dir.file("head.obj"))), dir.file("head.vdb"));
    for (const char* name : {"head.obj", "head.vdb"}) {
        const auto r = run_groom({"render", "--scalp", dir.file(name), "-o", dir.file(std::string(name) + ".png"), "--size", "80",
                                  "--view", "left"});
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const RgbImage a = read_png(dir.file("head.obj.png")), b = read_png(dir.file("head.vdb.png"));
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    auto covered = [](const RgbImage& im, int x, int y) { return im.at(x, y)[0] < 200; };  // background is ~240
    int area_a = 0, area_b = 0, differ = 0;
    for (int y = 0; y < 80; ++y)
        for (int x = 0; x < 80; ++x) {
            area_a += covered(a, x, y);
            area_b += covered(b, x, y);
            differ += covered(a, x, y) != covered(b, x, y);
        }
    EXPECT_GT(area_a, 1000);
    EXPECT_NEAR(area_b, area_a, 0.05 * area_a);
    EXPECT_LT(differ, 0.08 * area_a);
}
