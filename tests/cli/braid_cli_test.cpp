// `groom braid` and `groom populate` end to end: files in, files out, exit codes and messages.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/math/polyline.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <set>

using namespace groom;
using groom::test::run_groom;
using groom::test::TempDir;

namespace {

/// Two straight guides and a bent one, as OBJ polylines.
std::string guides_obj(const TempDir& dir)
{
    const std::string path = dir.file("guides.obj");
    groom::test::write_text(path,
                            "v 0 0 0\nv 0 5 0\nv 0 10 0\nv 0 15 0\n"
                            "v 3 0 0\nv 3 5 0\nv 3 10 0\nv 3 12 0\n"
                            "v 6 0 0\nv 6 5 1\nv 7 10 2\nv 9 14 3\n"
                            "l 1 2 3 4\nl 5 6 7 8\nl 9 10 11 12\n");
    return path;
}

/// A UV sphere of radius r about the origin as an OBJ mesh (outward-facing triangles).
std::string sphere_obj(const TempDir& dir, float r, int rings = 48, int segments = 96)
{
    const std::string path = dir.file("sphere.obj");
    std::ofstream f(path);
    f << "v 0 " << r << " 0\n";
    for (int i = 1; i < rings; ++i) {
        const double th = std::numbers::pi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double ph = 2.0 * std::numbers::pi * j / segments;
            f << "v " << r * std::sin(th) * std::cos(ph) << " " << r * std::cos(th) << " " << r * std::sin(th) * std::sin(ph) << "\n";
        }
    }
    f << "v 0 " << -r << " 0\n";
    const int south = 1 + (rings - 1) * segments + 1;
    const auto v = [&](int ring, int j) { return 2 + (ring - 1) * segments + (j % segments); };
    for (int j = 0; j < segments; ++j) f << "f 1 " << v(1, j + 1) << " " << v(1, j) << "\n";
    for (int i = 1; i + 1 < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            f << "f " << v(i, j) << " " << v(i, j + 1) << " " << v(i + 1, j + 1) << "\n";
            f << "f " << v(i, j) << " " << v(i + 1, j + 1) << " " << v(i + 1, j) << "\n";
        }
    }
    for (int j = 0; j < segments; ++j) f << "f " << south << " " << v(rings - 1, j) << " " << v(rings - 1, j + 1) << "\n";
    return path;
}

}  // namespace

TEST(BraidCli, BraidsGuidesIntoStrandsWithAttributes)
{
    TempDir dir;
    const std::string in = guides_obj(dir), out = dir.file("braids.usda");
    const auto r = run_groom({"braid", in, "-o", out, "--strands", "4", "--frequency", "3", "--width", "0.5", "--height", "0.2",
                              "--samples", "40", "--taper", "1,0.6", "--root-amplitude", "1", "--tip-amplitude", "0.5"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("braid: 3 guides -> 12 strands (4 each, plait) = 12 curves, 480 points"), std::string::npos) << r.err;
    const CurveSet cs = read_curves(out);
    ASSERT_EQ(cs.num_curves(), 12u);
    const auto guide = cs.find<int32_t>(Domain::Curve, "guide");
    const auto strand = cs.find<int32_t>(Domain::Curve, "strand");
    ASSERT_EQ(guide.size(), 12u);
    ASSERT_EQ(strand.size(), 12u);
    ASSERT_EQ(cs.find<float>(Domain::Point, attr::width).size(), cs.num_points());
    const std::vector<int64_t> ids = cs.curve_ids();
    EXPECT_EQ(std::set<int64_t>(ids.begin(), ids.end()).size(), 12u);
    for (size_t c = 0; c < 12; ++c) {
        EXPECT_EQ(guide[c], int32_t(c / 4));
        EXPECT_EQ(strand[c], int32_t(c % 4));
        EXPECT_EQ(cs.points_in(c), 40);
    }
    // Guide 0 runs up +Y from the origin: strands start within the root's amplitude of it.
    EXPECT_LE(length(cs.positions()[0]), 0.55f);
    EXPECT_GT(cs.positions()[39].y, 14.0f);
}

TEST(BraidCli, FibersAndKnotLength)
{
    TempDir dir;
    const std::string in = guides_obj(dir), out = dir.file("fibers.obj");
    const auto r = run_groom({"braid", in, "-o", out, "--knot-length", "2.5", "--width", "0.6", "--fibers", "5", "--fiber-radius",
                              "0.1", "--seed", "4", "--samples", "16"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet cs = read_curves(out);
    EXPECT_EQ(cs.num_curves(), 3u * 3u * 5u);
    EXPECT_EQ(cs.num_points(), 3u * 3u * 5u * 16u);
}

TEST(BraidCli, SameBytesForAnyThreadCount)
{
    TempDir dir;
    const std::string in = guides_obj(dir), a = dir.file("a.usda"), b = dir.file("b.usda");
    const std::vector<std::string> args{"braid", in, "--fibers", "30", "--seed", "8", "--knot-bias", "0.3"};
    auto with = [&](const std::string& out, const std::string& threads) {
        std::vector<std::string> v = args;
        v.insert(v.end(), {"-o", out, "--threads", threads});
        return run_groom(v);
    };
    ASSERT_EQ(with(a, "1").exit_code, 0);
    ASSERT_EQ(with(b, "2").exit_code, 0);
    const std::string ba = groom::test::read_bytes(a), bb = groom::test::read_bytes(b);
    ASSERT_GT(ba.size(), 1000u);
    EXPECT_TRUE(ba == bb) << "outputs differ between --threads 1 and --threads 2";
}

// Every pattern from the command line, with the ends: strands, fibers, a tie with kind = 1.
TEST(BraidCli, PatternsAndEnds)
{
    TempDir dir;
    const std::string in = guides_obj(dir);
    for (const std::string pattern : {"plait", "fishtail", "twist", "rope", "round", "lissajous"}) {
        const std::string out = dir.file(pattern + ".usda");
        const auto r = run_groom({"braid", in, "-o", out, "--pattern", pattern, "--fibers", "4", "--loose-length", "0.5", "--tie",
                                  "0.7", "--flyaways", "0.1", "--feed-in", "0.2"});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_NE(r.err.find(", " + pattern + ")"), std::string::npos) << r.err;
        const CurveSet cs = read_curves(out);
        const auto kind = cs.find<int32_t>(Domain::Curve, "kind");
        ASSERT_EQ(kind.size(), cs.num_curves());
        EXPECT_EQ(std::count(kind.begin(), kind.end(), 1), 3) << pattern;  // one tie per guide
    }
}

TEST(BraidCli, RejectsInvalidOptionsWithUsageErrorAndNoOutput)
{
    TempDir dir;
    const std::string in = guides_obj(dir), out = dir.file("x.usda");
    const auto expect_usage = [&](std::vector<std::string> extra, const std::string& message) {
        std::vector<std::string> args{"braid", in, "-o", out};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 2) << message << "\n" << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << "stderr: " << r.err;
        EXPECT_FALSE(std::filesystem::exists(out));
    };
    expect_usage({"--strands", "1"}, "braid: --strands must be >= 2 (got 1)");
    expect_usage({"--frequency", "-2"}, "braid: --frequency must be a finite number >= 0 and <= 1e+15 (got -2)");
    expect_usage({"--width", "-1"}, "braid: --width must be a finite number >= 0 and <= 1e+15 (got -1)");
    expect_usage({"--height", "-1"}, "braid: --height must be a finite number >= 0 and <= 1e+15 (got -1)");
    expect_usage({"--frequency", "2", "--knot-length", "1"}, "braid: --frequency and --knot-length are exclusive");
    expect_usage({"--orient", "sideways"}, "braid: --orient must be frame or scalp (got 'sideways')");
    expect_usage({"--orient", "scalp"}, "braid: --orient scalp needs a scalp");
    expect_usage({"--taper", "1,x"}, "braid: --taper: expected a comma-separated list of numbers");
    expect_usage({"--knot-bias", "2"}, "braid: --knot-bias must be in (-1, 1) (got 2)");
    expect_usage({"--pattern", "herringbone"},
                 "braid: --pattern must be one of plait|fishtail|twist|rope|round|lissajous (got 'herringbone')");
    expect_usage({"--hand", "left"}, "braid: --hand must be under, over or auto (got 'left')");
    expect_usage({"--pattern", "round", "--strands", "3"}, "braid: --pattern round needs an even --strands >= 4 (got --strands 3)");
    expect_usage({"--feed-in", "0.5"}, "braid: --feed-in moves fibers; give --fibers M > 0");
    // -o onto the input is refused.
    const auto r = run_groom({"braid", in, "-o", in});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("refusing to overwrite"), std::string::npos) << r.err;
}

// Cornrows on a sphere mesh (converted by load_scalp): y along the scalp normal, every point outside.
TEST(BraidCli, CornrowsOnAScalpMeshStayOutsideIt)
{
    TempDir dir;
    const float R = 10.0f;
    const std::string scalp = sphere_obj(dir, R);
    const std::string guides = dir.file("rows.obj");
    {
        std::ofstream f(guides);
        for (int g = 0; g < 3; ++g) {
            for (int k = 0; k <= 40; ++k) {
                const double lat = (70.0 - 50.0 * k / 40.0) * std::numbers::pi / 180.0, lon = (g * 20.0) * std::numbers::pi / 180.0;
                f << "v " << R * std::cos(lat) * std::cos(lon) << " " << R * std::sin(lat) << " " << R * std::cos(lat) * std::sin(lon) << "\n";
            }
        }
        for (int g = 0; g < 3; ++g) {
            f << "l";
            for (int k = 1; k <= 41; ++k) f << " " << g * 41 + k;
            f << "\n";
        }
    }
    const std::string out = dir.file("cornrows.usda");
    const auto r = run_groom({"braid", guides, "-o", out, "--scalp", scalp, "--orient", "scalp", "--frequency", "5", "--width", "0.6",
                              "--height", "0.3", "--clearance", "0.05", "--samples", "81"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("braid: scalp: lifted"), std::string::npos) << r.err;
    const CurveSet cs = read_curves(out);
    ASSERT_EQ(cs.num_curves(), 9u);
    // The mesh is inscribed in the sphere (chords sag inside by < R (1 - cos(pi / 48))): every point
    // clears the analytic sphere too, up to the level set's voxel-scale error.
    const auto W = cs.find<float>(Domain::Point, attr::width);
    for (size_t q = 0; q < cs.num_points(); ++q) {
        EXPECT_GT(length(cs.positions()[q]) - 0.5f * W[q], R - 0.03f) << q;
    }
}

TEST(PopulateCli, FillsADiscAroundEachCurve)
{
    TempDir dir;
    const std::string in = guides_obj(dir), out = dir.file("pop.usda");
    const auto r = run_groom({"populate", in, "-o", out, "--count", "25", "--radius", "0.3", "--seed", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet src = read_curves(in), cs = read_curves(out);
    ASSERT_EQ(cs.num_curves(), 75u);
    const auto fiber = cs.find<int32_t>(Domain::Curve, "fiber");
    ASSERT_EQ(fiber.size(), 75u);
    // Guide 0 is the straight +Y line through the origin: its fibers are within 0.3 of it.
    for (size_t c = 0; c < 25; ++c) {
        EXPECT_EQ(fiber[c], int32_t(c));
        for (int64_t q = cs.points_of(c).begin; q < cs.points_of(c).end; ++q) {
            const float3 p = cs.positions()[q];
            EXPECT_LE(std::hypot(p.x, p.z), 0.3f + 1e-5f);
        }
    }
    const auto bad = run_groom({"populate", in, "-o", out, "--count", "0", "--radius", "1", "--force"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("populate: --count must be in [1, 1000000] (got 0)"), std::string::npos) << bad.err;
}
