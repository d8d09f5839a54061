// --shard I/N and `groom merge` (cli/frame_options.h): the shards of a run, merged in order, are the
// whole run's output byte for byte, for every command that makes hair, with 1 and 2 threads.
#include "test_support.h"

#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"

#include <cmath>
#include <filesystem>

using namespace groom;
using groom::test::run_groom;

namespace {

/// 40 gently bent guides of 12 points over the y = 0 plane, growing up +Y.
std::string write_guides(const test::TempDir& dir)
{
    const int n = 40, k = 12;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(n, k));
    auto P = cs.positions_for_write();
    for (int c = 0; c < n; ++c) {
        const float x = float(c % 8) * 0.66f - 2.5f, z = float(c / 8) * 0.66f - 2.5f;
        for (int i = 0; i < k; ++i) {
            const float t = float(i) / float(k - 1);
            P[c * k + i] = {x + 0.4f * t * t * std::sin(float(c)), 6.0f * t, z + 0.4f * t * t * std::cos(float(c))};
        }
    }
    const std::string path = dir.file("guides.usda");
    write_curves(cs, path);
    return path;
}

/// 80 straight guides on the upper cap of the sphere of radius 10 at the origin.
std::string write_sphere_guides(const test::TempDir& dir)
{
    const int n = 80, k = 10;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(n, k));
    auto P = cs.positions_for_write();
    for (int c = 0; c < n; ++c) {
        const float polar = 0.9f * std::sqrt((float(c) + 0.5f) / float(n)), az = 2.39996323f * float(c);
        const float3 d{std::sin(polar) * std::cos(az), std::cos(polar), std::sin(polar) * std::sin(az)};
        for (int i = 0; i < k; ++i) P[c * k + i] = d * (10.0f + 4.0f * float(i) / float(k - 1));
    }
    const std::string path = dir.file("sphere_guides.usda");
    write_curves(cs, path);
    return path;
}

}  // namespace

TEST(Shard, MergedShardsAreTheWholeRunByteForByte)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir), sguides = write_sphere_guides(dir), head = dir.file("head.vdb"),
                      sphere = dir.file("sphere.vdb"), puff = dir.file("puff.usda");
    // The head as a level set once: edges and cornrow-guides would convert the mesh on each of their 6 runs.
    ASSERT_EQ(run_groom({"head", "-o", dir.file("head.obj"), "--resolution", "24"}).exit_code, 0);
    ASSERT_EQ(run_groom({"scalp", dir.file("head.obj"), "-o", head}).exit_code, 0);
    write_mesh(icosphere(float3(0, 0, 0), 10.0f, 4), dir.file("sphere.obj"));
    ASSERT_EQ(run_groom({"scalp", dir.file("sphere.obj"), "-o", sphere}).exit_code, 0);
    const std::vector<std::vector<std::string>> cases{
        {"generate", sguides, "--scalp", sphere, "--count", "300", "--seed", "3"},
        {"puff", "--scalp", sphere, "--center", "0,12,0", "--radius", "3", "--sphere-center", "0,15,0", "--sphere-radius", "6", "--rows",
         "5", "--cols", "4", "--hairs", "200", "--seed", "5"},
        {"gather", puff, "--scalp", sphere, "--hairs", "200", "--seed", "6"},
        {"braid", guides, "--strands", "3", "--frequency", "3", "--width", "0.5", "--fibers", "4"},
        {"populate", guides, "--count", "8", "--radius", "0.3", "--seed", "2"},
        {"curl", guides, "--type", "3b", "--uniformity", "0.4", "--seed", "7"},
        {"edges", "--scalp", head, "--direction", "random", "--from", "-180", "--to", "180", "--seed", "4"},
        {"cornrow-guides", "--scalp", head, "--count", "6"},
    };
    for (const auto& c : cases) {
        const std::string name = c[0];
        const std::string whole = name == "puff" ? puff : dir.file(name + "_whole.usda");
        std::vector<std::string> args = c;
        args.insert(args.end(), {"-o", whole, "--threads", "1", "--quiet"});
        const auto r = run_groom(args);
        ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
        const std::string expect = test::read_bytes(whole);
        ASSERT_GT(read_curves(whole).num_curves(), 3u) << name;
        // Halves for every command; thirds too for two of them (each run reads the scalp again: the
        // test's time goes there).
        const std::vector<int> splits = name == "generate" || name == "curl" ? std::vector<int>{2, 3} : std::vector<int>{2};
        for (int n : splits) {
            std::vector<std::string> merge{"merge"};
            for (int i = 0; i < n; ++i) {
                const std::string part = dir.file(name + "_" + std::to_string(i) + "of" + std::to_string(n) + ".usda");
                std::vector<std::string> sargs = c;
                // Two threads for the halves, one for the thirds: the split is thread-count free too.
                sargs.insert(sargs.end(), {"-o", part, "--shard", std::to_string(i) + "/" + std::to_string(n), "--threads",
                                           n == 2 ? "2" : "1", "--quiet"});
                const auto s = run_groom(sargs);
                ASSERT_EQ(s.exit_code, 0) << name << " shard " << i << "/" << n << ": " << s.err;
                merge.push_back(part);
            }
            const std::string merged = dir.file(name + "_merged" + std::to_string(n) + ".usda");
            merge.insert(merge.end(), {"-o", merged, "--quiet"});
            const auto m = run_groom(merge);
            ASSERT_EQ(m.exit_code, 0) << m.err;
            EXPECT_TRUE(test::read_bytes(merged) == expect) << name << ": " << n << " merged shards differ from the whole run";
        }
    }
}

TEST(Shard, BadShardsAreRefused)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir);
    for (const char* spec : {"2/2", "1", "-1/3", "0/0", "a/b"}) {
        const auto r = run_groom({"curl", guides, "-o", dir.file("x.usda"), "--shard", spec});
        EXPECT_EQ(r.exit_code, 2) << spec;
        EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
    }
    const auto r = run_groom({"convert", guides, "-o", dir.file("x.ply"), "--shard", "0/2"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("make hair"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x.usda")));
}

// A farm's shards come back as a shell lists them (`m.s*.usda`: shard 10 before shard 2), and a
// failed job leaves one out: merge orders them by the tag each carries and refuses a set with one
// missing, one twice, or a file that is no shard, leaving no output.
TEST(Shard, MergeOrdersShardsAndRefusesMissingOrRepeatedOnes)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir), whole = dir.file("whole.usda");
    const std::vector<std::string> run{"curl", guides, "--type", "3b", "--seed", "7", "--threads", "1", "--quiet"};
    std::vector<std::string> args = run;
    args.insert(args.end(), {"-o", whole});
    ASSERT_EQ(run_groom(args).exit_code, 0);
    const int n = 12;
    std::vector<std::string> parts;
    for (int i = 0; i < n; ++i) {
        parts.push_back(dir.file("m.s" + std::to_string(i) + ".usda"));
        std::vector<std::string> sargs = run;
        sargs.insert(sargs.end(), {"-o", parts.back(), "--shard", std::to_string(i) + "/" + std::to_string(n)});
        ASSERT_EQ(run_groom(sargs).exit_code, 0);
    }
    EXPECT_EQ(read_curves(parts[3]).detail_string("shard"), "3/12");
    auto merge = [&](const std::vector<int>& which, const std::string& out) {
        std::vector<std::string> margs{"merge"};
        for (int i : which) margs.push_back(i >= 0 ? parts[size_t(i)] : whole);
        margs.insert(margs.end(), {"-o", out});
        return run_groom(margs);
    };
    // The glob's order: 0, 1, 10, 11, 2, ...
    const std::string merged = dir.file("merged.usda");
    const auto m = merge({0, 1, 10, 11, 2, 3, 4, 5, 6, 7, 8, 9}, merged);
    ASSERT_EQ(m.exit_code, 0) << m.err;
    EXPECT_TRUE(test::read_bytes(merged) == test::read_bytes(whole)) << "shards merged in the glob's order differ from the whole run";
    EXPECT_NE(m.err.find("shard order"), std::string::npos) << m.err;

    const std::string bad = dir.file("bad.usda");
    const auto missing = merge({0, 1, 2, 3, 4, 6, 7, 8, 9, 10, 11}, bad);
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("missing (5)"), std::string::npos) << missing.err;
    const auto twice = merge({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 4}, bad);
    EXPECT_EQ(twice.exit_code, 2);
    EXPECT_NE(twice.err.find("shard 4/12 is given twice"), std::string::npos) << twice.err;
    const auto mixed = merge({-1, 0}, bad);
    EXPECT_EQ(mixed.exit_code, 2);
    EXPECT_NE(mixed.err.find("whole.usda is not a shard"), std::string::npos) << mixed.err;
    EXPECT_FALSE(std::filesystem::exists(bad));
}

// The tag is kept in every format that can hold it: .obj keeps it as `# groom detail` comments (its
// parts were merged without a word with one missing, or out of order: a trial), .ply as its own.
TEST(Shard, ObjAndPlyPartsCarryTheirTag)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir);
    for (const std::string ext : {"obj", "ply"}) {
        const std::vector<std::string> run{"curl", guides, "--type", "3b", "--seed", "7", "--quiet"};
        std::vector<std::string> args = run;
        const std::string whole = dir.file("whole." + ext);
        args.insert(args.end(), {"-o", whole});
        ASSERT_EQ(run_groom(args).exit_code, 0);
        std::vector<std::string> parts;
        for (int i = 0; i < 3; ++i) {
            parts.push_back(dir.file("p" + std::to_string(i) + "." + ext));
            std::vector<std::string> sargs = run;
            sargs.insert(sargs.end(), {"-o", parts.back(), "--shard", std::to_string(i) + "/3"});
            ASSERT_EQ(run_groom(sargs).exit_code, 0);
        }
        EXPECT_EQ(read_curves(parts[1]).detail_string("shard"), "1/3") << ext;
        const auto missing = run_groom({"merge", parts[0], parts[2], "-o", dir.file("bad." + ext)});
        EXPECT_EQ(missing.exit_code, 2) << ext << ": " << missing.err;
        EXPECT_NE(missing.err.find("missing (1)"), std::string::npos) << missing.err;
        const auto m = run_groom({"merge", parts[2], parts[0], parts[1], "-o", dir.file("merged." + ext)});
        ASSERT_EQ(m.exit_code, 0) << m.err;
        EXPECT_TRUE(test::read_bytes(dir.file("merged." + ext)) == test::read_bytes(whole)) << ext << ": merged parts differ from the whole run";
    }
    // .hair cannot hold the tag: the run says so before it writes (merge cannot check such parts).
    const auto h = run_groom({"curl", guides, "--type", "3b", "--seed", "7", "-o", dir.file("p0.hair"), "--shard", "0/3"});
    ASSERT_EQ(h.exit_code, 0) << h.err;
    EXPECT_NE(h.err.find("-o " + dir.file("p0.hair") + ": this format cannot hold the part's --shard tag"), std::string::npos) << h.err;
}

// Each part carries which run it is of: parts of another run (another --seed, --count or --type),
// or of another frame, are refused by name; parts of one run written with other thread counts or
// verbosity are the same run (a trial merged a 4,000-hair run's part into a 5,000-hair run's and
// got 4,666 hairs, and a part of frame 2 into frame 1, without a word).
TEST(Shard, MergeRefusesPartsOfAnotherRunOrFrame)
{
    test::TempDir dir;
    write_guides(dir);
    for (int f = 1; f <= 2; ++f) std::filesystem::copy_file(dir.file("guides.usda"), dir.file("g." + std::to_string(f) + ".usda"));
    const auto part = [&](const std::string& name, int shard, const std::string& type, const std::string& seed, std::vector<std::string> extra) {
        std::vector<std::string> args{"curl", dir.file("g.#.usda"), "--type", type, "--seed", seed, "--frames", "1:2", "-o", dir.file(name + ".#.usda"),
                                      "--shard", std::to_string(shard) + "/2", "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 0) << r.err;
    };
    part("a0", 0, "3b", "7", {"--threads", "1"});
    part("a1", 1, "3b", "7", {"--threads", "2", "--verbose"});  // the same run
    part("seed", 1, "3b", "8", {});
    part("type", 1, "4a", "7", {});
    const auto merge = [&](const std::string& first, const std::string& second) {
        return run_groom({"merge", dir.file(first), dir.file(second), "-o", dir.file("m.usda"), "--force"});
    };
    const auto same = merge("a0.1.usda", "a1.1.usda");
    EXPECT_EQ(same.exit_code, 0) << same.err;
    EXPECT_TRUE(read_curves(dir.file("m.usda")).detail_string("shard_run").empty());
    for (const auto& [second, why] : std::vector<std::pair<std::string, std::string>>{
             {"seed.1.usda", "another seed"}, {"type.1.usda", "another type"}, {"a1.2.usda", "another frame"}}) {
        std::filesystem::remove(dir.file("m.usda"));
        const auto r = merge("a0.1.usda", second);
        EXPECT_EQ(r.exit_code, 2) << why;
        EXPECT_NE(r.err.find("are shards of different runs"), std::string::npos) << why << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("m.usda"))) << why;
    }
}

// Parts that cannot be one groom are refused; what a merge fills in is said. A trial merged a shard
// written as .obj (no widths, no ids) with two .usda shards: a third of the hair came out width 0,
// invisible, ids -1, without a word; and a Y-up millimetre file joined a Z-up centimetre one.
TEST(Shard, MergeRefusesPartsThatDisagree)
{
    test::TempDir dir;
    const std::string guides = write_guides(dir);
    auto populate = [&](const std::string& shard, const std::string& out) {
        const auto r = run_groom({"populate", guides, "-o", dir.file(out), "--count", "4", "--radius", "0.1", "--shard", shard});
        ASSERT_EQ(r.exit_code, 0) << r.err;
    };
    populate("0/2", "p0.usda");
    populate("1/2", "p1.obj");
    populate("1/2", "p1.usda");
    auto r = run_groom({"merge", dir.file("p0.usda"), dir.file("p1.obj"), "-o", dir.file("m.usda")});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("p1.obj has no"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("m.usda")));
    ASSERT_EQ(run_groom({"merge", dir.file("p0.usda"), dir.file("p1.usda"), "-o", dir.file("m.usda")}).exit_code, 0);

    // Not shards: widths missing from one file are refused; other columns are filled, and said.
    ASSERT_EQ(run_groom({"convert", dir.file("m.usda"), "-o", dir.file("plain.obj")}).exit_code, 0);
    r = run_groom({"merge", dir.file("m.usda"), dir.file("plain.obj"), "-o", dir.file("w.usda")});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("plain.obj has no widths but"), std::string::npos) << r.err;
    test::write_text(dir.file("strand.usda"), "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
                                              " point3f[] points = [(0,0,0),(0,1,0)]\n int[] primvars:strand = [4] (interpolation = \"uniform\")\n}\n");
    r = run_groom({"merge", dir.file("strand.usda"), guides, "-o", dir.file("g.usda")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("columns not in every file are filled with -1 (integers) or 0 where missing: 'strand' (curve, not in " + guides + ")"),
              std::string::npos) << r.err;

    // Units and up axes must agree; a file that says none is taken as the other's, said.
    auto layer = [&](const std::string& name, const std::string& axis, const std::string& mpu) {
        test::write_text(dir.file(name), "#usda 1.0\n(\n upAxis = \"" + axis + "\"\n metersPerUnit = " + mpu +
                                             "\n)\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
                                             " point3f[] points = [(0,0,0),(0,1,0)]\n}\n");
    };
    layer("ymm.usda", "Y", "0.001");
    layer("zcm.usda", "Z", "0.01");
    layer("ycm.usda", "Y", "0.01");
    r = run_groom({"merge", dir.file("ymm.usda"), dir.file("ycm.usda"), "-o", dir.file("u.usda")});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("ymm.usda has units 'mm' but " + dir.file("ycm.usda") + " has 'cm'"), std::string::npos) << r.err;
    r = run_groom({"merge", dir.file("zcm.usda"), dir.file("ycm.usda"), "-o", dir.file("u.usda")});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("has up_axis 'Z' but"), std::string::npos) << r.err;
    r = run_groom({"merge", dir.file("ycm.usda"), guides, "-o", dir.file("u.usda")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find(guides + " does not say its units; taken as " + dir.file("ycm.usda") + "'s ('cm')"), std::string::npos) << r.err;
}
