// Every op command, run with --threads 1 and --threads 2 on the same inputs and seed, must write
// byte-identical files (the brief: "bitwise identical output for any thread count"). The inputs
// are big enough (240 guides) that TBB really splits the work over both threads.
// A command joins the table when it lands on main; a case whose command is not registered fails.
#include "test_support.h"

#include "kernel/io/curve_io.h"

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
    auto P = cs.positions();
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

struct Case {
    const char* command;
    const char* output_ext;
    std::vector<std::string> args;  ///< "{guides}", "{head}" and "{out}" are replaced
};

std::vector<Case> cases()
{
    return {
        {"convert", "ply", {"convert", "{guides}", "-o", "{out}"}},
        {"resample", "usda", {"resample", "{guides}", "-o", "{out}", "--segment-length", "0.37"}},
        {"curl", "usda", {"curl", "{guides}", "-o", "{out}", "--type", "3b", "--uniformity", "0.4", "--seed", "7"}},
        {"head", "obj", {"head", "-o", "{out}", "--resolution", "96"}},
        {"render", "png", {"render", "{guides}", "--scalp", "{head}", "-o", "{out}", "--size", "160x120", "--color-by", "strand"}},
    };
}

std::vector<std::string> expand(const std::vector<std::string>& args, const std::string& guides, const std::string& head,
                                const std::string& out)
{
    std::vector<std::string> r;
    for (const std::string& a : args) r.push_back(a == "{guides}" ? guides : a == "{head}" ? head : a == "{out}" ? out : a);
    return r;
}

}  // namespace

TEST(Determinism, EveryOpCommandWritesTheSameBytesWithOneAndTwoThreads)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir), head = dir.file("head.obj");
    const auto h = run_groom({"head", "-o", head, "--resolution", "24"});
    ASSERT_EQ(h.exit_code, 0) << h.err;
    for (const Case& c : cases()) {
        std::string bytes[2];
        for (int threads : {1, 2}) {
            const std::string out = dir.file(std::string(c.command) + "_" + std::to_string(threads) + "." + c.output_ext);
            std::vector<std::string> args = expand(c.args, guides, head, out);
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
