// `groom curl` end to end: files in, files out, exit codes and messages.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "kernel/math/polyline.h"
#include "support/sphere_mesh.h"

#include <filesystem>
#include <numbers>

using namespace groom;
using groom::test::run_groom;
using groom::test::TempDir;

namespace {

/// Two straight 15-unit guides and one bent one, as OBJ polylines.
std::string guides_obj(const TempDir& dir)
{
    const std::string path = dir.file("guides.obj");
    groom::test::write_text(path,
                            "v 0 0 0\nv 0 5 0\nv 0 10 0\nv 0 15 0\n"
                            "v 3 0 0\nv 3 5 0\nv 3 10 0\nv 3 15 0\n"
                            "v 6 0 0\nv 6 5 1\nv 7 10 2\nv 9 14 3\n"
                            "l 1 2 3 4\nl 5 6 7 8\nl 9 10 11 12\n");
    return path;
}

}  // namespace

TEST(CurlCli, CurlsGuidesAndWritesShapeCycleAndHairType)
{
    TempDir dir;
    const std::string in = guides_obj(dir), out = dir.file("curled.usda");
    const auto r = run_groom({"curl", in, "-o", out, "--type", "4a", "--uniformity", "0.5", "--seed", "11"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet src = read_curves(in), cs = read_curves(out);
    ASSERT_EQ(cs.num_curves(), 3u);
    EXPECT_EQ(cs.detail_string("hair_type"), "4a");
    const auto shape = cs.find<int32_t>(Domain::Point, "shape");
    const auto cycle = cs.find<int32_t>(Domain::Point, "cycle");
    ASSERT_EQ(shape.size(), cs.num_points());
    ASSERT_EQ(cycle.size(), cs.num_points());
    int shapes_seen = 0;
    for (int s = 0; s < 5; ++s) shapes_seen += std::count(shape.begin(), shape.end(), s) > 0;
    EXPECT_GE(shapes_seen, 3) << "uniformity 0.5 over dozens of cycles should mix shapes";
    for (size_t c = 0; c < 3; ++c) {
        const IndexRange a = src.points_of(c), b = cs.points_of(c);
        const float la = polyline_length(src.positions().subspan(size_t(a.begin), size_t(a.size())));
        const float lb = polyline_length(cs.positions().subspan(size_t(b.begin), size_t(b.size())));
        EXPECT_NEAR(lb, la, 0.01f * la) << "curve " << c;
        EXPECT_GT(b.size(), 100);
        EXPECT_EQ(cycle[size_t(b.begin)], 0);
        EXPECT_GT(cycle[size_t(b.end - 1)], 5);
    }
}

// A curve with nothing to curl around (one point, or every point at one spot) passes through as it
// is, and the command says so, naming how many and the first (a trial's came back without a word).
TEST(CurlCli, CurvesWithNothingToCurlAroundAreNamed)
{
    TempDir dir;
    const std::string in = dir.file("mixed.obj");
    groom::test::write_text(in, "v 0 0 0\nv 0 5 0\nv 0 10 0\nv 1 1 1\nv 1 1 1\nv 1 1 1\nl 1 2 3\nl 4 5 6\n");
    const auto r = run_groom({"curl", in, "-o", dir.file("out.usda"), "--type", "4a"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("1 of 2 curves have one point or zero length (the first: curve 1)"), std::string::npos) << r.err;
    const CurveSet out = read_curves(dir.file("out.usda"));
    ASSERT_EQ(out.num_curves(), 2u);
    const IndexRange flat = out.points_of(1);
    for (int64_t i = flat.begin; i < flat.end; ++i) EXPECT_EQ(out.positions()[size_t(i)], float3(1, 1, 1));
    const auto fine = run_groom({"curl", guides_obj(dir), "-o", dir.file("fine.usda"), "--type", "4a"});
    EXPECT_EQ(fine.err.find("zero length"), std::string::npos) << fine.err;
}

TEST(CurlCli, SameBytesForAnyThreadCount)
{
    TempDir dir;
    const std::string in = guides_obj(dir), a = dir.file("a.usda"), b = dir.file("b.usda");
    ASSERT_EQ(run_groom({"curl", in, "-o", a, "--threads", "1", "--type", "3b", "--offset", "0,0.1"}).exit_code, 0);
    ASSERT_EQ(run_groom({"curl", in, "-o", b, "--threads", "2", "--type", "3b", "--offset", "0,0.1"}).exit_code, 0);
    EXPECT_EQ(groom::test::read_bytes(a), groom::test::read_bytes(b));
    EXPECT_FALSE(groom::test::read_bytes(a).empty());
}

TEST(CurlCli, RejectsInvalidOptionsClearlyAndWritesNothing)
{
    TempDir dir;
    const std::string in = guides_obj(dir), out = dir.file("never.usda");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--type", "5a"}, "--type"},
        {{"--uniformity", "2"}, "--uniformity"},
        {{"--dominant", "hexagon"}, "--dominant"},
        {{"--shapes", "circle,blob"}, "--shapes"},
        {{"--shapes", "ellipse,rose"}, "--dominant"},
        {{"--shapes", "circle", "--uniformity", "0.5"}, "--uniformity"},
        {{"--amplitude", "0.5,0.1"}, "--amplitude"},
        {{"--amplitude", "a,b"}, "--amplitude"},
        {{"--amplitude", "0"}, "--amplitude"},  // not the type's default in disguise
        {{"--frequency", "0,0"}, "--frequency"},
        {{"--frequency", "1,2,3"}, "--frequency"},
        {{"--phase", "1,0"}, "--phase"},
        {{"--offset=-1,0"}, "--offset"},
        {{"--samples", "2"}, "--samples"},
        {{"--blend", "0.7"}, "--blend"},
        {{"--root-ease=-1"}, "--root-ease"},
        {{"--units-per-cm", "0"}, "--units-per-cm"},
        {{"--lame-exponent", "0"}, "--lame-exponent"},
        {{"--polygon-sides", "2"}, "--polygon-sides"},
        {{"--ellipse-aspect", "2"}, "--ellipse-aspect"},
        {{"--rose-petals", "0"}, "--rose-petals"},
    };
    for (const auto& [extra, option] : cases) {
        std::vector<std::string> args = {"curl", in, "-o", out};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 2) << option << ": " << r.err;
        EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << option;
    }
    // The value found is printed as given, not as 31 digits of float expansion.
    const auto huge = run_groom({"curl", in, "-o", out, "--lame-exponent", "1e30"});
    EXPECT_EQ(huge.exit_code, 2) << huge.err;
    EXPECT_NE(huge.err.find("(got 1e+30)"), std::string::npos) << huge.err;
}

TEST(CurlCli, RefusesToOverwriteItsInputAndReportsMissingFiles)
{
    TempDir dir;
    const std::string in = guides_obj(dir);
    const std::string before = groom::test::read_bytes(in);
    auto r = run_groom({"curl", in, "-o", in});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
    EXPECT_EQ(groom::test::read_bytes(in), before);
    r = run_groom({"curl", dir.file("missing.obj"), "-o", dir.file("x.usda")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("missing.obj"), std::string::npos) << r.err;
}

// --scalp: curls over a sphere mesh dip into it without the scalp and stay outside with it.
TEST(CurlCli, NoCurledPointInsideTheScalpMesh)
{
    TempDir dir;
    const float3 centre(0.0f, 0.0f, 0.0f);
    const float radius = 5.0f;
    const PolygonSoup sphere = icosphere(centre, radius, 4);
    const float chord = sphere_chordal_error(sphere, centre, radius);
    const std::string mesh = dir.file("sphere.obj"), guides = dir.file("guides.obj");
    write_mesh(sphere, mesh);
    // Guides 0.2 above the sphere, running over its top from the pole towards the equator.
    std::string obj, lines;
    int v = 0;
    for (int c = 0; c < 12; ++c) {
        const float az = 2.0f * std::numbers::pi_v<float> * float(c) / 12.0f;
        lines += "l";
        for (int i = 0; i < 12; ++i) {
            const float polar = 0.15f + 1.2f * float(i) / 11.0f;
            const float r = radius + 0.2f;
            obj += "v " + std::to_string(r * std::sin(polar) * std::cos(az)) + " " + std::to_string(r * std::cos(polar)) + " " +
                   std::to_string(r * std::sin(polar) * std::sin(az)) + "\n";
            lines += " " + std::to_string(++v);
        }
        lines += "\n";
    }
    groom::test::write_text(guides, obj + lines);
    const std::vector<std::string> common = {"--amplitude", "0.6", "--frequency", "0.5", "--root-ramp", "0"};
    auto min_radius = [&](const std::string& out) {
        float m = INFINITY;
        const CurveSet curled = read_curves(out);  // named: a range-for over a temporary's span would dangle
        for (const float3& p : curled.positions()) m = std::min(m, length(p - centre));
        return m;
    };
    std::vector<std::string> args = {"curl", guides, "-o", dir.file("free.usda")};
    args.insert(args.end(), common.begin(), common.end());
    auto r = run_groom(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_LT(min_radius(dir.file("free.usda")), radius - 0.3f) << "the curls must dip into the sphere, or the check below is vacuous";
    args = {"curl", guides, "-o", dir.file("scalp.usda"), "--scalp", mesh};
    args.insert(args.end(), common.begin(), common.end());
    r = run_groom(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Outside the mesh means outside the sphere less the mesh's chordal error (and float slack).
    EXPECT_GE(min_radius(dir.file("scalp.usda")), radius - chord - 1e-3f * radius);
}

// A .hair output cannot hold the point `shape` and `cycle` columns, so curl does not make them
// there (memory): the curled points are the same bits as in a file that keeps them.
TEST(CurlCli, HairOutputHasTheSamePointsWithoutTheLabelColumns)
{
    TempDir dir;
    const std::string in = guides_obj(dir), ply = dir.file("c.ply"), hair = dir.file("c.hair");
    ASSERT_EQ(run_groom({"curl", in, "-o", ply, "--type", "3b", "--seed", "4"}).exit_code, 0);
    const auto r = run_groom({"curl", in, "-o", hair, "--type", "3b", "--seed", "4"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("shape"), std::string::npos) << "no warning about columns nobody asked for: " << r.err;
    const CurveSet a = read_curves(ply), b = read_curves(hair);
    ASSERT_FALSE(a.find<int32_t>(Domain::Point, "shape").empty());
    ASSERT_EQ(a.num_points(), b.num_points());
    for (size_t i = 0; i < a.num_points(); ++i) ASSERT_EQ(a.positions()[i], b.positions()[i]) << "point " << i;
    // Written as it is made (curl_blocks into a .hair block writer): the very file `convert` makes
    // from the whole output.
    ASSERT_EQ(run_groom({"convert", ply, "-o", dir.file("whole.hair")}).exit_code, 0);
    EXPECT_EQ(groom::test::read_bytes(hair), groom::test::read_bytes(dir.file("whole.hair")));
    // A curve .hair cannot hold (over 65,536 points) is refused before anything is written.
    const auto big = run_groom({"curl", in, "-o", dir.file("big.hair"), "--frequency", "400,400", "--samples", "16"});
    EXPECT_NE(big.exit_code, 0);
    EXPECT_NE(big.err.find("65536 points per strand"), std::string::npos) << big.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("big.hair")));
}
