// A scalp given as the .vdb `groom scalp` made from a mesh gives the same output files, byte for
// byte, as the mesh itself (the file carries the repaired mesh: grid metadata groom_source_mesh),
// for generate, curl --scalp, cull and probe: on a sphere, and on Sintel's open head (skipped
// without ../shared/datasets).
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <cmath>

using namespace groom;
using groom::test::run_groom;

namespace {

/// 60 straight guides over the upper cap of a sphere of radius `R` at `c`, 10 points each,
/// the longer half of them dipping back into the sphere at their tips (work for cull).
std::string write_cap_guides(const test::TempDir& dir, const float3& c, float R)
{
    const int n = 60, k = 10;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(n, k));
    auto P = cs.positions_for_write();
    for (int i = 0; i < n; ++i) {
        const float polar = 0.9f * std::sqrt((float(i) + 0.5f) / float(n)), az = 2.39996323f * float(i);
        const float3 d{std::sin(polar) * std::cos(az), std::cos(polar), std::sin(polar) * std::sin(az)};
        for (int j = 0; j < k; ++j) {
            const float t = float(j) / float(k - 1);
            P[i * k + j] = c + d * (R * (1.0f + 0.4f * t)) + float3(0, i % 2 ? -0.6f * R * t * t : 0.0f, 0);
        }
    }
    const std::string path = dir.file("guides.usda");
    write_curves(cs, path);
    return path;
}

/// Runs each command with `--scalp mesh` and with `--scalp vdb` and compares the outputs byte for byte.
void expect_same_outputs(const test::TempDir& dir, const std::string& mesh, const std::string& guides, const std::string& hair_count)
{
    const std::string vdb = dir.file("scalp.vdb");
    ASSERT_EQ(run_groom({"scalp", mesh, "-o", vdb, "-q"}).exit_code, 0);
    // The hair every later command takes, from the mesh (it is checked against the .vdb's below).
    const std::string hair = dir.file("hair.hair");
    ASSERT_EQ(run_groom({"generate", guides, "--scalp", mesh, "--count", hair_count, "-o", hair, "-q"}).exit_code, 0);
    struct Case {
        const char* name;
        std::vector<std::string> args;
        const char* ext;
    };
    const std::vector<Case> cases{
        {"generate", {"generate", guides, "--count", hair_count, "--seed", "5"}, "hair"},
        {"curl", {"curl", hair, "--type", "3a", "--seed", "2"}, "hair"},
        {"cull trim", {"cull", hair, "--mode", "trim", "--clearance", "0.3"}, "hair"},
        {"cull push", {"cull", hair, "--mode", "push", "--clearance", "0.3"}, "hair"},
        {"cull delete", {"cull", hair, "--mode", "delete", "--clearance", "0.3"}, "hair"},
        {"probe", {"probe", hair}, "csv"},
    };
    for (const Case& c : cases) {
        std::string outputs[2];
        for (int k = 0; k < 2; ++k) {
            std::vector<std::string> args = c.args;
            const std::string out = dir.file(std::string("out") + char('0' + k) + "." + c.ext);
            args.insert(args.end(), {"--scalp", k == 0 ? mesh : vdb, "-o", out, "-q"});
            const auto r = run_groom(args);
            ASSERT_EQ(r.exit_code, 0) << c.name << ": " << r.err;
            outputs[k] = test::read_bytes(out);
        }
        EXPECT_GT(outputs[0].size(), 1000u) << c.name;
        EXPECT_TRUE(outputs[0] == outputs[1]) << c.name << ": --scalp " << mesh << " and its .vdb differ";
    }
}

}  // namespace

TEST(ScalpVdbCli, VdbGivesTheMeshsOutputsByteForByteOnASphere)
{
    test::TempDir dir;
    const float3 c(0.5f, 1.0f, -0.3f);
    const std::string mesh = dir.file("head.obj");
    write_mesh(icosphere(c, 10.0f, 4), mesh);
    expect_same_outputs(dir, mesh, write_cap_guides(dir, c, 10.0f), "2000");
}

TEST(ScalpVdbCli, VdbGivesTheMeshsOutputsByteForByteOnSintelsOpenHead)
{
    GROOM_REQUIRE_SHARED(mesh, "sintel_tressfx_opengl/sintel.obj");
    GROOM_REQUIRE_SHARED(guides, "sintel_tressfx_opengl/sintel_guides.obj");
    test::TempDir dir;
    expect_same_outputs(dir, mesh, guides, "5000");
}
