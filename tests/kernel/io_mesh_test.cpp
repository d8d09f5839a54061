// Mesh readers and topology statistics: faces are never dropped, statistics match hand-counted
// shapes, malformed files name the line.
#include "kernel/error.h"
#include "kernel/io/mesh_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

size_t count_lines_starting(const std::string& path, const std::string& prefix)
{
    std::ifstream f(path);
    size_t n = 0;
    for (std::string line; std::getline(f, line);) n += line.rfind(prefix, 0) == 0;
    return n;
}

/// A closed cube: 8 vertices, 6 quads.
std::string cube_obj()
{
    return "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
           "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
}

void expect_mesh_error(const std::string& path, const std::string& text, const std::string& needle)
{
    write_text(path, text);
    try {
        read_mesh(path);
        ADD_FAILURE() << "no error reading " << path;
    }
    catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what() << "\nexpected: " << needle;
    }
}

}  // namespace

TEST(MeshIoObj, ReadsNgonsNegativeIndicesAndSlashForms)
{
    TempDir dir;
    write_text(dir.file("m.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\nvt 0 0\nvn 0 0 1\n"
                                  "f 1/1/1 2/1/1 3/1/1 5//1 4\nf -5 -4 -3\n");
    const PolygonSoup s = read_mesh(dir.file("m.obj"));
    ASSERT_EQ(s.num_faces(), 2u);
    ASSERT_EQ(s.face(0).size(), 5u);
    EXPECT_EQ(s.face(0)[3], 4);
    EXPECT_EQ(s.face(1)[0], 0);
    EXPECT_EQ(s.face(1)[2], 2);
}

TEST(MeshIoObj, ReadsFaceVaryingTextureCoordinates)
{
    TempDir dir;
    // Two triangles sharing the edge 2-3, with different UVs on either side of it (a seam), one
    // relative vt index, and a face without UVs (its corners -1).
    write_text(dir.file("uv.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.25\nvt 0.75\n"
                                   "f 1/1 2/2 3/3\nf 2/4/1 4/-1/1 3/4/1\nf 1 2 4\n");
    const PolygonSoup s = read_mesh(dir.file("uv.obj"));
    ASSERT_TRUE(s.has_uvs());
    ASSERT_EQ(s.uvs.size(), 10u);
    EXPECT_EQ(s.uvs[8], 0.75f);  // `vt u` alone: v = 0
    EXPECT_EQ(s.uvs[9], 0.0f);
    EXPECT_EQ(s.face_uv_indices, (std::vector<int32_t>{0, 1, 2, 3, 4, 3, -1, -1, -1}));
    // No vt at all: no UVs.
    write_text(dir.file("plain.obj"), cube_obj());
    EXPECT_FALSE(read_mesh(dir.file("plain.obj")).has_uvs());
}

TEST(MeshIoObj, RejectsBadTextureCoordinates)
{
    TempDir dir;
    expect_mesh_error(dir.file("vtrange.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
                      "vtrange.obj:5: texture coordinate index 2 out of range (1 'vt' records)");
    expect_mesh_error(dir.file("vtnan.obj"), "v 0 0 0\nvt 0 nan\n", "vtnan.obj:2: expected a finite texture coordinate");
    expect_mesh_error(dir.file("vtzero.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2/1 3/1\n", "vtzero.obj:5: texture coordinate index 0 is invalid");
    expect_mesh_error(dir.file("vtrel.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-2 2/1 3/1\n", "reaches before the first 'vt'");
}

TEST(MeshIoPly, ReadsVertexAndCornerTextureCoordinates)
{
    TempDir dir;
    write_text(dir.file("st.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                   "property float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                   "0 0 0 0.1 0.2\n1 0 0 0.3 0.4\n0 1 0 0.5 0.6\n3 0 1 2\n");
    const PolygonSoup s = read_mesh(dir.file("st.ply"));
    ASSERT_TRUE(s.has_uvs());
    EXPECT_EQ(s.face_uv_indices, (std::vector<int32_t>{0, 1, 2}));
    EXPECT_FLOAT_EQ(s.uvs[3], 0.4f);
    write_text(dir.file("tc.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                   "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
                                   "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 6 0 0 1 0 0 1\n");
    const PolygonSoup c = read_mesh(dir.file("tc.ply"));
    ASSERT_TRUE(c.has_uvs());
    EXPECT_EQ(c.uvs, (std::vector<float>{0, 0, 1, 0, 0, 1}));
    expect_mesh_error(dir.file("tc4.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                           "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
                                           "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 4 0 0 1 0\n",
                      "face 0 has 4 texcoord values; expected 2 per corner (6)");
}

TEST(MeshStats, ClosedCubeHasNoBoundaryAndOneShell)
{
    TempDir dir;
    write_text(dir.file("c.obj"), cube_obj());
    const MeshStats st = mesh_stats(read_mesh(dir.file("c.obj")));
    EXPECT_EQ(st.vertices, 8);
    EXPECT_EQ(st.faces, 6);
    EXPECT_EQ(st.quads, 6);
    EXPECT_EQ(st.shells, 1);
    EXPECT_EQ(st.boundary_edges, 0);
    EXPECT_EQ(st.non_manifold_edges, 0);
    EXPECT_EQ(st.duplicate_vertices, 0);
    EXPECT_EQ(st.degenerate_faces, 0);
}

TEST(MeshStats, CountsBoundaryNonManifoldDuplicatesDegenerateAndShells)
{
    // Three triangles sharing edge (1,2) (a fin: non-manifold), one triangle elsewhere whose
    // vertices duplicate positions of nothing, and one zero-area triangle.
    PolygonSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {5, 5, 5}, {6, 5, 5}, {5, 6, 5}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    const int32_t f0[] = {0, 1, 2}, f1[] = {1, 0, 3}, f2[] = {0, 1, 4}, f3[] = {5, 6, 7}, f4[] = {8, 9, 10};
    for (auto f : {std::span<const int32_t>(f0), std::span<const int32_t>(f1), std::span<const int32_t>(f2), std::span<const int32_t>(f3),
                   std::span<const int32_t>(f4)})
        s.add_face(f);
    const MeshStats st = mesh_stats(s);
    EXPECT_EQ(st.duplicate_vertices, 1);        // point 8 repeats point 1
    EXPECT_EQ(st.non_manifold_edges, 1);        // edge (0,1) used three times
    EXPECT_EQ(st.boundary_edges, 6 + 3 + 3);    // fin's outer edges, triangle f3, triangle f4
    EXPECT_EQ(st.degenerate_faces, 1);          // f4 is collinear
    EXPECT_EQ(st.shells, 2);                    // f4 touches the fin through the welded point 8 == 1
    EXPECT_EQ(st.triangles, 5);
}

TEST(MeshIoObj, RejectsMalformedInput)
{
    TempDir dir;
    expect_mesh_error(dir.file("empty.obj"), "", "empty.obj: file is empty");
    expect_mesh_error(dir.file("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9001\n", "range.obj:4: vertex index 9001 out of range (3 vertices)");
    expect_mesh_error(dir.file("nan.obj"), "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "nan.obj:2: vertex coordinate is not finite");
    expect_mesh_error(dir.file("curves.obj"), "v 0 0 0\nv 1 0 0\nl 1 2\n", "these are curves");
    expect_mesh_error(dir.file("edge.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 3 1\n",
                      "edge.obj:5: expected a face of 3 or more vertex indices, found 2");
}

TEST(MeshIoObj, WriteReadRoundTripKeepsFaces)
{
    TempDir dir;
    write_text(dir.file("c.obj"), cube_obj());
    const PolygonSoup a = read_mesh(dir.file("c.obj"));
    write_mesh(a, dir.file("d.obj"));
    const PolygonSoup b = read_mesh(dir.file("d.obj"));
    EXPECT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(a.face_offsets, b.face_offsets);
    EXPECT_EQ(a.face_indices, b.face_indices);
}

TEST(MeshIoReal, PonytailHeadKeepsEveryFace)
{
    GROOM_REQUIRE_SHARED(path, "amd_tressfx_ponytail/ponytail_head.obj");
    const PolygonSoup s = read_mesh(path);
    EXPECT_EQ(s.num_faces(), count_lines_starting(path, "f "));
    EXPECT_EQ(s.points.size(), count_lines_starting(path, "v "));
    const MeshStats st = mesh_stats(s);
    // The dataset README: 11,744 vertices, 17,894 triangles, 2,604 duplicates, 108 non-manifold edges after welding.
    EXPECT_EQ(st.vertices, 11744);
    EXPECT_EQ(st.faces, 17894);
    EXPECT_EQ(st.duplicate_vertices, 2604);
    EXPECT_EQ(st.non_manifold_edges, 108);
}

TEST(MeshIoOff, ReadsCubeWithCommentsAndColours)
{
    TempDir dir;
    write_text(dir.file("c.off"), "OFF # cube\n8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                  "4 0 3 2 1 255 0 0\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n");
    const PolygonSoup s = read_mesh(dir.file("c.off"));
    EXPECT_EQ(s.num_faces(), 6u);
    const MeshStats st = mesh_stats(s);
    EXPECT_EQ(st.boundary_edges, 0);
    EXPECT_EQ(st.shells, 1);
    expect_mesh_error(dir.file("r.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "r.off:6: vertex index 3 out of range (3 vertices)");
    expect_mesh_error(dir.file("h.off"), "OFF\n4000000000 1 0\n0 0 0\n", "header claims 4000000000 vertices");
}

TEST(MeshIoStl, AsciiAndBinaryKeepEveryTriangle)
{
    TempDir dir;
    write_text(dir.file("a.stl"), "solid t\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n"
                                  "facet normal 0 0 1\n outer loop\n  vertex 1 0 0\n  vertex 1 1 0\n  vertex 0 1 0\n endloop\nendfacet\nendsolid t\n");
    const PolygonSoup a = read_mesh(dir.file("a.stl"));
    EXPECT_EQ(a.num_faces(), 2u);
    EXPECT_EQ(a.points.size(), 6u);
    const MeshStats st = mesh_stats(a);
    EXPECT_EQ(st.duplicate_vertices, 2);
    EXPECT_EQ(st.boundary_edges, 4);  // a unit square made of two triangles
    // Binary: header starting with "solid" on purpose (some exporters do this).
    std::string b = "solid but binary";
    b.resize(80, ' ');
    const uint32_t n = 2;
    b.append(reinterpret_cast<const char*>(&n), 4);
    const float tri[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 0}};
    for (const auto& t : tri) {
        b.append(reinterpret_cast<const char*>(t), 48);
        b.append(2, '\0');
    }
    write_text(dir.file("b.stl"), b);
    const PolygonSoup bs = read_mesh(dir.file("b.stl"));
    EXPECT_EQ(bs.num_faces(), 2u);
    EXPECT_EQ(bs.points[4], float3(1, 1, 0));
    write_text(dir.file("t.stl"), b.substr(0, b.size() - 10));
    expect_mesh_error(dir.file("t.stl"), b.substr(0, b.size() - 10), "binary STL claims 2 triangles (184 bytes) but the file has 174 bytes");
    expect_mesh_error(dir.file("e.stl"), "solid x\nfacet normal 0 0 1\n outer loop\n  vertex 0 0\n", "e.stl:4: expected 3 vertex coordinates");
}

TEST(MeshIoPly, WriteReadRoundTripKeepsNgons)
{
    TempDir dir;
    write_text(dir.file("m.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 1.5 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4 5\nf 2 6 3\n");
    const PolygonSoup a = read_mesh(dir.file("m.obj"));
    write_mesh(a, dir.file("m.ply"));
    const PolygonSoup b = read_mesh(dir.file("m.ply"));
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.face_offsets, b.face_offsets);
    EXPECT_EQ(a.face_indices, b.face_indices);
    expect_mesh_error(dir.file("r.ply"), "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                                         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 0 5\n",
                      "face 0 uses vertex 5, out of range (1 vertices)");
}

TEST(MeshIoReal, HeadsMatchTheDatasetReadme)
{
    // Figures from ../shared/datasets/README.md, written by whoever gathered the data.
    struct Expect {
        const char* file;
        int64_t vertices, duplicates, non_manifold, shells;  // -1 = not stated there
        bool closed;
    };
    const Expect cases[] = {
        {"ict_facekit/generic_neutral_mesh.obj", 26719, 345, 103, -1, false},
        {"makehuman/base.obj", 19158, -1, -1, 154, false},
        {"lee_perry_smith/LeePerrySmith.obj", 8838, -1, -1, -1, true},
        {"nefertiti_scan/nefertiti-lowres.obj", 35002, -1, -1, -1, true},
        {"sintel_frostbitten/sintel-collider.obj", 341, -1, -1, 1, true},
        {"sintel_frostbitten/sintel.obj", 3046, -1, -1, -1, false},
    };
    for (const Expect& e : cases) {
        GROOM_REQUIRE_SHARED(path, e.file);
        const PolygonSoup s = read_mesh(path);
        EXPECT_EQ(s.num_faces(), count_lines_starting(path, "f ")) << e.file;
        const MeshStats st = mesh_stats(s);
        EXPECT_EQ(st.vertices, e.vertices) << e.file;
        if (e.duplicates >= 0) EXPECT_EQ(st.duplicate_vertices, e.duplicates) << e.file;
        if (e.non_manifold >= 0) EXPECT_EQ(st.non_manifold_edges, e.non_manifold) << e.file;
        if (e.shells >= 0) EXPECT_EQ(st.shells, e.shells) << e.file;
        if (e.closed) EXPECT_EQ(st.boundary_edges, 0) << e.file;
        else EXPECT_GT(st.boundary_edges, 0) << e.file;
    }
}
