// `groom scalp`, `probe`, `project` and `cull` end to end through the executable, on an analytic
// sphere mesh; and every kind of bad input: clear error, non-zero exit, no output file.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "ops/head.h"
#include "support/sphere_mesh.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace groom;
using groom::test::read_bytes;
using groom::test::run_groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

/// Unit sphere (icosphere 4) at the origin written as OBJ.
std::string sphere_obj(const TempDir& dir)
{
    const std::string path = dir.file("sphere.obj");
    write_mesh(icosphere({0, 0, 0}, 1.0f, 4), path);
    return path;
}

TEST(ScalpCli, ScalpThenProbeAnswersLikeTheSphere)
{
    TempDir dir;
    const std::string obj = sphere_obj(dir);
    const auto r = run_groom({"scalp", obj, "-o", dir.file("s.vdb"), "--voxel", "0.02", "--report", dir.file("r.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("1 shells (1 closed)"), std::string::npos) << r.err;
    EXPECT_NE(read_bytes(dir.file("r.json")).find("\"output_faces\": 5120"), std::string::npos);
    write_text(dir.file("p.txt"), "# points\n0 0 1.03\n0.5 0 0\n\n3, 0, 0\n");
    for (const std::string scalp : {dir.file("s.vdb"), obj}) {
        const auto p = run_groom({"probe", "--scalp", scalp, dir.file("p.txt"), "-o", dir.file("p.csv")});
        ASSERT_EQ(p.exit_code, 0) << p.err;
        std::istringstream csv(read_bytes(dir.file("p.csv")));
        std::string line;
        std::getline(csv, line);
        EXPECT_EQ(line, "x,y,z,distance,nx,ny,nz,cx,cy,cz");
        const double expect[3] = {0.03, -0.5, 2.0};
        for (double e : expect) {
            ASSERT_TRUE(std::getline(csv, line));
            std::vector<double> v;
            std::stringstream ss(line);
            for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
            ASSERT_EQ(v.size(), 10u);
            EXPECT_NEAR(v[3], e, 0.01) << line;  // chordal error of icosphere 4 is ~0.0025
            EXPECT_NEAR(std::sqrt(v[7] * v[7] + v[8] * v[8] + v[9] * v[9]), 1.0, 0.01) << line;
        }
    }
}

TEST(ScalpCli, ProjectAndCullCurves)
{
    TempDir dir;
    const std::string obj = sphere_obj(dir);
    ASSERT_EQ(run_groom({"scalp", obj, "-o", dir.file("s.vdb"), "--voxel", "0.02", "-q"}).exit_code, 0);
    // Two curves: one hovering above the sphere, one diving through it.
    write_text(dir.file("c.obj"), "v 0 1.2 0\nv 0 1.5 0\nv 0 1.8 0\nv 1.2 0 0\nv 0.6 0 0\nv 0 0 0\nl 1 2 3\nl 4 5 6\n");
    auto r = run_groom({"project", dir.file("c.obj"), "--scalp", dir.file("s.vdb"), "-o", dir.file("p.obj"), "--offset", "0.1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    CurveSet p = read_curves(dir.file("p.obj"));
    EXPECT_NEAR(p.positions()[0].y, 1.1f, 0.01f);
    EXPECT_NEAR(p.positions()[2].y, 1.7f, 0.01f);
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    // Curves in other units (100 times the sphere's size: cm on a scalp in metres) are moved, and
    // said to have moved by more than half the scalp (a trial's moved by 91 onto a body 0.9 across).
    write_text(dir.file("far.obj"), "v 0 120 0\nv 0 150 0\nv 0 180 0\nl 1 2 3\n");
    r = run_groom({"project", dir.file("far.obj"), "--scalp", dir.file("s.vdb"), "-o", dir.file("far_p.obj")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("more than half the scalp's size"), std::string::npos) << r.err;
    r = run_groom({"cull", dir.file("c.obj"), "--scalp", dir.file("s.vdb"), "-o", dir.file("k.obj"), "--mode", "delete"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("1 of 2 curves affected"), std::string::npos) << r.err;
    EXPECT_EQ(read_curves(dir.file("k.obj")).num_curves(), 1u);
}

TEST(ScalpCli, SeveralMeshesAreOneSurface)
{
    // A head whose eye sockets are open and its eyeballs come as separate files: given together,
    // the field is their union. Two unit spheres at x = -1.5 and 1.5 (OBJ and PLY, one with UVs):
    // distance min(|p - a|, |p - b|) - 1 (icosphere 4: chordal error about 0.0025).
    TempDir dir;
    PolygonSoup a = icosphere({-1.5f, 0, 0}, 1.0f, 4), b = icosphere({1.5f, 0, 0}, 1.0f, 4);
    a.uvs = {0.25f, 0.5f};
    a.face_uv_indices.assign(a.face_indices.size(), 0);
    write_mesh(a, dir.file("a.obj"));
    write_mesh(b, dir.file("b.ply"));
    auto r = run_groom({"scalp", dir.file("a.obj"), dir.file("b.ply"), "-o", dir.file("s.vdb"), "--voxel", "0.02"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("2 shells (2 closed)"), std::string::npos) << r.err;
    write_text(dir.file("p.txt"), "-1.5 0 0\n1.5 0 0\n0 0 0\n3 0 0\n-1.5 1.2 0\n");
    r = run_groom({"probe", "--scalp", dir.file("s.vdb"), dir.file("p.txt"), "-o", dir.file("p.csv")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream csv(read_bytes(dir.file("p.csv")));
    std::string line;
    std::getline(csv, line);
    for (const double expect : {-1.0, -1.0, 0.5, 0.5, 0.2}) {
        ASSERT_TRUE(std::getline(csv, line));
        EXPECT_NEAR(std::stod(line.substr(line.find(',', line.find(',', line.find(',') + 1) + 1) + 1)), expect, 0.01) << line;
    }
    // An output naming the second input is refused, as for the first; a missing one names itself.
    r = run_groom({"scalp", dir.file("a.obj"), dir.file("b.ply"), "-o", dir.file("b.ply")});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("is also an input file"), std::string::npos) << r.err;
    r = run_groom({"scalp", dir.file("a.obj"), dir.file("missing.obj"), "-o", dir.file("t.vdb")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("missing.obj"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("t.vdb")));
    // The same file twice would be two coincident surfaces: refused, naming it.
    r = run_groom({"scalp", dir.file("a.obj"), dir.file("b.ply"), (dir.path() / "." / "a.obj").string(), "-o", dir.file("t.vdb")});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("is given twice (as MESH 1 and 3)"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("t.vdb")));
    // A mesh in other units or placed for another scene: one 100 head-sizes away, one 1,000x
    // smaller (centimetres against metres is 100x), refused naming both meshes and the way on.
    write_mesh(icosphere({300.0f, 0, 0}, 1.0f, 2), dir.file("far.obj"));
    write_mesh(icosphere({-1.5f, 0, 0}, 0.001f, 2), dir.file("tiny.obj"));
    for (const auto& [name, says] : {std::pair<std::string, std::string>{"far.obj", "lies away from"}, {"tiny.obj", "is of another scale than"}}) {
        r = run_groom({"scalp", dir.file("a.obj"), dir.file(name), "-o", dir.file("t.vdb")});
        EXPECT_EQ(r.exit_code, 1) << r.err;
        EXPECT_NE(r.err.find(name + " (bounds"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(says + " " + dir.file("a.obj")), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("Other units"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("t.vdb")));
    }
    // The first mesh sets the automatic voxel: its diagonal / 256 (2 sqrt(3) / 256), not the pair's.
    r = run_groom({"scalp", dir.file("a.obj"), dir.file("b.ply"), "-o", dir.file("v.vdb")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("2 meshes joined"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("voxel " + format_number(float(2.0 * std::sqrt(3.0) * 1.0 / 256.0)).substr(0, 6)), std::string::npos) << r.err;
    // A .vdb is a scalp already; --group names the mesh it was looked for in, and says it picks
    // faces of the first mesh only.
    r = run_groom({"scalp", dir.file("v.vdb"), "-o", dir.file("t.vdb")});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("is a .vdb, a scalp field already"), std::string::npos) << r.err;
    r = run_groom({"scalp", dir.file("a.obj"), dir.file("b.ply"), "--group", "head", "-o", dir.file("t.vdb")});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("--group picks faces of the first MESH only"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("t.vdb")));
}

TEST(ScalpCliReal, SintelsEyeballsFillHerOpenSockets)
{
    GROOM_REQUIRE_SHARED(head, "sintel_tressfx_opengl/sintel.obj");
    GROOM_REQUIRE_SHARED(eyes, "sintel_tressfx_opengl/sintel_eyeballs.obj");
    // The eyeballs sit in open sockets, inside no shell: kept (3 shells, none removed), and the
    // middle of each eyeball reads inside the joined scalp. Without them, in front of the socket's
    // back wall a point at the eyeball's middle is outside (the socket is empty).
    TempDir dir;
    auto r = run_groom({"scalp", head, eyes, "-o", dir.file("s.vdb"), "--report", dir.file("r.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(read_bytes(dir.file("r.json")).find("\"enclosed_shells_removed\": 0"), std::string::npos);
    EXPECT_NE(r.err.find("3 shells"), std::string::npos) << r.err;
    const PolygonSoup ball = read_mesh(eyes);
    float3 left, right;
    int nl = 0, nr = 0;
    for (const float3& p : ball.points) (p.x > 0.0f ? (++nr, right) : (++nl, left)) += p;
    ASSERT_GT(nl, 0);
    ASSERT_GT(nr, 0);
    left = left / float(nl), right = right / float(nr);
    std::ostringstream pts;
    pts << left.x << " " << left.y << " " << left.z << "\n" << right.x << " " << right.y << " " << right.z << "\n";
    write_text(dir.file("p.txt"), pts.str());
    ASSERT_EQ(run_groom({"scalp", head, "-o", dir.file("h.vdb"), "-q"}).exit_code, 0);
    for (const auto& [scalp, inside] : {std::pair<std::string, bool>{dir.file("s.vdb"), true}, {dir.file("h.vdb"), false}}) {
        r = run_groom({"probe", "--scalp", scalp, dir.file("p.txt"), "-o", dir.file("p.csv")});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        std::istringstream csv(read_bytes(dir.file("p.csv")));
        std::string line;
        std::getline(csv, line);
        for (int k = 0; k < 2; ++k) {
            ASSERT_TRUE(std::getline(csv, line));
            std::vector<double> v;
            std::stringstream ss(line);
            for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
            ASSERT_EQ(v.size(), 10u);
            EXPECT_EQ(v[3] < 0.0, inside) << scalp << ": " << line;
        }
    }
}

/// `soup` as OBJ text under object name `name` ("" for none), its vertex indices after `base`.
std::string obj_object(const PolygonSoup& soup, const std::string& name, size_t base)
{
    std::ostringstream out;
    if (!name.empty()) out << "o " << name << "\n";
    for (const float3& p : soup.points) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        out << "f";
        for (const int32_t v : soup.face(f)) out << " " << base + size_t(v) + 1;
        out << "\n";
    }
    return out.str();
}

TEST(ScalpCli, ReportNamesTheFilePartEachShellCameFrom)
{
    // A head (unit sphere, object 'Head') with an eye inside it (object 'Eye L', a name with a
    // space), joined to a second file without names (a sphere overlapping the head): the report
    // gives each shell's source, the note on the removed shell names it, and with one file alone
    // the names carry no file.
    TempDir dir;
    const PolygonSoup head = icosphere({0, 0, 0}, 1.0f, 3), eye = icosphere({0.4f, 0, 0}, 0.2f, 2);
    write_text(dir.file("head.obj"), obj_object(head, "Head", 0) + obj_object(eye, "Eye L", head.points.size()));
    write_mesh(icosphere({1.2f, 0, 0}, 0.5f, 3), dir.file("bun.obj"));
    auto r = run_groom({"scalp", dir.file("head.obj"), dir.file("bun.obj"), "-o", dir.file("s.vdb"), "--voxel", "0.05", "--report",
                        dir.file("r.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("removed 1 shell ('head.obj: Eye L') (320 faces) lying entirely inside a larger shell (inside one of "
                         "1280 faces ('head.obj: Head'))"),
              std::string::npos)
        << r.err;
    const auto report = nlohmann::json::parse(read_bytes(dir.file("r.json")));
    std::map<std::string, bool> removed;
    for (const auto& s : report["shell_list"]) removed[s["source"].get<std::string>()] = s["removed"].get<bool>();
    EXPECT_EQ(removed, (std::map<std::string, bool>{{"head.obj: Head", false}, {"head.obj: Eye L", true}, {"bun.obj", false}}));
    r = run_groom({"scalp", dir.file("head.obj"), "-o", dir.file("h.vdb"), "--voxel", "0.05", "--report", dir.file("h.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("removed 1 shell ('Eye L')"), std::string::npos) << r.err;
    // A mesh without names has no sources: "" in the report, no name in the notes.
    r = run_groom({"scalp", dir.file("bun.obj"), "-o", dir.file("b.vdb"), "--voxel", "0.05", "--report", dir.file("b.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(read_bytes(dir.file("b.json")))["shell_list"][0]["source"], "");
}

TEST(ScalpCli, FillHolesClosesRimsUpToALength)
{
    // A unit sphere missing its cap within 20 degrees of +Y: one rim, a regular 64-gon of perimeter
    // 2 x 64 sin(20 deg) sin(pi / 64) = 2.148. Its length is printed; a length above it fills it.
    TempDir dir;
    write_mesh(sphere_cap({0, 0, 0}, 1.0f, {0, -1, 0}, 160.0f, 48, 64), dir.file("open.obj"));
    auto r = run_groom({"scalp", dir.file("open.obj"), "-o", dir.file("a.vdb"), "--voxel", "0.02"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("1 hole (open rim) after repair, length 2.148"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("filled"), std::string::npos) << r.err;
    r = run_groom({"scalp", dir.file("open.obj"), "-o", dir.file("b.vdb"), "--voxel", "0.02", "--fill-holes", "2.2", "--report",
                   dir.file("r.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("1 hole filled (62 faces)"), std::string::npos) << r.err;
    EXPECT_NE(read_bytes(dir.file("r.json")).find("\"holes_filled\": 1"), std::string::npos);
    // Above the filled hole the distance is to its plane, y - cos(20 deg) (0.2603 at y = 1.2).
    write_text(dir.file("p.txt"), "0 1.2 0\n");
    r = run_groom({"probe", "--scalp", dir.file("b.vdb"), dir.file("p.txt"), "-o", dir.file("p.csv")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(read_bytes(dir.file("p.csv")).find("0,1.2,0,0.2603"), std::string::npos) << read_bytes(dir.file("p.csv"));
}

TEST(ScalpCli, BadInputFailsCleanlyWithoutOutput)
{
    TempDir dir;
    const std::string obj = sphere_obj(dir);
    write_text(dir.file("empty.obj"), "# nothing\n");
    write_text(dir.file("nan.obj"), "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
    write_text(dir.file("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    write_text(dir.file("garbage.vdb"), "not a vdb\n");
    struct Case {
        std::vector<std::string> args;
        int code;
        std::string says;
    };
    const std::string out = dir.file("out.vdb");
    // A real .vdb whose only grid is not a level set and not called "scalp": rename the grid and
    // change its class in the bytes of a good file ("staggered" is as long as "level set").
    ASSERT_EQ(run_groom({"scalp", obj, "-o", dir.file("good.vdb"), "--voxel", "0.05", "-q"}).exit_code, 0);
    std::string bytes = read_bytes(dir.file("good.vdb"));
    const size_t at = bytes.find("scalp"), cls = bytes.find("level set");
    ASSERT_NE(at, std::string::npos);
    ASSERT_NE(cls, std::string::npos);
    bytes[at + 4] = 'q';
    bytes.replace(cls, 9, "staggered");
    write_text(dir.file("other.vdb"), bytes);
    write_text(dir.file("p.txt"), "0 0 0\n");
    const Case cases[] = {
        {{"scalp", dir.file("empty.obj"), "-o", out}, 1, "empty"},
        {{"scalp", dir.file("nan.obj"), "-o", out}, 1, "nan.obj"},
        {{"scalp", dir.file("range.obj"), "-o", out}, 1, "range.obj"},
        {{"scalp", obj, "-o", out, "--voxel", "0"}, 2, "--voxel must be > 0"},
        {{"scalp", obj, "-o", out, "--voxel", "-1"}, 2, "--voxel must be > 0"},
        {{"scalp", obj, "-o", out, "--voxel", "0.0001", "--memory", "0.01"}, 1, "use --voxel"},
        {{"scalp", obj, "-o", out, "--band", "0"}, 2, "--band"},
        {{"scalp", obj, "-o", out, "--fill-holes", "-1"}, 2, "--fill-holes"},
        {{"probe", "--scalp", dir.file("other.vdb"), dir.file("p.txt"), "-o", dir.file("o.csv")}, 1,
         "other.vdb: no grid is named 'scalp' and none is a float level set (found: 'scalq' (float, staggered))"},
        {{"probe", "--scalp", dir.file("other.vdb"), dir.file("p.txt"), "-o", dir.file("o.csv"), "--scalp-grid", "scalp"}, 2,
         "--scalp-grid scalp: " + dir.file("other.vdb") + " has no grid of that name (found: 'scalq'"},
        {{"probe", "--scalp", obj, dir.file("p.txt"), "-o", dir.file("o.csv"), "--scalp-grid", "scalp"}, 2, "is a mesh, not a .vdb"},
        {{"probe", "--scalp", dir.file("garbage.vdb"), dir.file("p.txt"), "-o", dir.file("o.csv")}, 1, "garbage.vdb"},
        {{"project", dir.file("p.txt"), "--scalp", obj, "-o", dir.file("o.obj"), "--mode", "sideways"}, 2, "--mode"},
        {{"cull", dir.file("p.txt"), "--scalp", obj, "-o", dir.file("o.obj"), "--clearance", "-1"}, 2, "clearance"},
    };
    for (const Case& c : cases) {
        const auto r = run_groom(c.args);
        SCOPED_TRACE(c.args[0] + " " + c.args[1] + " ... -> " + r.err);
        EXPECT_EQ(r.exit_code, c.code);
        EXPECT_NE(r.err.find(c.says), std::string::npos);
        EXPECT_FALSE(std::filesystem::exists(out));
        EXPECT_FALSE(std::filesystem::exists(dir.file("o.csv")));
        EXPECT_FALSE(std::filesystem::exists(dir.file("o.obj")));
    }
}

}  // namespace

namespace {

/// The default head (`groom head`: about 44 units across, centimetres) as OBJ object `head`, and
/// one triangle (1 x 1) at x = `far` as object `stray`.
std::string head_with_stray_triangle(const TempDir& dir, float far, const std::string& name)
{
    const PolygonSoup head = make_head(HeadParams{});
    std::ostringstream obj;
    obj << "o head\n";
    for (const float3& p : head.points) obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (size_t f = 0; f < head.num_faces(); ++f) {
        obj << "f";
        for (const int32_t i : head.face(f)) obj << " " << i + 1;
        obj << "\n";
    }
    const size_t n = head.points.size();
    obj << "o stray\nv " << far << " 0 0\nv " << far << " 1 0\nv " << far << " 0 1\nf " << n + 1 << " " << n + 2 << " " << n + 3 << "\n";
    const std::string path = dir.file(name);
    write_text(path, obj.str());
    return path;
}

}  // namespace

TEST(ScalpCli, AutomaticVoxelMadeCoarseByAStrayPartIsRefusedNamingIt)
{
    // One triangle 1000 units from the default head: the automatic voxel (diagonal / 256) is 4.1,
    // the head spans 11 voxels and a probe through that grid flips inside and outside at 3% of the
    // points in the head's box. Refused, naming the file, the stray triangle and the two fixes.
    TempDir dir;
    const std::string mesh = head_with_stray_triangle(dir, 1000.0f, "stray.obj"), out = dir.file("s.vdb");
    const auto r = run_groom({"scalp", mesh, "-o", out, "--quiet"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    for (const std::string& part : std::vector<std::string>{mesh + ": the automatic voxel size ", "is too coarse for the head: its largest shell (16128 faces, 43.8",
          "because 1 other shell (1 face) reaches out of its box, the farthest (1 face, bounds 1000, 0, 0 to 1000, 1, 1)",
          "give --voxel 0.17", "keep only the head's faces with --group (OBJ)"})
        EXPECT_NE(r.err.find(part), std::string::npos) << "missing '" << part << "' in: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));

    // The head's own automatic voxel spans it 256 times along its diagonal; the message says how few here.
    const size_t spans = r.err.find("spans only ");
    ASSERT_NE(spans, std::string::npos) << r.err;
    const double voxels = std::stod(r.err.substr(spans + 11));
    EXPECT_GT(voxels, 8.0);
    EXPECT_LT(voxels, 16.0);

    // Each fix converts it, and the head's centre is then inside by its cranium's radius or so.
    write_text(dir.file("centre.txt"), "0 3 -1\n");
    for (const std::vector<std::string>& fix : {std::vector<std::string>{"--voxel", "0.25"}, std::vector<std::string>{"--group", "head"}}) {
        std::vector<std::string> args = {"scalp", mesh, "-o", out, "--quiet"};
        args.insert(args.end(), fix.begin(), fix.end());
        const auto ok = run_groom(args);
        ASSERT_EQ(ok.exit_code, 0) << fix[0] << ": " << ok.err;
        const auto p = run_groom({"probe", "--scalp", out, dir.file("centre.txt"), "-o", dir.file("c.csv"), "--quiet"});
        ASSERT_EQ(p.exit_code, 0) << p.err;
        std::istringstream csv(read_bytes(dir.file("c.csv")));
        std::string line;
        while (std::getline(csv, line) && !(line.size() && (std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '-'))) {
        }
        std::vector<double> v;
        std::stringstream cells(line);
        for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
        ASSERT_GE(v.size(), 4u) << line;
        EXPECT_LT(v[3], -5.0) << fix[0] << ": " << line;
    }

    // A command converting the mesh on the fly names its own options.
    const auto probe = run_groom({"probe", "--scalp", mesh, dir.file("centre.txt"), "-o", dir.file("c2.csv"), "--quiet"});
    EXPECT_EQ(probe.exit_code, 1) << probe.err;
    EXPECT_NE(probe.err.find("give --scalp-voxel 0.17"), std::string::npos) << probe.err;
    EXPECT_NE(probe.err.find("with --scalp-group (OBJ)"), std::string::npos) << probe.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("c2.csv")));

    // A part near the head (100 units away: the head still spans 92 voxels) is no reason to refuse.
    const std::string near = head_with_stray_triangle(dir, 100.0f, "near.obj");
    const auto n = run_groom({"scalp", near, "-o", dir.file("near.vdb"), "--quiet"});
    EXPECT_EQ(n.exit_code, 0) << n.err;
}
