// `groom partition` end to end: files in, files out, exit codes and messages.
#include "test_support.h"

#include "kernel/io/curve_io.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace groom;
using groom::test::run_groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

/// A UV sphere of radius 1 about the origin (48 x 96 quads, outward winding) as an OBJ mesh.
std::string sphere_obj(const TempDir& dir)
{
    const int rings = 48, segs = 96;
    std::ostringstream s;
    s << "v 0 1 0\n";
    for (int i = 1; i < rings; ++i) {
        const double lat = M_PI / 2 - M_PI * i / rings;
        for (int j = 0; j < segs; ++j) {
            const double lon = 2 * M_PI * j / segs;
            s << "v " << std::cos(lat) * std::cos(lon) << " " << std::sin(lat) << " " << -std::cos(lat) * std::sin(lon) << "\n";
        }
    }
    s << "v 0 -1 0\n";
    auto ring = [&](int i, int j) { return 2 + (i - 1) * segs + (j % segs); };  // 1-based OBJ index
    const int bottom = 2 + (rings - 1) * segs;
    for (int j = 0; j < segs; ++j) s << "f 1 " << ring(1, j) << " " << ring(1, j + 1) << "\n";
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < segs; ++j) s << "f " << ring(i, j) << " " << ring(i + 1, j) << " " << ring(i + 1, j + 1) << " " << ring(i, j + 1) << "\n";
    for (int j = 0; j < segs; ++j) s << "f " << ring(rings - 1, j) << " " << bottom << " " << ring(rings - 1, j + 1) << "\n";
    const std::string path = dir.file("sphere.obj");
    write_text(path, s.str());
    return path;
}

/// Three meridian guides 0.3 rad apart (longitudes -0.3, 0, 0.3), 2% above the unit sphere,
/// running north from latitude -0.5 to 0.5, as OBJ polylines.
std::string guides_obj(const TempDir& dir)
{
    std::ostringstream s;
    const int n = 41;
    for (int g = 0; g < 3; ++g) {
        const double lon = -0.3 + 0.3 * g;
        for (int i = 0; i < n; ++i) {
            const double lat = -0.5 + 1.0 * i / (n - 1);
            s << "v " << 1.02 * std::cos(lat) * std::cos(lon) << " " << 1.02 * std::sin(lat) << " " << 1.02 * std::cos(lat) * std::sin(lon)
              << "\n";
        }
    }
    for (int g = 0; g < 3; ++g) {
        s << "l";
        for (int i = 0; i < n; ++i) s << " " << g * n + i + 1;
        s << "\n";
    }
    const std::string path = dir.file("guides.obj");
    write_text(path, s.str());
    return path;
}

bool contains(const std::string& text, const std::string& needle) { return text.find(needle) != std::string::npos; }

}  // namespace

TEST(PartitionCli, MakesEdgeHairsRootedOnTheScalpWithTheirAttributes)
{
    TempDir dir;
    const std::string scalp = sphere_obj(dir), guides = guides_obj(dir), out = dir.file("edges.usda"), adj = dir.file("adj.csv");
    const auto r = run_groom({"partition", guides, "-o", out, "--scalp", scalp, "--count", "6", "--samples", "5", "--write-adjacent", adj});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "partition: 24 segments from 3 guides (1 with two neighbours, 2 with one)")) << r.err;
    const CurveSet cs = read_curves(out);
    ASSERT_EQ(cs.num_curves(), 24u);  // 6 per side: two sides for the middle guide, one for each edge
    const auto guide = cs.find<int32_t>(Domain::Curve, "guide");
    const auto side = cs.find<int32_t>(Domain::Curve, "side");
    const auto group = cs.find<int32_t>(Domain::Curve, "group");
    ASSERT_EQ(guide.size(), 24u);
    ASSERT_EQ(side.size(), 24u);
    ASSERT_EQ(group.size(), 24u);
    ASSERT_EQ(cs.find<float>(Domain::Point, "width").size(), cs.num_points());
    const auto P = cs.positions();
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const IndexRange rg = cs.points_of(c);
        // Root on the (level-set) scalp, tip on the guide 2% above the sphere; points in between
        // never inside (the mesh's chords sit up to 0.05% inside the true sphere).
        EXPECT_NEAR(length(P[rg.begin]), 1.0f, 0.01f) << "curve " << c;
        EXPECT_NEAR(length(P[rg.end - 1]), 1.02f, 1e-4f) << "curve " << c;
        for (int64_t p = rg.begin; p < rg.end; ++p) EXPECT_GE(length(P[p]), 0.99f);
        // Side 0 (left) of a northward meridian lies towards larger longitude.
        const float lon_root = std::atan2(P[rg.begin].z, P[rg.begin].x), lon_tip = std::atan2(P[rg.end - 1].z, P[rg.end - 1].x);
        EXPECT_EQ(lon_root > lon_tip, side[c] == 0) << "curve " << c;
        // Default roots: spread from a tenth of the way to the neighbour (0.3 rad away) to 0.47 of
        // it, projected: 0.0297 to 0.1410 rad, never on the midline at 0.15 (level-set roots: +-0.005).
        EXPECT_GE(std::fabs(lon_root - lon_tip), 0.0297f - 0.005f) << "curve " << c;
        EXPECT_LE(std::fabs(lon_root - lon_tip), 0.1410f + 0.005f) << "curve " << c;
    }
    EXPECT_EQ(groom::test::read_bytes(adj), "# source,left,right (guide indices; -1 = none). Left = scalp normal x guide tangent.\n"
                                            "0,1,-1\n1,2,0\n2,-1,1\n");

    // The written neighbours read back give the same result.
    const std::string again = dir.file("again.usda");
    ASSERT_EQ(run_groom({"partition", guides, "-o", again, "--scalp", scalp, "--count", "6", "--samples", "5", "--adjacent", adj}).exit_code, 0);
    EXPECT_EQ(groom::test::read_bytes(again), groom::test::read_bytes(out));
}

TEST(PartitionCli, EveryKCentroidsAndSameBytesForAnyThreadCount)
{
    TempDir dir;
    const std::string scalp = sphere_obj(dir), guides = guides_obj(dir), a = dir.file("a.usda"), b = dir.file("b.usda");
    const std::vector<std::string> common = {"partition", guides, "--scalp", scalp, "--spacing", "0.1", "--centroids", "every:3", "--jitter", "0.5"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> v = common;
        v.insert(v.end(), extra.begin(), extra.end());
        return v;
    };
    ASSERT_EQ(run_groom(with({"-o", a, "--threads", "1"})).exit_code, 0);
    ASSERT_EQ(run_groom(with({"-o", b, "--threads", "2"})).exit_code, 0);
    EXPECT_EQ(groom::test::read_bytes(a), groom::test::read_bytes(b));
    const CurveSet cs = read_curves(a);
    const auto group = cs.find<int32_t>(Domain::Curve, "group");
    ASSERT_EQ(cs.num_curves(), 4u * 10u);  // 1.02 rad of guide at spacing 0.1: 10 per side
    for (size_t c = 0; c < cs.num_curves(); ++c) EXPECT_EQ(group[c], int(c % 10) / 3);
}

TEST(PartitionCli, KnotCentroidsMeetTheBraidKnots)
{
    // Guides of 1.02 rad at radius 1.02: 4 knots centred at arc-length fractions 1/8, 3/8, 5/8, 7/8,
    // that is latitudes -0.375, -0.125, 0.125, 0.375.
    TempDir dir;
    const std::string scalp = sphere_obj(dir), guides = guides_obj(dir), out = dir.file("out.usda");
    const auto r = run_groom({"partition", guides, "-o", out, "--scalp", scalp, "--count", "8", "--centroids", "knots", "--frequency", "4", "--converge", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet cs = read_curves(out);
    const auto group = cs.find<int32_t>(Domain::Curve, "group");
    ASSERT_EQ(cs.num_curves(), 32u);
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        EXPECT_EQ(group[c], int(c % 8) / 2);
        const float3 tip = cs.positions()[cs.points_of(c).end - 1];
        EXPECT_NEAR(std::asin(tip.y / 1.02f), -0.375f + 0.25f * group[c], 1e-3f);
    }
    // A knot density rising towards the tip packs the knots there, as it does in groom braid: the
    // first knot centre moves away from the root.
    const std::string dense = dir.file("dense.usda");
    ASSERT_EQ(run_groom({"partition", guides, "-o", dense, "--scalp", scalp, "--count", "8", "--centroids", "knots", "--frequency", "4",
                         "--knot-density", "1,4", "--converge", "1"})
                  .exit_code,
              0);
    const CurveSet d = read_curves(dense);
    EXPECT_GT(std::asin(d.positions()[d.points_of(0).end - 1].y / 1.02f), -0.375f + 0.05f);
}

TEST(PartitionCli, CentroidFileGroupsSegments)
{
    TempDir dir;
    const std::string scalp = sphere_obj(dir), guides = guides_obj(dir), out = dir.file("out.usda"), cfile = dir.file("c.csv");
    write_text(cfile, "# guide,u\n1, 0.5\n");
    const auto r = run_groom({"partition", guides, "-o", out, "--scalp", scalp, "--count", "4", "--centroids", cfile, "--converge", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet cs = read_curves(out);
    const auto guide = cs.find<int32_t>(Domain::Curve, "guide");
    const auto P = cs.positions();
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        if (guide[c] != 1) continue;
        const float3 tip = P[cs.points_of(c).end - 1];  // all on guide 1's middle: lat 0, lon 0
        EXPECT_NEAR(tip.x, 1.02f, 1e-4f);
        EXPECT_NEAR(tip.y, 0.0f, 1e-4f);
        EXPECT_NEAR(tip.z, 0.0f, 1e-4f);
    }
}

TEST(PartitionCli, RejectsBadOptionsAndFilesWithoutWritingOutput)
{
    TempDir dir;
    const std::string scalp = sphere_obj(dir), guides = guides_obj(dir), out = dir.file("out.usda");
    auto expect_error = [&](std::vector<std::string> extra, int code, const std::string& needle) {
        std::vector<std::string> args = {"partition", guides, "-o", out, "--scalp", scalp};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, code) << needle << "\n" << r.err;
        EXPECT_TRUE(contains(r.err, needle)) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << needle;
    };
    expect_error({"--mediate", "2"}, 2, "--mediate must be lo,hi with 0 <= lo <= hi <= 1 (got 2,2)");
    expect_error({"--mediate", "0.1,0.2,0.3"}, 2, "--mediate: expected 1 to 2 comma-separated numbers, got 3");
    expect_error({"--count", "0"}, 2, "--count must be >= 1 (got 0)");
    expect_error({"--spacing", "0"}, 2, "--spacing must be > 0 scene units (got 0)");
    expect_error({"--units-per-cm", "-1"}, 2, "--units-per-cm must be a finite number > 0 (got -1)");
    expect_error({"--count", "3", "--spacing", "0.1"}, 2, "--count and --spacing are exclusive");
    expect_error({"--samples", "1"}, 2, "--samples must be >= 2 (got 1)");
    expect_error({"--width", "-1"}, 2, "--width must be > 0");
    expect_error({"--centroids", "every:0"}, 2, "every:K needs K >= 1 (got 0)");
    expect_error({"--frequency", "3"}, 2, "--frequency applies only with --centroids knots");
    expect_error({"--centroids", "knots", "--knot-length", "-1"}, 2, "--knot-length must be > 0 scene units (got -1)");
    expect_error({"--knot-density", "1,2"}, 2, "--knot-density applies only with --centroids knots");
    expect_error({"--centroids", "knots", "--knot-density", "1,x"}, 2, "partition: --knot-density: expected a comma-separated list of numbers");
    expect_error({"--centroids", "every:x"}, 2, "every:K needs an integer K >= 1 (got 'every:x')");

    const std::string bad = dir.file("bad.csv");
    write_text(bad, "0,1,-1\n1,2\n");
    expect_error({"--adjacent", bad}, 1, bad + ":2: expected 'source,left,right'");
    write_text(bad, "# neighbours\n0,1,-1\n1,7,0\n");
    expect_error({"--adjacent", bad}, 1, bad + ":3: left guide 7 out of range (3 guides: 0 to 2, or -1)");
    write_text(bad, "0,1,-1\n\n0,-1,1\n");
    expect_error({"--adjacent", bad}, 1, bad + ":3: source guide 0 already listed at line 1");
    write_text(bad, "2,2,1\n");
    expect_error({"--adjacent", bad}, 1, bad + ":1: guide 2 cannot be its own neighbour");
    expect_error({"--adjacent", dir.file("missing.csv")}, 1, "cannot open");
    write_text(bad, "# none\n");  // was taken as no file: the automatic search ran
    expect_error({"--adjacent", bad}, 1, bad + ": --adjacent lists no guide");
    write_text(bad, "1,1.5\n");
    expect_error({"--centroids", bad}, 1, bad + ":1: u must be in [0, 1] (got 1.5)");
    write_text(bad, "3,0.5\n");
    expect_error({"--centroids", bad}, 1, bad + ":1: guide 3 out of range (3 guides: 0 to 2)");

    // -o onto an input is refused unless --force.
    const auto r = run_groom({"partition", guides, "-o", guides, "--scalp", scalp});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "refusing to overwrite")) << r.err;
}

// What a renderer shows: edge hairs lying on a scan's skin, not dashed through it. On Lee
// Perry-Smith at the default voxel (0.05, 36 times the hair's width) the level set's surface strays
// from the scan's finer detail by more than a hair's half width: 3.5% of the edge hairs' points
// (8,755 of 252,116) were under the skin of a field at a quarter the voxel by more than that (a
// trial had measured 7.9% against a fifth). Lifted by the field's surface tolerance, at most 0.1%
// are, and the hairs still lie on the scalp: their median height over the fine field under a
// tenth of a voxel.
TEST(PartitionCliReal, EdgeHairsOnAScanLieOnItsSkinNotUnderIt)
{
    GROOM_REQUIRE_SHARED(scan, "lee_perry_smith/LeePerrySmith.obj");
    TempDir dir;
    ASSERT_EQ(run_groom({"scalp", scan, "-o", dir.file("s.vdb"), "-q"}).exit_code, 0);
    ASSERT_EQ(run_groom({"scalp", scan, "-o", dir.file("fine.vdb"), "--voxel", "0.0125", "-q"}).exit_code, 0);
    ASSERT_EQ(run_groom({"hairline", "--scalp", dir.file("s.vdb"), "-o", dir.file("h.usda"), "-q"}).exit_code, 0);
    ASSERT_EQ(run_groom({"cornrow-guides", "--scalp", dir.file("s.vdb"), "--hairline", dir.file("h.usda"), "--center", "0,2.3,0", "--radius", "1.7",
                         "--count", "12", "-o", dir.file("g.usda"), "-q"})
                  .exit_code,
              0);
    const auto r = run_groom({"partition", dir.file("g.usda"), "--scalp", dir.file("s.vdb"), "-o", dir.file("e.usda"), "--centroids", "knots",
                              "--knot-length", "0.385", "--samples", "6", "--max-height", "0.175", "--hairline", dir.file("h.usda"),
                              "--units-per-cm", "0.175"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto probe = run_groom({"probe", dir.file("e.usda"), "--scalp", dir.file("fine.vdb"), "-o", dir.file("p.csv")});
    ASSERT_EQ(probe.exit_code, 0) << probe.err;
    const CurveSet e = read_curves(dir.file("e.usda"));
    const auto width = e.find<float>(Domain::Point, "width");
    ASSERT_EQ(width.size(), e.num_points());
    std::ifstream csv(dir.file("p.csv"));
    std::string line;
    std::getline(csv, line);  // header
    std::vector<float> d;
    while (std::getline(csv, line)) {
        std::istringstream row(line);
        std::string cell;
        for (int k = 0; k < 4; ++k) std::getline(row, cell, ',');
        d.push_back(std::stof(cell));
    }
    ASSERT_EQ(d.size(), e.num_points());
    int64_t interior = 0, buried = 0;
    std::vector<float> heights;
    for (size_t c = 0; c < e.num_curves(); ++c) {
        const IndexRange rg = e.points_of(c);
        for (int64_t k = rg.begin + 1; k + 1 < rg.end; ++k) {
            ++interior;
            buried += d[size_t(k)] < -0.5f * width[size_t(k)];
            heights.push_back(d[size_t(k)]);
        }
    }
    ASSERT_GT(interior, 100000);
    EXPECT_LE(double(buried), 0.001 * double(interior)) << buried << " of " << interior << " points under the skin by over half a width";
    std::nth_element(heights.begin(), heights.begin() + std::ptrdiff_t(heights.size() / 2), heights.end());
    EXPECT_LT(heights[heights.size() / 2], 0.1f * 0.05f) << "median height over the fine field";
}
