// The --hairline file as every command reads it (cli/region_options.cpp read_hairline): a closed
// hairline in any of the forms DCCs and groom write it is the same hairline as the open one.
#include "test_support.h"

#include "kernel/io/curve_io.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

using namespace groom;
using groom::test::read_bytes;
using groom::test::run_groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

std::string exact(float v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
}

}  // namespace

// A user trial on the ICT head: `groom hairline` wrote its curve open (wrap "nonperiodic", the first
// point not repeated), so DCCs showed a gap; the same hairline closed (USD's periodic wrap, an OBJ
// record ending at its first vertex, Blender's loop of edges) was refused by cornrow-guides and
// gather ("point 180 turns back", "vertex 1 lies on a closed loop ... curves must be open chains")
// and taken by edges. Now each form gives every command the same bytes as the open one, and
// `groom hairline` writes it closed. A hairline that runs on past its start is refused still.
TEST(RegionOptions, AClosedHairlineInEveryFormIsTheOpenOne)
{
    TempDir dir;
    const std::string head = dir.file("head.obj"), scalp = dir.file("head.vdb");
    ASSERT_EQ(run_groom({"head", "-o", head, "--resolution", "32", "-q"}).exit_code, 0);
    ASSERT_EQ(run_groom({"scalp", head, "-o", scalp, "-q"}).exit_code, 0);
    const std::string periodic = dir.file("hl.usda");
    ASSERT_EQ(run_groom({"hairline", "--scalp", scalp, "-o", periodic, "--points", "120", "-q"}).exit_code, 0);
    EXPECT_NE(read_bytes(periodic).find("uniform token wrap = \"periodic\""), std::string::npos);

    // The open form, and the closed ones made from it.
    const CurveSet closed = read_curves(periodic);
    ASSERT_EQ(closed.num_points(), 121u);
    const auto P = closed.positions();
    ASSERT_EQ(P.front(), P.back());
    CurveSet open = CurveSet::from_counts(std::vector<int64_t>{120});
    std::copy(P.begin(), P.end() - 1, open.positions_for_write().begin());
    write_curves(open, dir.file("open.usda"));
    write_curves(closed, dir.file("repeated.usda"));
    CurveWriteOptions as_closed;
    as_closed.closed = true;
    write_curves(open, dir.file("closed.obj"), as_closed);
    std::string verts, obj_edges, ply_edges;
    for (size_t i = 0; i < 120; ++i) {
        const float3 p = P[i];
        verts += exact(p.x) + " " + exact(p.y) + " " + exact(p.z) + "\n";
        obj_edges += "l " + std::to_string(i + 1) + " " + std::to_string((i + 1) % 120 + 1) + "\n";  // Blender: one record an edge
        ply_edges += std::to_string(i) + " " + std::to_string((i + 1) % 120) + "\n";
    }
    std::string obj_verts;
    for (size_t at = 0, end; (end = verts.find('\n', at)) != std::string::npos; at = end + 1) obj_verts += "v " + verts.substr(at, end - at + 1);
    write_text(dir.file("loop.obj"), obj_verts + obj_edges);
    write_text(dir.file("loop.ply"), "ply\nformat ascii 1.0\nelement vertex 120\nproperty float x\nproperty float y\nproperty float z\n"
                                     "element edge 120\nproperty int vertex1\nproperty int vertex2\nend_header\n" + verts + ply_edges);

    ASSERT_EQ(run_groom({"puff", "--scalp", scalp, "-o", dir.file("puff.usda"), "--center", "4.8,9.5,-1.5", "--radius", "3", "--sphere-center",
                         "7.5,14,-1.5", "--sphere-radius", "6", "--rows", "4", "--cols", "4", "--hairs", "100", "-q"})
                  .exit_code,
              0);
    const auto outputs = [&](const std::string& hairline, const std::string& tag) {
        std::vector<std::string> bytes;
        const std::vector<std::vector<std::string>> commands = {
            {"cornrow-guides", "--scalp", scalp, "--count", "6"},
            {"gather", dir.file("puff.usda"), "--scalp", scalp, "--hairs", "300"},
            {"edges", "--scalp", scalp, "--count", "40"},
            {"sections", "--scalp", scalp, "--rows", "3", "--cols", "4"},
        };
        for (std::vector<std::string> args : commands) {
            const std::string out = dir.file(args[0] + "_" + tag + ".usda");
            args.insert(args.end(), {"--hairline", hairline, "-o", out, "-q"});
            const auto r = run_groom(args);
            EXPECT_EQ(r.exit_code, 0) << args[0] << " --hairline " << hairline << ": " << r.err;
            bytes.push_back(r.exit_code == 0 ? read_bytes(out) : r.err);
        }
        return bytes;
    };
    const std::vector<std::string> want = outputs(dir.file("open.usda"), "open");
    for (const char* form : {"hl.usda", "repeated.usda", "closed.obj", "loop.obj", "loop.ply"}) {
        std::string tag = form;
        tag[tag.find('.')] = '_';
        const std::vector<std::string> got = outputs(dir.file(form), tag);
        for (size_t k = 0; k < want.size(); ++k) EXPECT_TRUE(got[k] == want[k]) << form << ": command " << k << " differs from the open hairline's";
    }

    // Runs on past its start over its first five points: refused, naming the file and the point.
    CurveSet overlap = CurveSet::from_counts(std::vector<int64_t>{126});
    auto Q = overlap.positions_for_write();
    std::copy(P.begin(), P.end() - 1, Q.begin());
    std::copy(P.begin(), P.begin() + 6, Q.begin() + 120);
    write_curves(overlap, dir.file("overlap.usda"));
    for (const std::string cmd : {"cornrow-guides", "sections"}) {
        const auto r = run_groom({cmd, "--scalp", scalp, "--hairline", dir.file("overlap.usda"), "-o", dir.file("x.usda")});
        EXPECT_EQ(r.exit_code, 1) << cmd;
        EXPECT_NE(r.err.find("overlap.usda"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("point 125 turns back"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("x.usda")));
    }
    // Every command reads a loop of edges as the closed curve it is (Blender's closed curve; it had
    // been refused outside --hairline, so a hairline exported from Blender could not be converted).
    const auto info = run_groom({"info", dir.file("loop.obj")});
    EXPECT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("closed"), std::string::npos) << info.out;
}
