// `groom scalp`, `probe`, `project` and `cull` end to end through the executable, on an analytic
// sphere mesh; and every kind of bad input: clear error, non-zero exit, no output file.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <cmath>
#include <filesystem>
#include <fstream>
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
    r = run_groom({"cull", dir.file("c.obj"), "--scalp", dir.file("s.vdb"), "-o", dir.file("k.obj"), "--mode", "delete"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("1 of 2 curves affected"), std::string::npos) << r.err;
    EXPECT_EQ(read_curves(dir.file("k.obj")).num_curves(), 1u);
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
    // A real .vdb whose grid is not called "scalp": rename the grid in the bytes of a good file.
    ASSERT_EQ(run_groom({"scalp", obj, "-o", dir.file("good.vdb"), "--voxel", "0.05", "-q"}).exit_code, 0);
    std::string bytes = read_bytes(dir.file("good.vdb"));
    const size_t at = bytes.find("scalp");
    ASSERT_NE(at, std::string::npos);
    bytes[at + 4] = 'q';
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
        {{"probe", "--scalp", dir.file("other.vdb"), dir.file("p.txt"), "-o", dir.file("o.csv")}, 1, "no grid named 'scalp'"},
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
