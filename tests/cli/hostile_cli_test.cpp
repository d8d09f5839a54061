// Hostile geometry and parameters (issue 20): what killed `groom` with a signal or gave a silently
// wrong answer, each now a clean error naming the file or option (exit 1 or 2) or a right answer.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>

using namespace groom;
using groom::test::run_groom;
namespace fs = std::filesystem;

namespace {

std::string sphere_mesh(const test::TempDir& dir, float scale = 1.0f, float3 offset = {}, const std::string& name = "sphere.obj")
{
    PolygonSoup s = icosphere(float3(0, 0, 0), 10.0f, 3);
    for (float3& p : s.points) p = p * scale + offset;
    const std::string path = dir.file(name);
    write_mesh(s, path);
    return path;
}

/// Six straight radial guides on the sphere of radius 10, along +-x, +-y, +-z, of lengths 1 to 6.
std::string radial_guides(const test::TempDir& dir)
{
    const float3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(6, 8));
    auto P = cs.positions_for_write();
    for (int g = 0; g < 6; ++g)
        for (int i = 0; i < 8; ++i) P[g * 8 + i] = dirs[g] * (10.0f + float(g + 1) * float(i) / 7.0f);
    const std::string path = dir.file("radial.usda");
    write_curves(cs, path);
    return path;
}

bool all_finite(const CurveSet& cs)
{
    for (const float3& p : cs.positions())
        if (!isfinite(p)) return false;
    return true;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(Hostile, HugeBlendPowerIsTheNearestGuideNotSigfpe)
{
    // power 1000: each weight's base^1000 overflowed to inf, inf / inf gave NaN positions, and the
    // exact scalp query on them died of SIGFPE (GMP). The blend at such a power is the nearest guide:
    // a radial guide of length L carried to a root keeps its length.
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir), guides = radial_guides(dir), out = dir.file("g.usda");
    const auto r = run_groom({"generate", guides, "--scalp", mesh, "-o", out, "--count", "60", "--power", "1000", "--seed", "3",
                              "--region", "0,0,0,20"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CurveSet g = read_curves(out);
    ASSERT_EQ(g.num_curves(), 60u);
    ASSERT_TRUE(all_finite(g));
    const auto nearest = g.find<int32_t>(Domain::Curve, "guide");
    ASSERT_EQ(nearest.size(), 60u);
    const float3 guide_roots[6] = {{10, 0, 0}, {-10, 0, 0}, {0, 10, 0}, {0, -10, 0}, {0, 0, 10}, {0, 0, -10}};
    int checked = 0;
    for (size_t c = 0; c < g.num_curves(); ++c) {
        const IndexRange pts = g.points_of(c);
        const float3 root = g.positions()[pts.begin];
        // Where the second-nearest guide is 5% farther or more, its weight is below 1.05^-1000 = 6e-22.
        float d1 = 1e30f, d2 = 1e30f;
        for (const float3& r : guide_roots) {
            const float d = groom::length(root - r);
            if (d < d1) d2 = d1, d1 = d;
            else d2 = std::min(d2, d);
        }
        if (d2 < 1.05f * d1) continue;
        ++checked;
        const float length = groom::length(g.positions()[pts.end - 1] - root);
        EXPECT_NEAR(length, float(nearest[c] + 1), 2e-3f) << "curve " << c << " (nearest guide " << nearest[c] << ")";
    }
    EXPECT_GE(checked, 30);

    const auto puff = run_groom({"puff", "--scalp", mesh, "-o", dir.file("p.usda"), "--center", "0,10,0", "--radius", "3",
                                 "--sphere-center", "0,16,0", "--sphere-radius", "4", "--hairs", "30", "--power", "1000"});
    ASSERT_EQ(puff.exit_code, 0) << puff.err;
    const CurveSet p = read_curves(dir.file("p.usda"));
    EXPECT_EQ(p.num_curves(), 25u + 30u);
    EXPECT_TRUE(all_finite(p));
}

TEST(Hostile, ScalpMeshWhoseSizeOverflowsFloatIsRefused)
{
    // A head scaled to 1e30: the automatic voxel was inf (written to the .vdb, NaN from every probe)
    // and cornrow-guides and braid died of SIGFPE.
    test::TempDir dir;
    const std::string huge = sphere_mesh(dir, 1e29f, {}, "huge.obj");
    const std::string guides = radial_guides(dir);
    const std::vector<std::vector<std::string>> cases = {
        {"scalp", huge, "-o", dir.file("huge.vdb")},
        {"cornrow-guides", "--scalp", huge, "-o", dir.file("c.usda")},
        {"braid", guides, "--scalp", huge, "-o", dir.file("b.usda"), "--orient", "scalp", "--rest"},
        {"probe", "--scalp", huge, guides, "-o", dir.file("p.csv")},
    };
    for (const auto& args : cases) {
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 1) << args[0] << ": " << r.err;
        EXPECT_TRUE(contains(r.err, "huge.obj: the mesh is 3.4641e+30 units across")) << args[0] << ": " << r.err;
        EXPECT_TRUE(contains(r.err, "scale it down")) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir.file("huge.vdb")));

    // Far from the origin: float positions there cannot tell voxels apart.
    const std::string far = sphere_mesh(dir, 1.0f, {1e12f, 0, 0}, "far.obj");
    const auto r = run_groom({"scalp", far, "-o", dir.file("far.vdb")});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "far.obj: the mesh lies 1.00000001e+12 units from the origin") ||
                contains(r.err, "far.obj: the mesh lies 1e+12 units from the origin"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "--voxel")) << r.err;
}

TEST(Hostile, BraidWidthThatOverflowsIsAUsageError)
{
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir), guides = radial_guides(dir);
    const auto r = run_groom({"braid", guides, "--scalp", mesh, "-o", dir.file("b.usda"), "--width", "3e38", "--rest", "--orient", "scalp"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "braid: --width must be a finite number >= 0 and <= 1e+15 (got 3e+38)")) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("b.usda")));
}

TEST(Hostile, TruncatedOrBitFlippedVdbIsAnErrorNamingIt)
{
    // 18 of 32 truncations and 16 of 60 bit flips of a .vdb segfaulted `probe`; now each is read
    // correctly or refused naming the file, exit 1, never a signal.
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir), vdb = dir.file("sphere.vdb");
    ASSERT_EQ(run_groom({"scalp", mesh, "-o", vdb, "--voxel", "1", "--band", "2"}).exit_code, 0);
    const std::string bytes = test::read_bytes(vdb);
    const std::string points = dir.file("points.txt");
    test::write_text(points, "0 3 0\n0 30 0\n12 0 0\n");
    std::vector<std::pair<std::string, std::string>> cases;
    for (int i = 0; i < 32; ++i) cases.push_back({"truncated to " + std::to_string(i) + "/32", bytes.substr(0, bytes.size() * i / 32)});
    std::mt19937_64 rng(20);
    for (int i = 0; i < 60; ++i) {
        std::string b = bytes;
        const size_t at = rng() % b.size();
        const int bit = int(rng() % 8);
        b[at] = char(b[at] ^ (1 << bit));
        cases.push_back({"bit " + std::to_string(bit) + " of byte " + std::to_string(at) + " flipped", b});
    }
    int refused = 0;
    for (const auto& [what, data] : cases) {
        const std::string bad = dir.file("bad.vdb"), out = dir.file("probe.csv");
        test::write_text(bad, data);
        fs::remove(out);
        // --memory: a length flipped to gigabytes fails fast instead of zeroing gigabytes.
        const auto r = run_groom({"probe", "--scalp", bad, points, "-o", out, "--memory", "0.5"});
        ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << what << ": exit " << r.exit_code << " " << r.err;
        if (r.exit_code == 1) {
            ++refused;
            EXPECT_TRUE(contains(r.err, "groom: error: " + bad)) << what << ": " << r.err;
            EXPECT_FALSE(fs::exists(out)) << what;
            continue;
        }
        // Read as a valid scalp (a flipped bit in a value, say): every answer is a number.
        std::istringstream csv(test::read_bytes(out));
        std::string line;
        std::getline(csv, line);
        for (int n = 0; std::getline(csv, line); ++n) {
            EXPECT_EQ(line.find("nan"), std::string::npos) << what << ": " << line;
            EXPECT_EQ(line.find("inf"), std::string::npos) << what << ": " << line;
        }
    }
    EXPECT_GE(refused, 32) << "every truncation but the whole file is refused, and some flips";
}

// GCC defines __SANITIZE_ADDRESS__, Clang answers __has_feature.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

TEST(Hostile, OutOfMemoryInsideTheLevelSetNamesTheVoxel)
{
    if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: RLIMIT_AS cannot apply";
    // A budget above what the process may allocate (`ulimit -v`): meshToVolume's tasks ran out of
    // memory, OpenVDB allocated again while unwinding, and std::terminate aborted the process.
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir);
    test::RunOptions limited;
    limited.address_space_limit = 600ull << 20;
    const auto r = run_groom({"scalp", mesh, "-o", dir.file("s.vdb"), "--voxel", "0.01", "--memory", "100", "--threads", "2"}, limited);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "out of memory")) << r.err;
    EXPECT_TRUE(contains(r.err, "voxel size 0.01")) << r.err;
    EXPECT_TRUE(contains(r.err, "estimated")) << r.err;
    EXPECT_TRUE(contains(r.err, "--voxel")) << r.err;
    EXPECT_FALSE(contains(r.err, "terminate called")) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("s.vdb")));

    // Without --memory the budget follows `ulimit -v`, and the same job is refused before it starts.
    const auto up_front = run_groom({"scalp", mesh, "-o", dir.file("s.vdb"), "--voxel", "0.01", "--threads", "2"}, limited);
    EXPECT_EQ(up_front.exit_code, 1) << up_front.err;
    EXPECT_TRUE(contains(up_front.err, "over the 0.439453 GiB budget (--memory); use --voxel")) << up_front.err;
}

// A budget too small to read the scalp's .vdb (the reading child runs within it): a user's
// `--memory 0.001` was told "not a readable .vdb file (std::bad_alloc)", as if the file were damaged.
TEST(Hostile, ABudgetTooSmallToReadTheScalpSaysRaiseMemory)
{
    if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: RLIMIT_AS cannot apply";
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir), vdb = dir.file("s.vdb");
    ASSERT_EQ(run_groom({"scalp", mesh, "-o", vdb}).exit_code, 0);
    const std::string points = dir.file("p.xyz");
    test::write_text(points, "0 30 0\n");
    const auto r = run_groom({"probe", points, "--scalp", vdb, "-o", dir.file("p.csv"), "--memory", "0.0001"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "s.vdb: reading it needs more memory than the")) << r.err;
    EXPECT_TRUE(contains(r.err, "raise --memory")) << r.err;
    EXPECT_FALSE(contains(r.err, "bad_alloc")) << r.err;
}

TEST(Hostile, MemoryBudgetRefusesOutputsBeforeAllocating)
{
    test::TempDir dir;
    const std::string guides = radial_guides(dir);
    // 8 points x 1,000,000 fibers x 6 guides = 4.8e7 points: about 1.9 GB, over 1 GiB; --count allows 1e6.
    const auto pop = run_groom({"populate", guides, "-o", dir.file("p.usda"), "--count", "1000000", "--radius", "0.1", "--memory", "1"});
    EXPECT_EQ(pop.exit_code, 1) << pop.err;
    EXPECT_TRUE(contains(pop.err, "populate: 6 curves x 1000000 fibers (--count) = 4.8e+07 points needs about")) << pop.err;
    EXPECT_TRUE(contains(pop.err, "over the 1 GiB memory budget; lower --count (or raise the budget with --memory GiB)")) << pop.err;
    EXPECT_FALSE(fs::exists(dir.file("p.usda")));

    // A 30-byte-scale file asking resample for ten billion points (it asked for 23.8 GB and was killed).
    const std::string line = dir.file("line.usda");
    test::write_text(line, "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
                           " point3f[] points = [(0,0,0), (1e9,0,0)]\n}\n");
    const auto rs = run_groom({"resample", line, "-o", dir.file("r.usda"), "--segment-length", "0.1"});
    EXPECT_EQ(rs.exit_code, 1) << rs.err;
    EXPECT_TRUE(contains(rs.err, "resample: 1e+10 points at --segment-length 0.1 (curve 0 alone needs 1e+10) needs about")) << rs.err;
    EXPECT_TRUE(contains(rs.err, "use a larger --segment-length or --count")) << rs.err;
    // The budget from the environment, and the same job within it.
    test::RunOptions small;
    small.env = {{"GROOM_MEMORY", "0.01"}};
    const auto env = run_groom({"resample", line, "-o", dir.file("r.usda"), "--segment-length", "1000"}, small);
    EXPECT_EQ(env.exit_code, 1) << env.err;
    EXPECT_TRUE(contains(env.err, "over the 10.2 MiB memory budget")) << env.err;
    const auto fits = run_groom({"resample", line, "-o", dir.file("r.usda"), "--segment-length", "1000", "--memory", "1"}, small);
    ASSERT_EQ(fits.exit_code, 0) << fits.err;
    EXPECT_EQ(read_curves(dir.file("r.usda")).num_points(), 1000001u);

    // A curve longer than float can measure was resampled to 2 points.
    const std::string longer = dir.file("longer.usda");
    test::write_text(longer, "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
                             " point3f[] points = [(0,0,0), (1e30,0,0)]\n}\n");
    const auto lr = run_groom({"resample", longer, "-o", dir.file("r2.usda"), "--segment-length", "1"});
    EXPECT_EQ(lr.exit_code, 1) << lr.err;
    EXPECT_TRUE(contains(lr.err, "resample: curve 0 is too long for float to measure")) << lr.err;
}

TEST(Hostile, IntegerOptionsAreDecimalAndIdsNeverWrap)
{
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir), guides = radial_guides(dir);
    // `--count 010` was octal 8.
    const auto ten = run_groom({"populate", guides, "-o", dir.file("p.usda"), "--count", "010", "--radius", "0.1"});
    ASSERT_EQ(ten.exit_code, 0) << ten.err;
    EXPECT_EQ(read_curves(dir.file("p.usda")).num_curves(), 6u * 10u);
    const auto hex = run_groom({"populate", guides, "-o", dir.file("p.usda"), "--count", "0x10", "--radius", "0.1"});
    EXPECT_EQ(hex.exit_code, 2);
    EXPECT_TRUE(contains(hex.err, "--count: expected a decimal integer, got '0x10'")) << hex.err;
    const auto negative_seed = run_groom({"populate", guides, "-o", dir.file("p.usda"), "--seed", "-1", "--radius", "0.1"});
    EXPECT_EQ(negative_seed.exit_code, 2) << negative_seed.err;
    EXPECT_TRUE(contains(negative_seed.err, "--seed: expected a decimal integer >= 0, got '-1'")) << negative_seed.err;

    // Ids past 2^63 - 1 wrapped to negative; a value past int64 was clamped to it.
    const auto wrap = run_groom({"generate", guides, "--scalp", mesh, "-o", dir.file("g.usda"), "--count", "5", "--first-id",
                                 "9223372036854775807", "--region", "0,0,0,20"});
    EXPECT_EQ(wrap.exit_code, 2) << wrap.err;
    EXPECT_TRUE(contains(wrap.err, "generate: --first-id 9223372036854775807 + 5 curves passes the largest id, 2^63 - 1")) << wrap.err;
    const auto past = run_groom({"generate", guides, "--scalp", mesh, "-o", dir.file("g.usda"), "--count", "5", "--first-id",
                                 "9223372036854775808", "--region", "0,0,0,20"});
    EXPECT_EQ(past.exit_code, 2) << past.err;
    EXPECT_TRUE(contains(past.err, "'9223372036854775808' is out of range for a 64-bit integer")) << past.err;
    const auto puff = run_groom({"puff", "--scalp", mesh, "-o", dir.file("p.usda"), "--center", "0,10,0", "--radius", "3",
                                 "--sphere-center", "0,16,0", "--sphere-radius", "4", "--first-id", "9223372036854775800"});
    EXPECT_EQ(puff.exit_code, 2) << puff.err;
    EXPECT_TRUE(contains(puff.err, "puff: --first-id 9223372036854775800 + 25 guides + 0 --hairs passes the largest id")) << puff.err;
    EXPECT_FALSE(fs::exists(dir.file("g.usda")));
}

TEST(Hostile, BadWidthsAreRefusedOnRead)
{
    test::TempDir dir;
    const std::string good = radial_guides(dir);
    for (const std::string w : {"nan", "inf", "-0.5"}) {
        const std::string path = dir.file("w.usda");
        test::write_text(path, "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [3]\n"
                               " point3f[] points = [(0,0,0), (0,1,0), (0,2,0)]\n float[] widths = [0.1, " +
                                   w + ", 0.1] (interpolation = \"vertex\")\n}\n");
        const auto r = run_groom({"convert", path, "-o", dir.file("out.ply")});
        EXPECT_EQ(r.exit_code, 1) << w << ": " << r.err;
        EXPECT_TRUE(contains(r.err, path + ": point 1 (curve 0) has width")) << w << ": " << r.err;
        EXPECT_TRUE(contains(r.err, "expected a finite width >= 0")) << r.err;
        EXPECT_FALSE(fs::exists(dir.file("out.ply")));
    }
}

TEST(Hostile, PartingStepTooFineForTheBudgetIsRefusedBeforeWalking)
{
    // `--step 1e-6` across the head walked 12 million points (970 MB) past `--memory 0.0625` (found
    // after the op fuzzer's op_sections hang). The legs' bound (4 |a - b| / step + 16 points, as
    // surface_path caps them) is checked first: here 4 * ~31 / 1e-6 points, about 4.5 GB. The budget
    // holds the sphere's field (about 90 MB with what the process holds, as the scalp's estimate now
    // counts it; 64 MiB did before it did).
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir), out = dir.file("p.usda");
    const auto bad = run_groom({"parting", "--scalp", mesh, "-o", out, "--through", "0,10,0/10,0,0/0,0,10", "--step", "1e-6", "--memory",
                                "0.125", "--quiet"});
    EXPECT_EQ(bad.exit_code, 1) << bad.err;
    EXPECT_TRUE(contains(bad.err, "--step")) << bad.err;
    EXPECT_TRUE(contains(bad.err, "memory budget")) << bad.err;
    EXPECT_FALSE(fs::exists(out));
    const auto ok = run_groom({"parting", "--scalp", mesh, "-o", out, "--through", "0,10,0/10,0,0/0,0,10", "--memory", "0.125", "--quiet"});
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_TRUE(fs::exists(out));
}

TEST(Hostile, BoundedOpsEstimateTheirOutputBeforeAllocating)
{
    // partition, cull, project and cornrow-guides make outputs bounded by their input or by closed
    // ranges, but each still estimates its output against --memory before allocating, like every op:
    // under a 2 MiB budget (the sphere scalp at --scalp-voxel 2 fits: about 1 MB of level set) each
    // is refused naming its options and the estimate, and writes nothing; the same command at its
    // defaults (partition: 24 a side) fits the same budget.
    test::TempDir dir;
    const std::string mesh = sphere_mesh(dir);
    const std::vector<std::string> scalp = {"--scalp", mesh, "--scalp-voxel", "2", "--memory", "0.002", "--quiet"};
    auto with = [&](std::vector<std::string> args) {
        args.insert(args.end(), scalp.begin(), scalp.end());
        return args;
    };
    auto refused = [&](const test::RunResult& r, const std::string& out, const std::vector<std::string>& parts) {
        EXPECT_EQ(r.exit_code, 1) << r.err;
        for (const std::string& p : parts) EXPECT_TRUE(contains(r.err, p)) << "missing '" << p << "' in: " << r.err;
        EXPECT_TRUE(contains(r.err, "needs about ")) << r.err;
        EXPECT_TRUE(contains(r.err, "over the 2.05 MiB memory budget")) << r.err;
        EXPECT_TRUE(contains(r.err, "raise the budget with --memory GiB")) << r.err;
        EXPECT_FALSE(fs::exists(out)) << out;
    };

    // cornrow-guides: 8 rows of 100,000 points, 16 MB of positions and root UVs.
    const std::string rows = dir.file("rows.usda");
    refused(run_groom(with({"cornrow-guides", "-o", rows, "--samples", "100000"})), rows,
            {"cornrow-guides: 8 guides (--count) x 100000 --samples", "lower --count, --samples or --tail-samples"});
    ASSERT_EQ(run_groom(with({"cornrow-guides", "-o", rows})).exit_code, 0);

    // partition of those 8 rows: 100,000 segments per side of each, 1.6e6 x 8 points.
    const std::string edges = dir.file("edges.usda");
    refused(run_groom(with({"partition", rows, "-o", edges, "--count", "100000"})), edges,
            {"segments (--count or --spacing per side of each guide) x 8 --samples", "raise --spacing or lower --count / --samples"});
    const auto fits = run_groom(with({"partition", rows, "-o", edges, "--count", "24"}));  // the automatic count needs 5 MiB
    ASSERT_EQ(fits.exit_code, 0) << fits.err;
    EXPECT_GT(read_curves(edges).num_curves(), 0u);

    // project and cull copy their input: 20,000 curves x 16 points, 3.8 MB of positions.
    // Straight hairs standing on the sphere's pole.
    auto hairs = [&](size_t n, const std::string& name) {
        CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(n, 16));
        auto P = cs.positions_for_write();
        for (size_t i = 0; i < P.size(); ++i) P[i] = float3(0.0f, 10.5f + 0.1f * float(i % 16), 0.0f);
        write_curves(cs, dir.file(name));
        return dir.file(name);
    };
    const std::string big = hairs(20000, "many.ply");
    const std::string moved = dir.file("moved.usda"), culled = dir.file("culled.usda");
    refused(run_groom(with({"project", big, "-o", moved})), moved,
            {"project: a copy of 320000 points in 20000 curves (the input)", "project fewer curves at a time"});
    refused(run_groom(with({"cull", big, "-o", culled, "--mode", "trim"})), culled,
            {"cull: up to 320000 points in 20000 curves (the input)", "cull fewer curves at a time"});
    // The first 1,000 of them fit.
    const std::string few = hairs(1000, "few.ply");
    EXPECT_EQ(run_groom(with({"project", few, "-o", moved})).exit_code, 0);
    EXPECT_EQ(run_groom(with({"cull", few, "-o", culled})).exit_code, 0);
}
