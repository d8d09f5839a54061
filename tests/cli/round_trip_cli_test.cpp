// Round trips a pipeline depends on: `convert` never fails on groom's own output (64-bit ids PLY
// cannot hold are dropped with a warning, never rounded), and a head's OBJ groups picked by name.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

using namespace groom;
using groom::test::read_bytes;
using groom::test::run_groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

bool contains(const std::string& text, const std::string& needle) { return text.find(needle) != std::string::npos; }

CurveSet three_curves()
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{3, 3, 3});
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(float(i), 0.5f * float(i), 1.0f / float(i + 1));
    return cs;
}

}  // namespace

TEST(RoundTripCli, PlyKeepsIdsUpTo2Pow53ExactlyAndDropsLargerOnesWithAWarning)
{
    TempDir dir;
    constexpr int64_t k53 = int64_t(1) << 53;
    // Within 2^53: kept exactly (a double holds every such integer).
    CurveSet small = three_curves();
    auto ids = small.add<int64_t>(Domain::Curve, attr::id);
    ids[0] = k53, ids[1] = -k53, ids[2] = k53 - 1;
    write_curves(small, dir.file("small.usda"));
    auto r = run_groom({"convert", dir.file("small.usda"), "-o", dir.file("small.ply")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(contains(r.err, "dropped")) << r.err;
    const CurveSet back = read_curves(dir.file("small.ply"));
    const auto bid = back.find<int64_t>(Domain::Curve, attr::id);
    ASSERT_EQ(bid.size(), 3u);
    EXPECT_EQ(bid[0], k53);
    EXPECT_EQ(bid[1], -k53);
    EXPECT_EQ(bid[2], k53 - 1);

    // Beyond: the column is left out, the rest written, and the warning says why.
    CurveSet big = three_curves();
    auto bids = big.add<int64_t>(Domain::Curve, attr::id);
    bids[0] = 7, bids[1] = k53 + 1, bids[2] = std::numeric_limits<int64_t>::max();
    big.add<int32_t>(Domain::Curve, "kind")[1] = 4;
    write_curves(big, dir.file("big.usda"));
    r = run_groom({"convert", dir.file("big.usda"), "-o", dir.file("big.ply")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "dropped: curve id (64-bit values beyond 2^53")) << r.err;
    const CurveSet b2 = read_curves(dir.file("big.ply"));
    EXPECT_TRUE(b2.find<int64_t>(Domain::Curve, attr::id).empty());
    ASSERT_EQ(b2.find<int32_t>(Domain::Curve, "kind").size(), 3u);
    EXPECT_EQ(b2.find<int32_t>(Domain::Curve, "kind")[1], 4);
    for (size_t i = 0; i < big.num_points(); ++i) EXPECT_EQ(b2.positions()[i], big.positions()[i]);
}

TEST(RoundTripCli, ConvertTakesPartitionsHashedIdsToEveryFormat)
{
    TempDir dir;
    const std::string scalp = dir.file("head.obj");
    write_mesh(icosphere(float3(0, 0, 0), 10.0f, 3), scalp);
    // Three guides just above the sphere, side by side.
    CurveSet g = CurveSet::from_counts(std::vector<int64_t>{20, 20, 20});
    auto P = g.positions_for_write();
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 20; ++i) {
            const double lon = -0.3 + 0.3 * k, lat = -0.5 + i / 19.0;
            P[k * 20 + i] = float3(float(10.2 * std::cos(lat) * std::cos(lon)), float(10.2 * std::sin(lat)), float(10.2 * std::cos(lat) * std::sin(lon)));
        }
    write_curves(g, dir.file("guides.usda"));
    const std::string edges = dir.file("edges.usda");
    auto r = run_groom({"partition", dir.file("guides.usda"), "--scalp", scalp, "-o", edges, "--count", "4"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet src = read_curves(edges);
    bool beyond = false;
    for (int64_t id : src.find<int64_t>(Domain::Curve, attr::id)) beyond |= id > (int64_t(1) << 53);
    ASSERT_TRUE(beyond) << "partition's ids are 63-bit hashes";
    for (const char* ext : {"ply", "obj", "hair", "usda"}) {
        const std::string out = dir.file(std::string("x.") + ext);
        r = run_groom({"convert", edges, "-o", out});
        ASSERT_EQ(r.exit_code, 0) << ext << ": " << r.err;
        EXPECT_EQ(read_curves(out).num_curves(), src.num_curves()) << ext;
    }
}

TEST(RoundTripCli, MeshGroupsPickedByNameForScalpInfoAndCommands)
{
    TempDir dir;
    // A head (sphere) in object "head" and a far "eye" sphere in group "eye": each alone is one shell.
    const PolygonSoup head = icosphere(float3(0, 0, 0), 10.0f, 3), eye = icosphere(float3(30, 0, 0), 2.0f, 3);
    std::string text = "# head and eye\n";
    for (const PolygonSoup* s : {&head, &eye})
        for (const float3& p : s->points) text += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    auto faces = [&](const PolygonSoup& s, size_t base) {
        for (size_t f = 0; f < s.num_faces(); ++f) {
            text += "f";
            for (int32_t i : s.face(f)) text += " " + std::to_string(base + i + 1);
            text += "\n";
        }
    };
    text += "o head\n";
    faces(head, 0);
    text += "g eye\n";
    faces(eye, head.points.size());
    const std::string obj = dir.file("person.obj");
    write_text(obj, text);

    auto r = run_groom({"info", obj});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "group head  " + std::to_string(head.num_faces() + eye.num_faces()) + " faces")) << r.out;
    EXPECT_TRUE(contains(r.out, "group eye  " + std::to_string(eye.num_faces()) + " faces")) << r.out;
    r = run_groom({"info", obj, "--group", "eye", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "\"faces\": " + std::to_string(eye.num_faces()))) << r.out;
    EXPECT_TRUE(contains(r.out, "\"vertices\": " + std::to_string(eye.points.size()))) << r.out;

    // A curve at x = 14, 4 from the head and 14 from the eye, projected onto the scalp: onto the
    // head with the whole file, onto the eye with --scalp-group eye or a .vdb made with --group eye.
    CurveSet c = CurveSet::from_counts(std::vector<int64_t>{2});
    c.positions_for_write()[0] = float3(14, 0, 0), c.positions_for_write()[1] = float3(14, 0.5f, 0);
    write_curves(c, dir.file("c.usda"));
    const std::string vdb = dir.file("eye.vdb");
    r = run_groom({"scalp", obj, "--group", "eye", "-o", vdb});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    struct Way {
        std::vector<std::string> scalp;
        float3 centre;
        float radius;
    };
    for (const Way& w : {Way{{"--scalp", obj}, float3(0, 0, 0), 10.0f}, Way{{"--scalp", obj, "--scalp-group", "eye"}, float3(30, 0, 0), 2.0f},
                         Way{{"--scalp", vdb}, float3(30, 0, 0), 2.0f}}) {
        std::vector<std::string> args{"project", dir.file("c.usda"), "-o", dir.file("p.usda"), "--mode", "all", "--force"};
        args.insert(args.end(), w.scalp.begin(), w.scalp.end());
        r = run_groom(args);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        // The icospheres' chords sit up to 2.5% of the radius inside the sphere.
        const CurveSet projected = read_curves(dir.file("p.usda"));
        for (const float3& p : projected.positions()) EXPECT_NEAR(length(p - w.centre), w.radius, 0.03f * w.radius);
    }

    // Misses and misuse are errors naming the file, the group and what there is; no output.
    r = run_groom({"scalp", obj, "--group", "teeth", "-o", dir.file("t.vdb")});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "no faces in an object or group named 'teeth' (the file has 'head', 'eye')")) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("t.vdb")));
    r = run_groom({"hairline", "--scalp", vdb, "--scalp-group", "eye", "-o", dir.file("l2.usda")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_TRUE(contains(r.err, "is a level set, not a mesh")) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("l2.usda")));
}
