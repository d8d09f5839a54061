// General behaviour of the `groom` command line, through the real executable: help, version,
// suggestions for typos, exit codes (0 ok, 1 failure, 2 usage), `-` for stdin/stdout, refusal to
// overwrite an input, and atomic output. Also `groom info`, `convert` and `resample` end to end.
#include "test_support.h"

#include "kernel/io/curve_io.h"

#include <cstdlib>
#include <cstring>
#include <sys/wait.h>
#include <filesystem>
#include <nlohmann/json.hpp>

using namespace groom;
using groom::test::read_bytes;
using groom::test::run_groom;
using groom::test::TempDir;
using groom::test::write_text;

namespace {

const char* kTwoCurvesUsda = R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2, 3]
    point3f[] points = [(0, 0, 0), (0, 3, 4), (1, 0, 0), (1, 1, 0), (1, 2, 0)]
    float[] widths = [0.1, 0.1, 0.2, 0.2, 0.2] (interpolation = "vertex")
    int64[] primvars:id = [7, 9] (interpolation = "uniform")
}
)";

std::vector<std::string> files_in(const TempDir& dir)
{
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

TEST(Cli, HelpListsCommandsAndExitsZero)
{
    const auto r = run_groom({"--help"});
    EXPECT_EQ(r.exit_code, 0);
    for (const char* cmd : {"info", "convert", "resample"}) EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd;
    const auto sub = run_groom({"convert", "--help"});
    EXPECT_EQ(sub.exit_code, 0);
    EXPECT_NE(sub.out.find("--ascii"), std::string::npos);
    EXPECT_NE(sub.out.find("--threads"), std::string::npos);
}

TEST(Cli, VersionPrintsNameAndVersion)
{
    const auto r = run_groom({"--version"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out.rfind("groom " GROOM_VERSION, 0), 0u) << r.out;
}

TEST(Cli, UnknownCommandSuggestsTheNearestAndExitsTwo)
{
    const auto r = run_groom({"infoo", "x.usda"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("groom: error: unknown command 'infoo'; did you mean 'info'?"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST(Cli, UnknownOptionSuggestsTheNearestAndExitsTwo)
{
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    const auto r = run_groom({"convert", dir.file("a.usda"), "-o", dir.file("b.ply"), "--acsii"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("convert: unknown option '--acsii'; did you mean '--ascii'?"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("b.ply")));
}

// Several guide files where one is taken: named in the order given, with the way to join them.
TEST(Cli, ExtraInputFilesAreNamedInOrderWithMerge)
{
    TempDir dir;
    for (const char* f : {"a.usda", "b.usda", "c.usda"}) write_text(dir.file(f), kTwoCurvesUsda);
    const auto r = run_groom({"resample", dir.file("a.usda"), dir.file("b.usda"), dir.file("c.usda"), "-o", dir.file("o.usda"), "--count", "4"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("resample: unexpected arguments: " + dir.file("b.usda") + " " + dir.file("c.usda")), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("groom merge"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("o.usda")));
}

TEST(Cli, MissingRequiredArgumentAndBadValueExitTwo)
{
    EXPECT_EQ(run_groom({"convert"}).exit_code, 2);
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    const auto r = run_groom({"resample", dir.file("a.usda"), "-o", dir.file("b.usda"), "--count", "1"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("groom: error: resample: --count must be >= 2 (got 1)"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("b.usda")));
}

TEST(Cli, UnreadableOrMalformedInputExitsOneNamingTheFile)
{
    TempDir dir;
    const auto missing = run_groom({"info", dir.file("missing.usda")});
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_NE(missing.err.find("groom: error: " + dir.file("missing.usda") + ": cannot open for reading"), std::string::npos) << missing.err;
    write_text(dir.file("bad.obj"), "v 0 0 0\nv 1 1 1\nl 1 2 3\n");
    const auto bad = run_groom({"convert", dir.file("bad.obj"), "-o", dir.file("out.usda")});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find(dir.file("bad.obj") + ":3: vertex index 3 out of range (2 vertices)"), std::string::npos) << bad.err;
    // Atomic output: nothing named out.usda, and no temporary left behind either.
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"bad.obj"});
    // A format groom does not read is the file's problem for info as for convert (a user trial
    // found 2 from one and 1 from the other on a TressFX .tfx).
    write_text(dir.file("strands.tfx"), "x");
    for (const std::string command : {"info", "convert"}) {
        std::vector<std::string> args = {command, dir.file("strands.tfx")};
        if (command == "convert") args.insert(args.end(), {"-o", dir.file("out.usda")});
        const auto r = run_groom(args);
        EXPECT_EQ(r.exit_code, 1) << command << ": " << r.err;
        EXPECT_NE(r.err.find("strands.tfx"), std::string::npos) << r.err;
    }
}

TEST(Cli, FailedWriteLeavesNoFile)
{
    // An attribute name USD cannot hold fails while encoding: no output and no temporary.
    TempDir dir;
    write_text(dir.file("a.ply"), "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                                  "property float 1bad\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n0 0 0 1\n0 1 0 1\n0 1\n");
    const auto r = run_groom({"convert", dir.file("a.ply"), "-o", dir.file("b.usda")});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("attribute '1bad' is not a valid USD property name"), std::string::npos) << r.err;
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"a.ply"});
    // An output directory that does not exist: refused before any work (exit 2), nothing written.
    const auto nodir = run_groom({"convert", dir.file("a.ply"), "-o", dir.file("no/such/dir/b.obj")});
    EXPECT_EQ(nodir.exit_code, 2);
    EXPECT_NE(nodir.err.find("does not exist; create it first"), std::string::npos) << nodir.err;
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"a.ply"});
}

TEST(Cli, OutputOntoInputIsRefusedWithoutForce)
{
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    const auto r = run_groom({"resample", dir.file("a.usda"), "-o", dir.file("a.usda"), "--count", "4"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("is also an input file; refusing to overwrite it (pass --force to allow)"), std::string::npos) << r.err;
    EXPECT_EQ(read_bytes(dir.file("a.usda")), kTwoCurvesUsda);
    const auto forced = run_groom({"resample", dir.file("a.usda"), "-o", dir.file("a.usda"), "--count", "4", "--force"});
    EXPECT_EQ(forced.exit_code, 0) << forced.err;
    EXPECT_EQ(read_curves(dir.file("a.usda")).num_points(), 8u);
}

TEST(Cli, DashMeansStdinAndStdout)
{
    const auto r = run_groom({"convert", "-", "-o", "-", "--quiet"}, kTwoCurvesUsda);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.rfind("#usda 1.0", 0), 0u);
    EXPECT_NE(r.out.find("point3f[] points = [(0, 0, 0), (0, 3, 4),\n        (1, 0, 0), (1, 1, 0), (1, 2, 0)]"), std::string::npos) << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const auto info = run_groom({"info", "-", "--json"}, kTwoCurvesUsda);
    EXPECT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("\"curves\": 2"), std::string::npos) << info.out;
}

// A mesh file with nothing in it (Blender 3.4's exporters write one for a hair Curves object) is
// described, and said to hold no geometry; a trial's info reported "vertices 0" without a word.
TEST(CliInfo, AFileWithNoGeometryIsSaidToHoldNone)
{
    TempDir dir;
    write_text(dir.file("empty.obj"), "# Blender v3.4.1 OBJ File: ''\n# www.blender.org\n");
    const auto r = run_groom({"info", dir.file("empty.obj")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("vertices            0"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("holds no geometry"), std::string::npos) << r.err;
    write_text(dir.file("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(run_groom({"info", dir.file("tri.obj")}).err.find("no geometry"), std::string::npos);
}

TEST(CliInfo, CurvesTextAndJson)
{
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    const auto text = run_groom({"info", dir.file("a.usda")});
    EXPECT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("curves            2\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("points            5\n"), std::string::npos);
    EXPECT_NE(text.out.find("points per curve  min 2  median 2.5  max 3\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("length            min 2  median 3.5  max 5\n"), std::string::npos) << text.out;  // 2 and 5 (a 3-4-5 segment)
    EXPECT_NE(text.out.find("bounds            (0, 0, 0) to (1, 3, 4)"), std::string::npos) << text.out;
    const auto json = run_groom({"info", dir.file("a.usda"), "--json"});
    EXPECT_EQ(json.exit_code, 0);
    // Parsed, not matched as text: what a script reading it gets.
    const nlohmann::json j = nlohmann::json::parse(json.out);
    EXPECT_EQ(j["points_per_curve"], nlohmann::json::parse(R"({"min": 2, "median": 2.5, "max": 3})")) << json.out;
    EXPECT_EQ(j["length"]["median"], 3.5);
    EXPECT_EQ(j["bounds"]["max"], nlohmann::json::parse("[1, 3, 4]"));
    const auto has = [&](const char* column) {
        return std::count(j["attributes"].begin(), j["attributes"].end(), nlohmann::json::parse(column)) == 1;
    };
    EXPECT_TRUE(has(R"({"name": "width", "domain": "point", "type": "float"})")) << json.out;
    EXPECT_TRUE(has(R"({"name": "id", "domain": "curve", "type": "int64"})")) << json.out;
}

TEST(CliInfo, MeshByContentAndForcedKinds)
{
    TempDir dir;
    write_text(dir.file("cube.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                     "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
    const auto r = run_groom({"info", dir.file("cube.obj"), "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "mesh");
    for (const auto& [key, value] : std::initializer_list<std::pair<const char*, int>>{
             {"vertices", 8}, {"faces", 6}, {"quads", 6}, {"shells", 1}, {"boundary_edges", 0}, {"non_manifold_edges", 0}, {"duplicate_vertices", 0}})
        EXPECT_EQ(j[key], value) << key << "\n" << r.out;
    const auto forced = run_groom({"info", dir.file("cube.obj"), "--curves"});
    EXPECT_EQ(forced.exit_code, 1);
    EXPECT_NE(forced.err.find("this is a mesh"), std::string::npos) << forced.err;
    EXPECT_EQ(run_groom({"info", dir.file("cube.obj"), "--curves", "--mesh"}).exit_code, 2);
}

TEST(CliConvert, ChainThroughEveryFormatKeepsPointsExactly)
{
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    const std::vector<std::string> chain{"a.usda", "b.ply", "c.hair", "d.obj", "e.ply", "f.usda"};
    for (size_t i = 0; i + 1 < chain.size(); ++i) {
        std::vector<std::string> args{"convert", dir.file(chain[i]), "-o", dir.file(chain[i + 1])};
        if (chain[i + 1] == "e.ply") args.push_back("--ascii");
        const auto r = run_groom(args);
        ASSERT_EQ(r.exit_code, 0) << chain[i] << " -> " << chain[i + 1] << ": " << r.err;
    }
    const CurveSet a = read_curves(dir.file("a.usda")), f = read_curves(dir.file("f.usda"));
    ASSERT_EQ(a.num_points(), f.num_points());
    EXPECT_EQ(std::memcmp(a.positions().data(), f.positions().data(), a.num_points() * sizeof(float3)), 0);
    EXPECT_EQ(std::vector<int64_t>(a.offsets().begin(), a.offsets().end()), std::vector<int64_t>(f.offsets().begin(), f.offsets().end()));
    EXPECT_NE(read_bytes(dir.file("e.ply")).find("format ascii 1.0"), std::string::npos);
}

TEST(CliConvert, SaysWhichAttributesTheTargetDrops)
{
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    const auto r = run_groom({"convert", dir.file("a.usda"), "-o", dir.file("b.obj")});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.err.find("dropped: point width, curve id"), std::string::npos) << r.err;
    const auto hair = run_groom({"convert", dir.file("a.usda"), "-o", dir.file("b.hair")});
    EXPECT_NE(hair.err.find("dropped: curve id"), std::string::npos) << hair.err;
    const auto quiet = run_groom({"convert", dir.file("a.usda"), "-o", dir.file("c.ply"), "-q"});
    EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

TEST(CliResample, CountAndSegmentLength)
{
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    ASSERT_EQ(run_groom({"resample", dir.file("a.usda"), "-o", dir.file("b.ply"), "--count", "6"}).exit_code, 0);
    const CurveSet b = read_curves(dir.file("b.ply"));
    EXPECT_EQ(b.num_points(), 12u);
    EXPECT_EQ(b.positions()[5], float3(0, 3, 4));  // tip kept exactly
    const auto both = run_groom({"resample", dir.file("a.usda"), "-o", dir.file("c.ply"), "--count", "6", "--segment-length", "0.5"});
    EXPECT_EQ(both.exit_code, 2);
    EXPECT_NE(both.err.find("exclusive"), std::string::npos);
}

TEST(CliConvert, UsdaOutputParsesWithTinyusdz)
{
    // Independent reader (scripts/check-usda.sh): skipped where node or a cached tinyusdz is absent,
    // so the suite never needs the network.
    TempDir dir;
    write_text(dir.file("a.obj"), "v 0 0 0\nv 0 1 0\nv 0 2 0.5\nv 1 0 0\nv 1 1 0\nl 1 2 3\nl 4 5\n");
    ASSERT_EQ(run_groom({"convert", dir.file("a.obj"), "-o", dir.file("b.ply")}).exit_code, 0);
    ASSERT_EQ(run_groom({"resample", dir.file("b.ply"), "-o", dir.file("c.usda"), "--count", "5"}).exit_code, 0);
    const std::string cmd = "GROOM='" GROOM_BINARY "' bash '" GROOM_SOURCE_DIR "/scripts/check-usda.sh' --no-install '" + dir.file("c.usda") + "' > '" +
                            dir.file("log") + "' 2>&1";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    if (WEXITSTATUS(status) == 77) GTEST_SKIP() << read_bytes(dir.file("log"));
    EXPECT_EQ(WEXITSTATUS(status), 0) << read_bytes(dir.file("log"));
    EXPECT_NE(read_bytes(dir.file("log")).find("\"curves\":2\"points\":10"), std::string::npos) << read_bytes(dir.file("log"));
}

// Every command says which columns its output's format cannot hold, as convert did alone: a trial's
// `partition -o e.ply` lost its 63-bit ids without a word. Said once per output, on stderr.
TEST(Cli, EveryCommandNamesTheColumnsItsOutputCannotHold)
{
    TempDir dir;
    write_text(dir.file("a.usda"), kTwoCurvesUsda);
    const auto r = run_groom({"populate", dir.file("a.usda"), "-o", dir.file("p.obj"), "--count", "3", "--radius", "0.1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("populate: " + dir.file("p.obj") + ": .obj cannot hold these attributes, dropped: point width"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("curve id"), std::string::npos) << r.err;
    const auto usda = run_groom({"populate", dir.file("a.usda"), "-o", dir.file("p.usda"), "--count", "3", "--radius", "0.1"});
    ASSERT_EQ(usda.exit_code, 0) << usda.err;
    EXPECT_EQ(usda.err.find("cannot hold"), std::string::npos) << usda.err;
    const auto quiet = run_groom({"populate", dir.file("a.usda"), "-o", dir.file("q.obj"), "--count", "3", "--radius", "0.1", "--quiet"});
    EXPECT_EQ(quiet.err, "");
}
