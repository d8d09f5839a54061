// OBJ round trips with Blender and real heads: per-edge `l a b` records (what both Blender OBJ
// exporters write) joined into curves, and meshes read by `o`/`g` name.
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "test_support.h"
#include "tests/kernel/curve_samples.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

using namespace groom;
using groom::test::expect_parse_error;
using groom::test::expect_points_bit_exact;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

/// Point i of curve c of tests/data/blender/README.md's source: 12 curves of 24 points.
float3 blender_source_point(int c, int i)
{
    const double a = 2.0 * M_PI * c / 12, t = i / 23.0;
    // The source file was written with 6 decimals ("%.6f"); so is Blender's export.
    auto six = [](double v) { return std::round(v * 1e6) / 1e6; };
    return float3(float(six(std::cos(a) * (1 + t))), float(six(2 * t)), float(six(std::sin(a) * (1 + t) + 0.1 * std::sin(6 * t + c))));
}

}  // namespace

TEST(CurveIoObjEdges, BlenderExportsOfTwelveCurvesReadBackAsTwelve)
{
    // Blender 3.4.1 imported 12 polylines (legacy importer, whole polylines) and wrote them back
    // with each exporter: 276 `l a b` records each, the new exporter's not in curve order.
    for (const char* name : {"blender_new.obj", "blender_legacy.obj"}) {
        const std::string path = std::string(GROOM_SOURCE_DIR) + "/tests/data/blender/" + name;
        const CurveSet cs = read_curves(path);
        ASSERT_EQ(cs.num_curves(), 12u) << name;
        for (size_t c = 0; c < 12; ++c) {
            ASSERT_EQ(cs.points_in(c), 24) << name << " curve " << c;
            for (int i = 0; i < 24; ++i) {
                const float3 want = blender_source_point(int(c), i), got = cs.positions()[cs.points_of(c).begin + i];
                // Blender prints 6 decimals of its own float copy: within 1e-6 of the source's.
                ASSERT_LE(length(got - want), 2e-6f) << name << " curve " << c << " point " << i;
            }
        }
    }
}

TEST(CurveIoObjEdges, EdgesJoinIntoChainsRootFirstWholeRecordsStayInFileOrder)
{
    TempDir dir;
    std::string v;
    for (int i = 1; i <= 10; ++i) v += "v " + std::to_string(i) + " 0 0\n";
    // Only edges, written out of order and one chain drawn tip to root: chains by vertex order,
    // each from its source.
    write_text(dir.file("edges.obj"), v + "l 5 6\nl 2 1\nl 6 7\nl 3 2\nl 4 3\n");
    CurveSet cs = read_curves(dir.file("edges.obj"));
    ASSERT_EQ(cs.num_curves(), 2u);
    ASSERT_EQ(cs.points_in(0), 4);  // 4 -> 3 -> 2 -> 1: every edge points toward 1
    EXPECT_EQ(cs.positions()[0], float3(4, 0, 0));
    EXPECT_EQ(cs.positions()[3], float3(1, 0, 0));
    ASSERT_EQ(cs.points_in(1), 3);
    EXPECT_EQ(cs.positions()[4], float3(5, 0, 0));
    EXPECT_EQ(cs.positions()[6], float3(7, 0, 0));

    // Whole polylines mixed with edges: each curve where its first record is. `l 7 8` shares
    // vertex 8 with a whole polyline only, and whole polylines are never joined: a curve of its own.
    write_text(dir.file("mixed.obj"), v + "l 8 9 10\nl 4 5\nl 1 2 3\nl 5 6\nl 7 8\n");
    cs = read_curves(dir.file("mixed.obj"));
    ASSERT_EQ(cs.num_curves(), 4u);
    EXPECT_EQ(cs.points_in(0), 3);
    EXPECT_EQ(cs.positions()[0], float3(8, 0, 0));
    EXPECT_EQ(cs.points_in(1), 3);  // 4 5 6 joined
    EXPECT_EQ(cs.positions()[3], float3(4, 0, 0));
    EXPECT_EQ(cs.positions()[5], float3(6, 0, 0));
    EXPECT_EQ(cs.points_in(2), 3);
    EXPECT_EQ(cs.positions()[6], float3(1, 0, 0));
    EXPECT_EQ(cs.points_in(3), 2);
    EXPECT_EQ(cs.positions()[9], float3(7, 0, 0));
}

TEST(CurveIoObjEdges, TwoPointCurvesGroomWroteRoundTrip)
{
    TempDir dir;
    CurveSet src = CurveSet::from_counts(std::vector<int64_t>{2, 2, 5, 2});
    auto P = src.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(float(i) * 0.25f, std::sqrt(float(i)), -float(i));
    write_curves(src, dir.file("a.obj"));
    expect_points_bit_exact(src, read_curves(dir.file("a.obj")));
}

TEST(CurveIoObjEdges, BranchesLoopsAndSelfEdgesAreRefusedNamingTheVertex)
{
    TempDir dir;
    const std::string v = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n";
    expect_parse_error(dir.file("branch.obj"), v + "l 1 2\nl 1 3\nl 1 4\n", "vertex 1 has more than two two-point 'l' records (edges)");
    CurveReadOptions strict;
    strict.closed_loops = false;
    write_text(dir.file("loop.obj"), v + "l 1 2\nl 2 3\nl 3 1\n");
    try {
        read_curves(dir.file("loop.obj"), strict);
        ADD_FAILURE() << "a loop was read where open chains were asked for";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 1 lies on a closed loop of two-point 'l' records"), std::string::npos) << e.what();
    }
    expect_parse_error(dir.file("self.obj"), v + "l 1 2\nl 3 3\n", "self.obj:6: 'l' record joins vertex 3 to itself");
}

// A closed loop of edges is a closed curve (CurveReadOptions::closed_loops, on unless a caller asks
// for open chains only, above): from its lowest vertex the way its edges point, that vertex
// repeated at the end, as a USD periodic curve reads; after the open chains, in both OBJ and PLY.
// A hairline exported from Blender had been refused by every command but those reading
// --hairline (a trial). A curve written `closed` reads back the same way.
TEST(CurveIoObjEdges, ALoopOfEdgesIsOneClosedCurveWhereAsked)
{
    TempDir dir;
    CurveReadOptions loops;
    loops.closed_loops = true;
    // Vertices 1..4 a loop whose edges run 1->4->3->2->1 (given out of order), 5-6 an open chain.
    const std::string v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nv 6 6 6\n";
    write_text(dir.file("loop.obj"), v + "l 3 2\nl 5 6\nl 1 4\nl 2 1\nl 4 3\n");
    const CurveSet c = read_curves(dir.file("loop.obj"), loops);
    ASSERT_EQ(c.num_curves(), 2u);
    ASSERT_EQ(c.points_in(1), 5);
    const auto P = c.positions();
    EXPECT_EQ(P[0], float3(5, 5, 5));
    const float3 want[] = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {0, 0, 0}};
    for (int i = 0; i < 5; ++i) EXPECT_EQ(P[size_t(c.points_of(1).begin + i)], want[i]) << i;
    EXPECT_EQ(read_curves(dir.file("loop.obj")).num_curves(), 2u);  // read so by default too
    // The same loop as PLY edges.
    write_text(dir.file("loop.ply"), "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                                     "element edge 4\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                                     "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 1\n0 3\n1 0\n3 2\n");
    const CurveSet p = read_curves(dir.file("loop.ply"), loops);
    ASSERT_EQ(p.num_curves(), 1u);
    ASSERT_EQ(p.num_points(), 5u);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(p.positions()[size_t(i)], want[i]) << i;
    EXPECT_TRUE(is_closed(read_curves(dir.file("loop.ply"))));  // by default too
    // Written closed: OBJ's record ends at its first vertex again, USD says periodic; read back,
    // the first point repeats at the end, as the loop of edges gave it.
    CurveSet open = CurveSet::from_counts(std::vector<int64_t>{4});
    std::copy(std::begin(want), std::begin(want) + 4, open.positions_for_write().begin());
    CurveWriteOptions closed;
    closed.closed = true;
    for (const char* ext : {".obj", ".usda"}) {
        const std::string f = dir.file(std::string("closed") + ext);
        write_curves(open, f, closed);
        const CurveSet back = read_curves(f);
        ASSERT_EQ(back.num_points(), 5u) << ext;
        for (int i = 0; i < 5; ++i) EXPECT_EQ(back.positions()[size_t(i)], want[i]) << ext << " " << i;
    }
    EXPECT_NE(test::read_bytes(dir.file("closed.usda")).find("uniform token wrap = \"periodic\""), std::string::npos);
    EXPECT_NE(test::read_bytes(dir.file("closed.obj")).find("\nl 1 2 3 4 1\n"), std::string::npos);
    write_curves(open, dir.file("open.usda"));
    EXPECT_NE(test::read_bytes(dir.file("open.usda")).find("uniform token wrap = \"nonperiodic\""), std::string::npos);
}

TEST(MeshIoGroups, APickedGroupKeepsItsFacesTextureCoordinates)
{
    // Root UVs on a head picked out of a file with eyes and teeth: the chosen faces' corners keep
    // their own (u, v), a seam vertex (5 here, two `vt`) included.
    TempDir dir;
    const std::string path = dir.file("uv.obj");
    write_text(path,
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nv 6 5 5\n"
               "vt 0.1 0.2\nvt 0.3 0.4\nvt 0.5 0.6\nvt 0.7 0.8\nvt 0.9 0.95\n"
               "o Eyes\nf 5/1 6/2 4/3\n"
               "o Head\nf 1/1 2/2 3/3 4/4\nf 3/4 5/5 4/3\n");
    const PolygonSoup head = read_mesh(path, "Head");
    ASSERT_EQ(head.num_faces(), 2u);
    ASSERT_TRUE(head.has_uvs());
    ASSERT_EQ(head.face_uv_indices.size(), head.face_indices.size());
    const float want[7][2] = {{0.1f, 0.2f}, {0.3f, 0.4f}, {0.5f, 0.6f}, {0.7f, 0.8f}, {0.7f, 0.8f}, {0.9f, 0.95f}, {0.5f, 0.6f}};
    for (size_t k = 0; k < 7; ++k) {
        const int32_t t = head.face_uv_indices[k];
        ASSERT_GE(t, 0);
        EXPECT_EQ(head.uvs[size_t(2 * t)], want[k][0]) << "corner " << k;
        EXPECT_EQ(head.uvs[size_t(2 * t + 1)], want[k][1]) << "corner " << k;
    }
}

TEST(MeshIoGroups, PicksTheFacesOfOneObjectOrGroupWithTheirVerticesOnly)
{
    TempDir dir;
    const std::string path = dir.file("head.obj");
    // A quad "head" in object Head, a triangle in group eyes (two names), one more face in teeth.
    write_text(path,
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nv 6 5 5\nv 5 6 5\nv 9 9 9\n"
               "o Head\nf 1 2 3 4\n"
               "g eyes left_eye\nf 5 6 7\n"
               "o Teeth\nf 5 6 8\n");
    EXPECT_EQ(read_mesh(path).num_faces(), 3u);
    const PolygonSoup head = read_mesh(path, "Head");  // the object: its own face and its group's
    EXPECT_EQ(head.num_faces(), 2u);
    EXPECT_EQ(head.points.size(), 7u);
    const PolygonSoup eye = read_mesh(path, "left_eye");
    ASSERT_EQ(eye.num_faces(), 1u);
    ASSERT_EQ(eye.points.size(), 3u);  // renumbered: only the face's own vertices
    EXPECT_EQ(eye.points[eye.face(0)[0]], float3(5, 5, 5));
    EXPECT_EQ(eye.points[eye.face(0)[2]], float3(5, 6, 5));
    EXPECT_EQ(read_mesh(path, "Teeth").num_faces(), 1u);

    const std::vector<MeshGroup> groups = read_mesh_groups(path);
    ASSERT_EQ(groups.size(), 4u);
    EXPECT_EQ(groups[0].name, "Head");
    EXPECT_EQ(groups[0].faces, 2);
    EXPECT_EQ(groups[1].name, "eyes");
    EXPECT_EQ(groups[1].faces, 1);
    EXPECT_EQ(groups[3].name, "Teeth");

    try {
        read_mesh(path, "Hair");
        ADD_FAILURE() << "no error for a missing group";
    }
    catch (const ParseError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find(path + ": no faces in an object or group named 'Hair' (the file has 'Head', 'eyes', 'left_eye', 'Teeth')"),
                  std::string::npos)
            << m;
    }
    write_mesh(read_mesh(path), dir.file("head.ply"));
    EXPECT_THROW(read_mesh(dir.file("head.ply"), "Head"), InvalidParam);
}

TEST(MeshIoGroupsReal, PonytailHeadWithoutTeethEyesJacketAndBands)
{
    GROOM_REQUIRE_SHARED(path, "amd_tressfx_ponytail/ponytail_head.obj");
    // Count the file's own records: faces under `o Mesh_head`, vertices they use.
    std::ifstream in(path);
    std::string line, object;
    int64_t faces = 0;
    for (int64_t n = 0; std::getline(in, line); ++n) {
        if (line.rfind("o ", 0) == 0) object = line.substr(2);
        else if (line.rfind("f ", 0) == 0 && object == "Mesh_head") ++faces;
    }
    ASSERT_GT(faces, 1000);
    const PolygonSoup all = read_mesh(path);
    const PolygonSoup head = read_mesh(path, "Mesh_head");
    EXPECT_EQ(int64_t(head.num_faces()), faces);
    EXPECT_LT(head.points.size(), all.points.size());
    std::set<int32_t> used(head.face_indices.begin(), head.face_indices.end());
    EXPECT_EQ(used.size(), head.points.size());  // no vertex of the other parts comes along
    const std::vector<MeshGroup> groups = read_mesh_groups(path);
    EXPECT_EQ(groups.size(), 10u);
    int64_t total = 0;
    for (const MeshGroup& g : groups) total += g.faces;
    EXPECT_EQ(total, int64_t(all.num_faces()));
}
