// Animated grooms (cli/frame_options.h): --frames patterns, a rigidly moving scalp (--scalp-xform),
// coherence of a groom from frame to frame, --shard and `groom merge`.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace groom;
using groom::test::run_groom;

namespace {

constexpr float kRadius = 10.0f;  // the sphere scalp, centred at the origin

/// 60 guides of 10 points rooted on the sphere's upper cap, growing 4 units along the normal, then
/// bent in the plane of the normal and +X: joint i turns by bend * i / 9 radians, so each segment keeps
/// its length (an isometric bend: arc-length resampling picks the same segment and fraction every
/// frame).
CurveSet sphere_guides(float bend)
{
    const int n = 60, k = 10;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(n, k));
    auto P = cs.positions_for_write();
    for (int c = 0; c < n; ++c) {
        const float polar = 0.8f * std::sqrt((float(c) + 0.5f) / float(n)), az = 2.39996323f * float(c);
        const float3 nrm{std::sin(polar) * std::cos(az), std::cos(polar), std::sin(polar) * std::sin(az)};
        const float3 side = normalize(cross(nrm, float3(0, 0, 1)), float3(1, 0, 0));
        float3 p = nrm * kRadius;
        float angle = 0.0f;
        for (int i = 0; i < k; ++i) {
            P[c * k + i] = p;
            angle += bend * float(i) / float(k - 1);
            p = p + (nrm * std::cos(angle) + side * std::sin(angle)) * (4.0f / float(k - 1));
        }
    }
    return cs;
}

struct Pose {
    double r[3][3];
    double t[3];
};

/// A turn of `deg` degrees about the axis (0.3, 1, 0.2) and a shift: a head turning and bobbing.
Pose pose_at(int frame)
{
    const double deg = 7.5 * frame, a = deg * M_PI / 180.0;
    double ax[3] = {0.3, 1.0, 0.2};
    const double len = std::sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    for (double& v : ax) v /= len;
    const double c = std::cos(a), s = std::sin(a), C = 1 - c;
    const double x = ax[0], y = ax[1], z = ax[2];
    return {{{c + x * x * C, x * y * C - z * s, x * z * C + y * s},
             {y * x * C + z * s, c + y * y * C, y * z * C - x * s},
             {z * x * C - y * s, z * y * C + x * s, c + z * z * C}},
            {0.5 * frame, -0.25 * frame, 3.0 + 0.1 * frame}};
}

float3 apply(const Pose& p, const float3& v)
{
    const double in[3] = {v.x, v.y, v.z};
    double o[3];
    for (int i = 0; i < 3; ++i) o[i] = p.r[i][0] * in[0] + p.r[i][1] * in[1] + p.r[i][2] * in[2] + p.t[i];
    return {float(o[0]), float(o[1]), float(o[2])};
}

float3 apply_inverse(const Pose& p, const float3& v)
{
    const double d[3] = {v.x - p.t[0], v.y - p.t[1], v.z - p.t[2]};
    double o[3];
    for (int i = 0; i < 3; ++i) o[i] = p.r[0][i] * d[0] + p.r[1][i] * d[1] + p.r[2][i] * d[2];
    return {float(o[0]), float(o[1]), float(o[2])};
}

/// The xform file for frames [0, frames): 3x4 matrices, 17 significant digits (exact doubles).
std::string write_poses(const test::TempDir& dir, int frames)
{
    std::string text = "# frame, then [R|t] row by row\n";
    char buf[64];
    for (int f = 0; f < frames; ++f) {
        const Pose p = pose_at(f);
        text += std::to_string(f);
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 4; ++j) {
                std::snprintf(buf, sizeof buf, " %.17g", j < 3 ? p.r[i][j] : p.t[i]);
                text += buf;
            }
        }
        text += "\n";
    }
    const std::string path = dir.file("poses.txt");
    test::write_text(path, text);
    return path;
}

std::string frame_file(const test::TempDir& dir, const std::string& stem, int frame, const std::string& ext)
{
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04d", frame);
    return dir.file(stem + "." + buf + "." + ext);
}

std::string sphere_mesh(const test::TempDir& dir)
{
    const std::string path = dir.file("sphere.obj");
    write_mesh(icosphere(float3(0, 0, 0), kRadius, 4), path);
    return path;
}

float largest_jump(const CurveSet& a, const CurveSet& b)
{
    EXPECT_EQ(a.num_points(), b.num_points());
    float worst = 0.0f;
    for (size_t i = 0; i < std::min(a.num_points(), b.num_points()); ++i) worst = std::max(worst, length(a.positions()[i] - b.positions()[i]));
    return worst;
}

}  // namespace

TEST(FramesCli, PatternsAreFilledPerFrameAndAnOutputWithoutOneIsRefused)
{
    test::TempDir dir;
    const std::string scalp = sphere_mesh(dir);
    for (int f = 3; f <= 5; ++f) write_curves(sphere_guides(0.05f * float(f)), frame_file(dir, "guides", f, "usda"));
    const auto r = run_groom({"generate", dir.file("guides.####.usda"), "--scalp", scalp, "--count", "50", "--frames", "3:5", "-o",
                              dir.file("hair.####.usda"), "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (int f = 3; f <= 5; ++f) EXPECT_EQ(read_curves(frame_file(dir, "hair", f, "usda")).num_curves(), 50u) << f;
    EXPECT_FALSE(std::filesystem::exists(frame_file(dir, "hair", 2, "usda")));

    const auto bad = run_groom({"generate", dir.file("guides.####.usda"), "--scalp", scalp, "--count", "50", "--frames", "3:5", "-o",
                                dir.file("one.usda")});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("frame pattern"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("one.usda")));

    const auto missing = run_groom({"generate", dir.file("guides.####.usda"), "--scalp", scalp, "--count", "50", "--frames", "3:6", "-o",
                                    dir.file("m.####.usda"), "--quiet"});
    EXPECT_NE(missing.exit_code, 0);
    EXPECT_NE(missing.err.find("1 of the 4 frames' files are missing"), std::string::npos) << missing.err;
    EXPECT_NE(missing.err.find("guides.0006.usda"), std::string::npos) << missing.err;
    // Found before any frame runs: frames 3-5, which have their guides, are not written either (a
    // trial's farm job wrote the frames before the missing one, then stopped).
    for (int f = 3; f <= 6; ++f) EXPECT_FALSE(std::filesystem::exists(frame_file(dir, "m", f, "usda"))) << f;

    // With --scalp-xform or --shard the command writes through memory; the real file is still
    // refused when it is an input.
    const auto onto_input = run_groom({"curl", frame_file(dir, "guides", 3, "usda"), "--shard", "0/2", "-o", frame_file(dir, "guides", 3, "usda")});
    EXPECT_EQ(onto_input.exit_code, 2);
    EXPECT_NE(onto_input.err.find("also an input"), std::string::npos) << onto_input.err;

    for (const char* spec : {"5:3", "a:b", "-1:2"}) {
        const auto r2 = run_groom({"generate", dir.file("guides.####.usda"), "--scalp", scalp, "--count", "5", "--frames", spec, "-o",
                                   dir.file("x.####.usda")});
        EXPECT_EQ(r2.exit_code, 2) << spec;
        EXPECT_NE(r2.err.find("--frames"), std::string::npos) << r2.err;
    }
}

TEST(FramesCli, ScalpXformFileErrorsNameTheLine)
{
    test::TempDir dir;
    const std::string scalp = sphere_mesh(dir);
    write_curves(sphere_guides(0.0f), dir.file("g.usda"));
    test::write_text(dir.file("sheared.txt"), "0 0 0 0 0 0 0\n1 1 0.5 0 0  0 1 0 0  0 0 1 0\n");
    const auto r = run_groom({"generate", dir.file("g.usda"), "--scalp", scalp, "--count", "5", "--frames", "0:1", "--scalp-xform",
                              dir.file("sheared.txt"), "-o", dir.file("x.####.usda")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("sheared.txt:2"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("rigid"), std::string::npos) << r.err;
    test::write_text(dir.file("short.txt"), "0 0 0 0 0 0 0\n");
    const auto r2 = run_groom({"generate", dir.file("g.usda"), "--scalp", scalp, "--count", "5", "--frames", "0:1", "--scalp-xform",
                               dir.file("short.txt"), "-o", dir.file("x.####.usda")});
    EXPECT_EQ(r2.exit_code, 2);
    EXPECT_NE(r2.err.find("no pose for frame 1"), std::string::npos) << r2.err;
    EXPECT_FALSE(std::filesystem::exists(frame_file(dir, "x", 0, "usda")));
    // A translation past any scene: named by its line, not as a non-finite point of the output.
    test::write_text(dir.file("far.txt"), "0 0 0 0 0 0 0\n1 1e40 0 0 0 0 0\n");
    const auto r3 = run_groom({"generate", dir.file("g.usda"), "--scalp", scalp, "--count", "5", "--frames", "0:1", "--scalp-xform",
                               dir.file("far.txt"), "-o", dir.file("x.####.usda")});
    EXPECT_NE(r3.exit_code, 0);
    EXPECT_NE(r3.err.find("far.txt:2: expected a translation within 1e15 scene units, found 1e+40"), std::string::npos) << r3.err;
}

// A head and its guides that move rigidly: every frame's groom is frame 0's moved by the pose
// P_f P_0^-1. The command runs in the scalp's rest frame (the guides come in through P_f^-1), so
// roots, ids and random draws are the same on every frame; what differs is float rounding of the
// guides' round trip (a few ulps of the scene's size, about 20: 2e-6) carried through the blend and
// of the final transform. Tolerance: 2e-5 scene units, 1e-6 of the scene's size.
TEST(FramesCli, RigidlyMovingHeadAndGuidesGiveFrameZerosGroomMoved)
{
    test::TempDir dir;
    const std::string scalp = sphere_mesh(dir);
    const int frames = 4;
    const std::string poses = write_poses(dir, frames);
    const CurveSet rest = sphere_guides(0.3f);
    for (int f = 0; f < frames; ++f) {
        CurveSet g = rest;
        for (float3& p : g.positions_for_write()) p = apply(pose_at(f), p);
        write_curves(g, frame_file(dir, "guides", f, "usda"));
    }
    for (const char* command : {"generate", "curl"}) {
        std::vector<std::string> args{command, dir.file("guides.####.usda"), "--scalp", scalp, "--frames", "0:3", "--scalp-xform", poses,
                                      "-o", dir.file(std::string(command) + ".####.usda"), "--quiet"};
        if (std::string(command) == "generate") args.insert(args.end(), {"--count", "300", "--seed", "9"});
        else args.insert(args.end(), {"--type", "3b", "--seed", "4"});
        const auto r = run_groom(args);
        ASSERT_EQ(r.exit_code, 0) << command << ": " << r.err;
        const CurveSet f0 = read_curves(frame_file(dir, command, 0, "usda"));
        ASSERT_GT(f0.num_curves(), 0u);
        for (int f = 1; f < frames; ++f) {
            const CurveSet ff = read_curves(frame_file(dir, command, f, "usda"));
            ASSERT_EQ(ff.num_points(), f0.num_points()) << command << " frame " << f;
            EXPECT_EQ(ff.curve_ids(), f0.curve_ids()) << command << " frame " << f;
            float worst = 0.0f;
            for (size_t i = 0; i < f0.num_points(); ++i) {
                const float3 expect = apply(pose_at(f), apply_inverse(pose_at(0), f0.positions()[i]));
                worst = std::max(worst, length(ff.positions()[i] - expect));
            }
            EXPECT_LT(worst, 2e-5f) << command << " frame " << f;
            std::printf("%s frame %d: largest distance from frame 0's groom moved %.3g\n", command, f, worst);
        }
    }
}

// --scalp-xform and --shard run the command on memory paths ("mem:PATH"): what it prints names
// the user's files instead (a trial read "generate: ... -> mem:out.0000.usda").
TEST(FramesCli, MessagesNameTheUsersFilesNotTheMemoryPaths)
{
    test::TempDir dir;
    const std::string scalp = sphere_mesh(dir);
    const std::string poses = write_poses(dir, 2);
    for (int f = 0; f < 2; ++f) {
        CurveSet g = sphere_guides(0.3f);
        for (float3& p : g.positions_for_write()) p = apply(pose_at(f), p);
        write_curves(g, frame_file(dir, "guides", f, "usda"));
    }
    const auto posed = run_groom({"curl", dir.file("guides.####.usda"), "--scalp", scalp, "--frames", "0:1", "--scalp-xform", poses, "-o",
                                  dir.file("curl.####.usda"), "--type", "3b", "--verbose"});
    ASSERT_EQ(posed.exit_code, 0) << posed.err;
    EXPECT_NE(posed.err.find(frame_file(dir, "curl", 1, "usda")), std::string::npos) << posed.err;
    const auto shard = run_groom({"curl", frame_file(dir, "guides", 0, "usda"), "-o", dir.file("part.usda"), "--shard", "1/2", "--type", "3b"});
    ASSERT_EQ(shard.exit_code, 0) << shard.err;
    EXPECT_NE(shard.err.find(dir.file("part.usda")), std::string::npos) << shard.err;
    for (const auto* r : {&posed, &shard}) EXPECT_EQ(r->err.find("mem:"), std::string::npos) << r->err;
}

// Guides that bend smoothly (every joint turns a little more each frame) over a still head. The
// roots stay (they come from the scalp and the seed), and generate blends each guide's offsets from
// its root with weights of the root alone, turned by a rotation of the root alone: a generated point
// moves by a convex combination of the guides' resampled point moves, and a resampled point of an
// isometric bend sits on the same segment at the same fraction, so it moves no more than that
// segment's ends. Bound: the largest jump of any output point <= 1.0 x the guides' largest jump
// (+1e-5 for rounding). Curl then winds each hair around that centreline with the centreline's own
// frame: a point at radius r off it moves by at most the centreline's move plus r times the turn of
// that frame. Here the frame turns by at most 0.2 rad a frame (the tip's bend grows by 0.04 x 45/9)
// and curl type 3a's radius is well under the 0.24 the guides' points jump, so: curl's largest jump
// <= 1.5 x the guides' (measured 1.01 x; generate's 1.00 x).
TEST(FramesCli, HairFollowsABendingGuideWithoutJumps)
{
    test::TempDir dir;
    const std::string scalp = sphere_mesh(dir);
    const int frames = 6;
    std::vector<CurveSet> guides;
    for (int f = 0; f < frames; ++f) {
        guides.push_back(sphere_guides(0.04f * float(f)));
        write_curves(guides.back(), frame_file(dir, "guides", f, "usda"));
    }
    float guide_jump = 0.0f;
    for (int f = 1; f < frames; ++f) guide_jump = std::max(guide_jump, largest_jump(guides[f - 1], guides[f]));
    ASSERT_GT(guide_jump, 0.05f);

    const auto r = run_groom({"generate", dir.file("guides.####.usda"), "--scalp", scalp, "--count", "400", "--seed", "2", "--frames",
                              "0:5", "-o", dir.file("hair.####.usda"), "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto c = run_groom({"curl", dir.file("hair.####.usda"), "--frames", "0:5", "--type", "3a", "--seed", "1", "-o",
                              dir.file("curl.####.usda"), "--quiet"});
    ASSERT_EQ(c.exit_code, 0) << c.err;
    std::vector<CurveSet> hair, curled;
    for (int f = 0; f < frames; ++f) {
        hair.push_back(read_curves(frame_file(dir, "hair", f, "usda")));
        curled.push_back(read_curves(frame_file(dir, "curl", f, "usda")));
    }
    float hair_jump = 0.0f, curl_jump = 0.0f;
    for (int f = 1; f < frames; ++f) {
        ASSERT_EQ(hair[f].curve_ids(), hair[0].curve_ids());
        for (size_t cidx = 0; cidx < hair[f].num_curves(); ++cidx) {
            const int64_t root = hair[f].points_of(cidx).begin;
            EXPECT_EQ(length(hair[f].positions()[root] - hair[0].positions()[root]), 0.0f) << "root of curve " << cidx << " moved";
        }
        hair_jump = std::max(hair_jump, largest_jump(hair[f - 1], hair[f]));
        curl_jump = std::max(curl_jump, largest_jump(curled[f - 1], curled[f]));
    }
    EXPECT_LE(hair_jump, 1.0f * guide_jump + 1e-5f) << "guides' largest jump " << guide_jump;
    EXPECT_LE(curl_jump, 1.5f * guide_jump) << "guides' largest jump " << guide_jump;
    std::printf("guides' largest frame-to-frame jump %.4f, generate's %.4f (%.2fx), curl's %.4f (%.2fx)\n", guide_jump, hair_jump,
                hair_jump / guide_jump, curl_jump, curl_jump / guide_jump);
}

// A frame pattern of head meshes: the field is rebuilt only on the frames whose mesh differs from the
// frame before's (a head that holds still costs nothing), and a rigid head named once is built once.
TEST(FramesCli, ADeformingHeadIsRebuiltOnlyWhenItsMeshChanges)
{
    test::TempDir dir;
    write_mesh(icosphere(float3(0, 0, 0), kRadius, 3), frame_file(dir, "head", 0, "obj"));
    std::filesystem::copy_file(frame_file(dir, "head", 0, "obj"), frame_file(dir, "head", 1, "obj"));
    write_mesh(icosphere(float3(0, 0, 0), kRadius * 1.05f, 3), frame_file(dir, "head", 2, "obj"));
    std::filesystem::copy_file(frame_file(dir, "head", 2, "obj"), frame_file(dir, "head", 3, "obj"));
    write_curves(sphere_guides(0.0f), dir.file("g.usda"));
    const auto r = run_groom({"generate", dir.file("g.usda"), "--scalp", dir.file("head.####.obj"), "--count", "20", "--frames", "0:3", "-o",
                              dir.file("h.####.usda")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("4 frames"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("scalp field built 2 times"), std::string::npos) << r.err;
    const auto once = run_groom({"generate", dir.file("g.usda"), "--scalp", frame_file(dir, "head", 0, "obj"), "--count", "20", "--frames",
                                 "0:3", "-o", dir.file("k.####.usda")});
    ASSERT_EQ(once.exit_code, 0) << once.err;
    EXPECT_NE(once.err.find("scalp field built once"), std::string::npos) << once.err;
}
