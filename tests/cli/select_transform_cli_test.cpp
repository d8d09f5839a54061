// `groom select` and `groom transform` end to end: the kept ids, the moved points, errors that name
// the option and what was expected, and no output file after an error. And root UVs end to end:
// `generate` on a scalp mesh with UVs and on the .vdb `groom scalp` made from it.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "support/sphere_mesh.h"

#include <cmath>
#include <filesystem>

using namespace groom;
using groom::test::run_groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

/// Six two-point curves at x = c with ids 10 c and kind c % 2, widths 0.01 (c + 1) at the root.
std::string six_curves(const TempDir& dir)
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(6, 2));
    auto P = cs.positions_for_write();
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    auto kind = cs.add<int32_t>(Domain::Curve, "kind");
    auto w = cs.add<float>(Domain::Point, attr::width);
    for (int c = 0; c < 6; ++c) {
        P[2 * c] = float3(float(c), 0, 0);
        P[2 * c + 1] = float3(float(c), 1, 0);
        id[c] = 10 * c;
        kind[c] = c % 2;
        w[2 * c] = 0.01f * float(c + 1);
        w[2 * c + 1] = 0.005f;
    }
    const std::string path = dir.file("six.usda");
    write_curves(cs, path);
    return path;
}

}  // namespace

TEST(SelectCli, KeepsIdsAndComparisonsAndInverts)
{
    TempDir dir;
    const std::string in = six_curves(dir), out = dir.file("out.usda");
    auto r = run_groom({"select", in, "--ids", "10-30", "--where", "kind==1", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("2 of 6 curves match"), std::string::npos) << r.err;
    EXPECT_EQ(read_curves(out).curve_ids(), (std::vector<int64_t>{10, 30}));
    r = run_groom({"select", in, "--where", "width>0.035", "--where", "kind!=1", "--invert", "-o", out, "--force"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_curves(out).curve_ids(), (std::vector<int64_t>{0, 10, 20, 30, 50}));
    EXPECT_EQ(r.err.find("no curve kept"), std::string::npos) << r.err;
    // Ids past the input's: an empty file, said so with the ids there are (a trial's went unremarked).
    r = run_groom({"select", in, "--ids", "100-200", "-o", out, "--force"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("no curve kept"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the input's ids run from 0 to 50"), std::string::npos) << r.err;
}

// A guide at the top of int64's range is one guide (the loop over the range had wrapped and grown
// without end: a trial).
TEST(SelectCli, TheLargestGuideIsOneGuide)
{
    TempDir dir;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(2, 2));
    auto P = cs.positions_for_write();
    P[1] = P[3] = float3(0, 1, 0);
    auto guide = cs.add<int64_t>(Domain::Curve, "guide");
    guide[0] = 3, guide[1] = INT64_MAX;
    write_curves(cs, dir.file("g.usda"));
    const auto r = run_groom({"select", dir.file("g.usda"), "--guide", "9223372036854775807", "-o", dir.file("o.usda")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_curves(dir.file("o.usda")).num_curves(), 1u);
    // A range across int64's whole width is too long, not wrapped to a short one (a review).
    const auto wide = run_groom({"select", dir.file("g.usda"), "--guide", "-9223372036854775807-9223372036854775807", "-o", dir.file("w.usda")});
    EXPECT_EQ(wide.exit_code, 2) << wide.err;
    EXPECT_NE(wide.err.find("is too long"), std::string::npos) << wide.err;
}

TEST(SelectCli, BadExpressionNamesTheOptionAndWhatWasExpected)
{
    TempDir dir;
    const std::string in = six_curves(dir), out = dir.file("out.usda");
    auto r = run_groom({"select", in, "--where", "width=>0.1", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--where 'width=>0.1'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("expected NAME OP NUMBER"), std::string::npos) << r.err;
    r = run_groom({"select", in, "--ids", "3-x", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--ids '3-x'"), std::string::npos) << r.err;
    r = run_groom({"select", in, "--where", "radius<1", "-o", out});
    EXPECT_NE(r.err.find("'radius', which the curves do not have"), std::string::npos) << r.err;
    r = run_groom({"select", in, "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("give --ids, --guide, --where or --prim"), std::string::npos) << r.err;
    // Prim paths come from a USD file; a .ply carries none.
    write_curves(read_curves(in), dir.file("six.ply"));
    r = run_groom({"select", dir.file("six.ply"), "--prim", "/groom", "-o", out});
    EXPECT_NE(r.err.find("--prim needs curves that carry their prim paths"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SelectCli, PrimKeepsTheCurvesOfAPrimAndThoseUnderIt)
{
    // Three prims, one curve each at x = 0, 1, 2: /hair/a, /hair/ab (under /hair, not under
    // /hair/a), /other. The output does not keep the prim bookkeeping.
    TempDir dir;
    const std::string in = dir.file("prims.usda"), out = dir.file("out.usda");
    auto prim = [](const char* name, int x) {
        const std::string p = "(" + std::to_string(x) + ", 0, 0), (" + std::to_string(x) + ", 1, 0)";
        return std::string("    def BasisCurves \"") + name + "\" {\n        uniform token type = \"linear\"\n"
               "        int[] curveVertexCounts = [2]\n        point3f[] points = [" + p + "]\n    }\n";
    };
    write_text(in, "#usda 1.0\ndef Xform \"hair\" {\n" + prim("a", 0) + prim("ab", 1) + "}\ndef Xform \"other\" {\n" + prim("c", 2) + "}\n");
    auto xs = [](const CurveSet& cs) {
        std::vector<float> x;
        for (size_t c = 0; c < cs.num_curves(); ++c) x.push_back(cs.positions()[cs.points_of(c).begin].x);
        return x;
    };
    auto r = run_groom({"select", in, "--prim", "/hair", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(xs(read_curves(out)), (std::vector<float>{0, 1}));
    r = run_groom({"select", in, "--prim", "/hair/a", "-o", out, "--force"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(xs(read_curves(out)), (std::vector<float>{0}));
    r = run_groom({"select", in, "--prim", "/hair/ab,/other", "--invert", "-o", out, "--force"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet kept = read_curves(out);
    EXPECT_EQ(xs(kept), (std::vector<float>{0}));
    EXPECT_EQ(kept.attributes(Domain::Curve).find("prim"), nullptr);
    EXPECT_EQ(kept.detail_string("prim_paths"), "");
}

TEST(TransformCli, MovesAStraightGuideAndConvertsUnitsAndAxis)
{
    TempDir dir;
    const std::string in = six_curves(dir), out = dir.file("out.usda");
    auto r = run_groom({"transform", in, "--scale", "2", "--rotate", "0,0,90", "--translate=-1,0,5", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    CurveSet cs = read_curves(out);
    // (c, t, 0) -> Rz(90) 2 (c, t, 0) + (-1, 0, 5) = (-2t - 1, 2c, 5).
    for (int c = 0; c < 6; ++c)
        for (int t = 0; t < 2; ++t) {
            const float3 p = cs.positions()[2 * c + t];
            EXPECT_NEAR(p.x, -2.0f * float(t) - 1.0f, 1e-6f);
            EXPECT_NEAR(p.y, 2.0f * float(c), 1e-6f);
            EXPECT_NEAR(p.z, 5.0f, 1e-6f);
        }
    EXPECT_NEAR(cs.find<float>(Domain::Point, attr::width)[0], 0.02f, 1e-7f);
    r = run_groom({"transform", in, "--units", "m", "--from-units", "cm", "--up-axis", "z", "-o", out, "--force"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    cs = read_curves(out);
    EXPECT_NEAR(cs.positions()[11].x, 0.05f, 1e-8f);
    EXPECT_NEAR(cs.positions()[11].z, 0.01f, 1e-8f);
    EXPECT_EQ(cs.detail_string("units"), "m");
    EXPECT_EQ(cs.detail_string("up_axis"), "Z");
    // The .usda says so in its layer metadata too.
    const std::string text = groom::test::read_bytes(out);
    EXPECT_NE(text.find("upAxis = \"Z\""), std::string::npos);
    EXPECT_NE(text.find("metersPerUnit = 1"), std::string::npos);
}

TEST(TransformCli, BadValuesNameTheOption)
{
    TempDir dir;
    const std::string in = six_curves(dir), out = dir.file("out.usda");
    auto r = run_groom({"transform", in, "--scale", "1,2", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--scale '1,2': expected one factor or three"), std::string::npos) << r.err;
    r = run_groom({"transform", in, "--rotate", "0,0", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--rotate"), std::string::npos) << r.err;
    r = run_groom({"transform", in, "--scale", "0", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--scale must be finite and non-zero"), std::string::npos) << r.err;
    r = run_groom({"transform", in, "--units", "m", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("give --from-units"), std::string::npos) << r.err;
    r = run_groom({"transform", in, "--up-axis", "x", "-o", out});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--up-axis"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(RootUvCli, GenerateFromMeshOrVdbWritesTheSameRootUvsAndUsdSt)
{
    TempDir dir;
    // The lat-long sphere with its UVs as an OBJ (v, vt, f v/vt).
    const PolygonSoup soup = latlong_uv_sphere(10.0f, 24, 48);
    std::string obj;
    for (const float3& p : soup.points) obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    for (size_t i = 0; i < soup.uvs.size(); i += 2) obj += "vt " + std::to_string(soup.uvs[i]) + " " + std::to_string(soup.uvs[i + 1]) + "\n";
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        obj += "f";
        for (int64_t k = soup.face_offsets[f]; k < soup.face_offsets[f + 1]; ++k) {
            obj += " " + std::to_string(soup.face_indices[size_t(k)] + 1) + "/" + std::to_string(soup.face_uv_indices[size_t(k)] + 1);
        }
        obj += "\n";
    }
    write_text(dir.file("sphere.obj"), obj);
    // Three guides at latitude 60 degrees, longitudes 40, 70, 100.
    CurveSet guides = CurveSet::from_counts(std::vector<int64_t>(3, 4));
    for (int g = 0; g < 3; ++g) {
        const float th = 3.14159265f / 3, ph = (40.0f + 30.0f * float(g)) * 3.14159265f / 180;
        const float3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
        for (int i = 0; i < 4; ++i) guides.positions_for_write()[size_t(4 * g + i)] = n * (10.0f + float(i));
    }
    write_curves(guides, dir.file("guides.usda"));
    auto r = run_groom({"scalp", dir.file("sphere.obj"), "-o", dir.file("sphere.vdb"), "--voxel", "0.25"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_groom({"generate", dir.file("guides.usda"), "--scalp", dir.file("sphere.obj"), "--scalp-voxel", "0.25", "--count", "200", "-o",
                   dir.file("from_mesh.usda")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_groom({"generate", dir.file("guides.usda"), "--scalp", dir.file("sphere.vdb"), "--count", "200", "-o", dir.file("from_vdb.usda")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet a = read_curves(dir.file("from_mesh.usda")), b = read_curves(dir.file("from_vdb.usda"));
    const auto ua = a.find<float3>(Domain::Curve, "root_uv"), ub = b.find<float3>(Domain::Curve, "root_uv");
    ASSERT_EQ(ua.size(), 200u);
    ASSERT_EQ(ub.size(), 200u);
    // Roots differ (a loaded .vdb samples roots on its zero crossing's mesh), but each root's UV is
    // its latitude and longitude within the closed form's bound (tests/fields/scalp_uv_test.cpp).
    const double pi = 3.14159265358979, dtheta = pi / 24;
    for (const CurveSet* cs : {&a, &b}) {
        const auto uv = cs->find<float3>(Domain::Curve, "root_uv");
        for (size_t c = 0; c < cs->num_curves(); ++c) {
            const float3 d = normalize(cs->positions()[size_t(cs->points_of(c).begin)]);
            double phi = std::atan2(double(d.z), double(d.x));
            if (phi < 0) phi += 2 * pi;
            const double theta = std::acos(double(d.y)), band = std::floor(theta / dtheta) * dtheta;
            const double e = std::max(std::fabs(1 / std::tan(band)), std::fabs(1 / std::tan(band + dtheta))) * dtheta;
            EXPECT_NEAR(uv[c].x, phi / (2 * pi), (1.1 * e / 4 + 0.01) / 48) << c;
            EXPECT_NEAR(uv[c].y, 1 - theta / pi, 0.03 / 24) << c;
        }
    }
    const std::string text = groom::test::read_bytes(dir.file("from_vdb.usda"));
    EXPECT_NE(text.find("texCoord2f[] primvars:st = [("), std::string::npos);
    EXPECT_NE(text.find("interpolation = \"uniform\""), std::string::npos);
    // Reading groom's own file back says nothing about the renderers' copy of root_uv.
    r = run_groom({"info", dir.file("from_vdb.usda")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("primvars:st"), std::string::npos) << r.err;
}
