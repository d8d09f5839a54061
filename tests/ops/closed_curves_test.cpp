// Closed curves (a hairline) through every curve format and the ops that keep or make curves: a loop
// read from USD `wrap = "periodic"`, an OBJ record back to its first vertex or a loop of edges comes
// back a loop when written again (`groom convert` of a hairline had written it open, its ends on top
// of each other: a trial), and curves made from loops are not loops.
#include "kernel/curve_set_edit.h"
#include "kernel/io/curve_io.h"
#include "kernel/math/polyline.h"
#include "ops/resample.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace groom;
using groom::test::read_bytes;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

/// A 12-gon of radius 1 in the XZ plane, each point once, with a per-point `width` i / 10.
CurveSet twelve_gon()
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>{12});
    auto P = cs.positions_for_write();
    auto w = cs.add<float>(Domain::Point, attr::width);
    for (int i = 0; i < 12; ++i) {
        const float a = float(i) * float(M_PI) / 6.0f;
        P[size_t(i)] = {std::cos(a), 0.0f, std::sin(a)};
        w[size_t(i)] = float(i) / 10.0f;
    }
    return cs;
}

/// The loop as readers give it: 13 points, the first repeated at the end.
void expect_loop(const CurveSet& cs, const std::string& what)
{
    ASSERT_EQ(cs.num_curves(), 1u) << what;
    ASSERT_EQ(cs.num_points(), 13u) << what;
    EXPECT_TRUE(is_closed(cs)) << what;
    const auto P = cs.positions();
    const CurveSet ref = twelve_gon();
    for (size_t i = 0; i < 13; ++i) EXPECT_EQ(P[i], ref.positions()[i % 12]) << what << " point " << i;
}

}  // namespace

TEST(ClosedCurves, ALoopWrittenClosedReadsBackClosedInEveryFormatThatSaysSo)
{
    TempDir dir;
    CurveWriteOptions closed;
    closed.closed = true;
    for (const std::string ext : {"usda", "obj", "ply"}) {
        // Written closed (as `groom hairline` writes), read back, written again with no option
        // (as `groom convert` does) and read again: the same loop each time.
        const std::string a = dir.file("a." + ext), b = dir.file("b." + ext);
        write_curves(twelve_gon(), a, closed);
        const CurveSet first = read_curves(a);
        expect_loop(first, a);  // .ply too: the first point repeated and the mark (`hairline -o h.ply` wrote it open: a review)
        write_curves(first, b);
        const CurveSet second = read_curves(b);
        expect_loop(second, b);
        EXPECT_EQ(read_bytes(a), read_bytes(b)) << ext << ": a loop written closed again is the same file";
    }
    // .usda: periodic, each point (and its width) once.
    const std::string usda = read_bytes(dir.file("b.usda"));
    EXPECT_NE(usda.find("wrap = \"periodic\""), std::string::npos) << usda;
    EXPECT_NE(usda.find("curveVertexCounts = [12]"), std::string::npos) << usda;
    EXPECT_EQ(usda.find("closed"), std::string::npos) << "the loop is said by wrap, not by a primvar";
    EXPECT_EQ(read_curves(dir.file("b.usda")).find<float>(Domain::Point, attr::width).size(), 13u);
    // .obj: 12 vertices, the record back to the first.
    const std::string obj = read_bytes(dir.file("b.obj"));
    size_t vertices = 0;
    for (size_t at = obj.find("\nv "); at != std::string::npos; at = obj.find("\nv ", at + 1)) ++vertices;
    EXPECT_EQ(vertices, 12u);
    EXPECT_NE(obj.find("l 1 2 3 4 5 6 7 8 9 10 11 12 1\n"), std::string::npos) << obj;
    // .hair cannot say it, but keeps the loop's repeated point.
    write_curves(twelve_gon(), dir.file("h.hair"), closed);
    EXPECT_EQ(read_curves(dir.file("h.hair")).num_points(), 13u);
    // Through .ply (its points as they are, with the detail) into .usda: periodic again.
    const std::string looped = dir.file("looped.ply");
    write_curves(read_curves(dir.file("a.usda")), looped);
    write_curves(read_curves(looped), dir.file("c.usda"));
    EXPECT_EQ(read_bytes(dir.file("c.usda")), usda);
}

TEST(ClosedCurves, LoopsOfEdgesAndOpenCurvesReadAsTheyAre)
{
    TempDir dir;
    // Blender's closed curve: a loop of two-point records.
    std::string edges;
    for (int i = 0; i < 4; ++i) edges += "v " + std::to_string(i % 2) + " 0 " + std::to_string(i / 2) + "\n";
    edges += "l 1 2\nl 2 4\nl 4 3\nl 3 1\n";
    write_text(dir.file("loop.obj"), edges);
    CurveReadOptions loops;
    loops.closed_loops = true;
    const CurveSet square = read_curves(dir.file("loop.obj"), loops);
    EXPECT_TRUE(is_closed(square));
    EXPECT_EQ(square.num_points(), 5u);
    // An open curve, and a file holding an open curve beside a loop, are not closed.
    write_text(dir.file("open.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\n");
    EXPECT_FALSE(is_closed(read_curves(dir.file("open.obj"))));
    write_text(dir.file("mixed.usda"), "#usda 1.0\ndef BasisCurves \"a\" {\n uniform token type = \"linear\"\n uniform token wrap = \"periodic\"\n"
                                       " int[] curveVertexCounts = [3]\n point3f[] points = [(0,0,0),(1,0,0),(1,1,0)]\n}\n"
                                       "def BasisCurves \"b\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
                                       " point3f[] points = [(0,0,0),(1,0,0)]\n}\n");
    // A file's mark does not make an open curve a loop: an .obj's `closed 1` comment beside an open
    // record (a trial's second curve came out periodic), a .ply's beside an open curve.
    write_text(dir.file("marked.obj"), "# groom detail closed int 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3 1\nl 1 2\n");
    EXPECT_FALSE(is_closed(read_curves(dir.file("marked.obj"))));
    write_text(dir.file("marked.ply"), "ply\nformat ascii 1.0\ncomment groom detail closed int 1\nelement vertex 2\nproperty float x\n"
                                       "property float y\nproperty float z\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n"
                                       "end_header\n0 0 0\n1 0 0\n0 1\n");
    EXPECT_FALSE(is_closed(read_curves(dir.file("marked.ply"))));
    const CurveSet mixed = read_curves(dir.file("mixed.usda"));
    EXPECT_EQ(mixed.num_points(), 6u);  // the loop's first point repeated
    EXPECT_FALSE(is_closed(mixed));
    write_curves(mixed, dir.file("mixed_out.usda"));
    EXPECT_NE(read_bytes(dir.file("mixed_out.usda")).find("wrap = \"nonperiodic\""), std::string::npos);
}

TEST(ClosedCurves, OpsThatKeepEachCurvesEndsKeepLoopsOthersDoNot)
{
    TempDir dir;
    CurveWriteOptions closed;
    closed.closed = true;
    write_curves(twelve_gon(), dir.file("h.usda"), closed);
    const CurveSet loop = read_curves(dir.file("h.usda"));
    ASSERT_TRUE(is_closed(loop));
    // Resampled: the ends stay where they were, so the curve is still the loop.
    ResampleParams rp;
    rp.count = 40;
    const CurveSet fine = resample(loop, rp);
    EXPECT_TRUE(is_closed(fine));
    EXPECT_EQ(fine.positions().front(), fine.positions().back());
    // At least a triangle: 2 or 3 points would be a point, or a line there and back (a trial's
    // `--count 2` wrote a periodic curve of length 0); a long segment length gives 4 points.
    for (const int64_t n : {2, 3}) {
        rp.count = n;
        EXPECT_THROW(resample(loop, rp), InvalidParam) << n;
    }
    rp.count = 0;
    rp.segment_length = 1e6f;
    const CurveSet coarse = resample(loop, rp);
    ASSERT_EQ(coarse.num_points(), 4u);
    EXPECT_GT(polyline_length(coarse.positions()), 0.5f * polyline_length(loop.positions()));
    // Selected: the same loops. Joined to an open curve: not all loops.
    EXPECT_TRUE(is_closed(remove_curves(loop, std::vector<char>{0})));
    EXPECT_FALSE(is_closed(join(loop, CurveSet::from_counts(std::vector<int64_t>{2}))));
    // Curves made from loops by an op (carry_curve_attributes) are not loops.
    CurveSet made = CurveSet::from_counts(std::vector<int64_t>{5});
    carry_curve_attributes(loop, made, std::vector<int64_t>{0});
    EXPECT_FALSE(is_closed(made));
}
