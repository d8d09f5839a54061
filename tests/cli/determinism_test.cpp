// Every op command, run with --threads 1 and --threads 2 on the same inputs and seed, must write
// byte-identical files (the brief: "bitwise identical output for any thread count"). The inputs
// are big enough (240 guides) that TBB really splits the work over both threads.
// A command joins the table when it lands on main; a case whose command is not registered fails.
// `groom scalp` too: OpenVDB stamps every .vdb with a random UUID, which write_scalp replaces by one
// made from the file's content.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <cmath>
#include <filesystem>

using namespace groom;
using groom::test::run_groom;

namespace {

/// 240 gently bent guides of 12 points over a 10 x 10 patch of the y = 0 plane, growing up +Y.
std::string write_guides(const test::TempDir& dir)
{
    const int n = 240, k = 12;
    std::vector<int64_t> counts(n, k);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (int c = 0; c < n; ++c) {
        const float x = float(c % 16) * 0.66f - 5.0f, z = float(c / 16) * 0.66f - 5.0f;
        for (int i = 0; i < k; ++i) {
            const float t = float(i) / float(k - 1);
            P[c * k + i] = {x + 0.4f * t * t * std::sin(float(c)), 6.0f * t, z + 0.4f * t * t * std::cos(float(c))};
        }
    }
    const std::string path = dir.file("guides.usda");
    write_curves(cs, path);
    return path;
}

/// 120 straight guides of 10 points, rooted on the upper cap of the sphere of radius 10 at the
/// origin and growing 4 units along its normal, on a golden-angle spiral.
std::string write_sphere_guides(const test::TempDir& dir)
{
    const int n = 120, k = 10;
    std::vector<int64_t> counts(n, k);
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (int c = 0; c < n; ++c) {
        const float polar = 0.9f * std::sqrt((float(c) + 0.5f) / float(n)), az = 2.39996323f * float(c);
        const float3 dir_out{std::sin(polar) * std::cos(az), std::cos(polar), std::sin(polar) * std::sin(az)};
        for (int i = 0; i < k; ++i) P[c * k + i] = dir_out * (10.0f + 4.0f * float(i) / float(k - 1));
    }
    const std::string path = dir.file("sphere_guides.usda");
    write_curves(cs, path);
    return path;
}

struct Case {
    const char* command;
    const char* output_ext;
    /// "{guides}" (240 guides on a plane), "{head}" (head mesh), "{sguides}" (guides on the sphere),
    /// "{sphere}" (the sphere's level set from `groom scalp`), "{puff}" (the puff case's output) and "{out}"
    /// are replaced.
    std::vector<std::string> args;
};

std::vector<Case> cases()
{
    return {
        {"project", "usda", {"project", "{guides}", "--scalp", "{sphere}", "-o", "{out}", "--mode", "root", "--offset", "0.1"}},
        {"cull", "usda", {"cull", "{sguides}", "--scalp", "{sphere}", "-o", "{out}", "--mode", "push", "--clearance", "0.5"}},
        {"cornrow-guides", "usda", {"cornrow-guides", "--scalp", "{head}", "-o", "{out}", "--count", "6"}},
        {"sections", "usda", {"sections", "--scalp", "{head}", "-o", "{out}", "--cols", "5", "--seed", "4"}},
        {"partition", "usda", {"partition", "{sguides}", "--scalp", "{sphere}", "-o", "{out}", "--count", "6", "--samples", "5"}},
        {"generate", "usda", {"generate", "{sguides}", "--scalp", "{sphere}", "-o", "{out}", "--count", "400", "--seed", "3"}},
        {"puff", "usda", {"puff", "--scalp", "{sphere}", "-o", "{out}", "--center", "0,12,0", "--radius", "3", "--sphere-center", "0,15,0",
                          "--sphere-radius", "6", "--rows", "5", "--cols", "4", "--hairs", "300", "--seed", "5"}},
        {"hairline", "usda", {"hairline", "--scalp", "{sphere}", "-o", "{out}"}},
        {"parting", "usda", {"parting", "--scalp", "{sphere}", "-o", "{out}", "--through", "0,0,20/0,20,0/0,0,-20"}},
        // The puff case's own output (run above) is the puff to gather into.
        {"gather", "usda", {"gather", "{puff}", "--scalp", "{sphere}", "-o", "{out}", "--hairs", "300", "--seed", "6"}},
        {"convert", "ply", {"convert", "{guides}", "-o", "{out}"}},
        {"resample", "usda", {"resample", "{guides}", "-o", "{out}", "--segment-length", "0.37"}},
        {"select", "usda", {"select", "{guides}", "-o", "{out}", "--ids", "0-2,5", "--invert"}},
        {"transform", "usda", {"transform", "{guides}", "-o", "{out}", "--rotate", "10,20,30", "--scale", "1.5,1,0.5", "--translate", "1,2,3"}},
        {"braid", "usda", {"braid", "{guides}", "-o", "{out}", "--strands", "3", "--frequency", "3", "--width", "0.5", "--fibers", "4"}},
        {"populate", "usda", {"populate", "{guides}", "-o", "{out}", "--count", "8", "--radius", "0.3", "--seed", "2"}},
        {"curl", "usda", {"curl", "{guides}", "-o", "{out}", "--type", "3b", "--uniformity", "0.4", "--seed", "7"}},
        {"head", "obj", {"head", "-o", "{out}", "--resolution", "96"}},
        {"scalp", "vdb", {"scalp", "{head}", "-o", "{out}"}},
        {"edges", "usda", {"edges", "--scalp", "{head}", "-o", "{out}", "--direction", "random", "--from", "-180", "--to", "180", "--seed", "4"}},
        {"render", "png", {"render", "{guides}", "--scalp", "{head}", "-o", "{out}", "--size", "160x120", "--color-by", "strand"}},
    };
}

struct Inputs {
    std::string guides, head, sguides, sphere, puff;
};

std::vector<std::string> expand(const std::vector<std::string>& args, const Inputs& in, const std::string& out)
{
    std::vector<std::string> r;
    for (const std::string& a : args) {
        r.push_back(a == "{guides}" ? in.guides : a == "{head}" ? in.head : a == "{sguides}" ? in.sguides
                    : a == "{sphere}" ? in.sphere : a == "{puff}" ? in.puff : a == "{out}" ? out : a);
    }
    return r;
}

}  // namespace

TEST(Determinism, EveryOpCommandWritesTheSameBytesWithOneAndTwoThreads)
{
    test::TempDir dir;
    Inputs in{write_guides(dir), dir.file("head.obj"), write_sphere_guides(dir), dir.file("sphere.vdb"), dir.file("puff_1.usda")};
    const auto h = run_groom({"head", "-o", in.head, "--resolution", "24"});
    ASSERT_EQ(h.exit_code, 0) << h.err;
    write_mesh(icosphere(float3(0, 0, 0), 10.0f, 4), dir.file("sphere.obj"));
    const auto sc = run_groom({"scalp", dir.file("sphere.obj"), "-o", in.sphere});
    ASSERT_EQ(sc.exit_code, 0) << sc.err;
    for (const Case& c : cases()) {
        std::string bytes[2];
        for (int threads : {1, 2}) {
            const std::string out = dir.file(std::string(c.command) + "_" + std::to_string(threads) + "." + c.output_ext);
            std::vector<std::string> args = expand(c.args, in, out);
            args.insert(args.end(), {"--threads", std::to_string(threads), "--quiet"});
            const auto r = run_groom(args);
            ASSERT_EQ(r.exit_code, 0) << c.command << " --threads " << threads << ": " << r.err;
            bytes[threads - 1] = test::read_bytes(out);
        }
        EXPECT_GT(bytes[0].size(), 100u) << c.command;
        EXPECT_TRUE(bytes[0] == bytes[1]) << c.command << ": output differs between --threads 1 and --threads 2 ("
                                          << bytes[0].size() << " vs " << bytes[1].size() << " bytes)";
    }
}
