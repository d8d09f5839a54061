// Inputs that crashed, hung or over-allocated a reader, each now refused with a clean groom::Error
// of a stated kind whose message names the problem. Two sources:
//   - files under tests/data/regressions/<fuzz target>/: byte-exact inputs scripts/fuzz.sh found
//     (the same folders seed the fuzzers, so a fixed bug stays fixed under fuzzing too);
//   - inputs built here: the limits of issue 9 (headers claiming billions of items, deep nesting).
// Every regression file must have an expectation below (RegressionFiles.EveryFileHasAnExpectation).
#include "test_support.h"

#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"

#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

using namespace groom;
namespace fs = std::filesystem;

namespace {

enum class Kind { Parse, Limit };

struct Target {
    const char* ext;
    bool mesh;
};

/// The fuzz targets (fuzz/<name>_fuzz.cpp) and which public reader reaches their parser.
const std::map<std::string, Target>& targets()
{
    static const std::map<std::string, Target> t{
        {"usda", {"usda", false}},     {"obj_curves", {"obj", false}}, {"ply_curves", {"ply", false}},
        {"hair", {"hair", false}},     {"obj_mesh", {"obj", true}},    {"ply_mesh", {"ply", true}},
        {"off", {"off", true}},        {"stl", {"stl", true}},
    };
    return t;
}

/// Writes `bytes` with the target's extension and reads it through the public API (read_curves /
/// read_mesh, as every command does). Returns "" when it was refused as expected, else what went wrong.
std::string refusal_problem(const std::string& target, const std::string& bytes, Kind kind, const std::string& message)
{
    const Target& t = targets().at(target);
    test::TempDir dir;
    const std::string path = dir.file(std::string("input.") + t.ext);
    test::write_text(path, bytes);
    try {
        if (t.mesh) read_mesh(path);
        else read_curves(path);
    }
    catch (const LimitExceeded& e) {
        if (kind != Kind::Limit) return std::string("LimitExceeded instead of ParseError: ") + e.what();
        if (std::string(e.what()).find(message) == std::string::npos) return "message lacks '" + message + "': " + e.what();
        return "";
    }
    catch (const ParseError& e) {
        if (kind != Kind::Parse) return std::string("ParseError instead of LimitExceeded: ") + e.what();
        if (std::string(e.what()).find(message) == std::string::npos) return "message lacks '" + message + "': " + e.what();
        return "";
    }
    catch (const std::exception& e) {
        return std::string("wrong error type: ") + e.what();
    }
    return "accepted instead of refused";
}

struct FileCase {
    const char* target;
    const char* file;     ///< under tests/data/regressions/<target>/
    Kind kind;
    const char* message;  ///< a part of the message that names the problem
};

/// Fuzzer findings, with what the input did before its fix (see `git log` of the fix for details).
const std::vector<FileCase> kFileCases = {
    // 184 million strands, 0 points, no segment array: allocated 1.4 GB of per-strand counts before
    // noticing the points could not add up.
    {"hair", "oom_184m_strands_no_segment_array.hair", Kind::Limit, "184549379 strands but only 0 points"},
    // ASCII face index 8.9e65 (declared int): refused as out of range, but the message cast the
    // double to int64 first (UBSan: value outside the range of 'long'). Since issue 20 an ASCII
    // integer outside its declared type is refused where it is read, before any index check.
    {"ply_mesh", "ub_face_index_9e65.ply", Kind::Parse, "property 'vertex_indices' is out of range for its type int"},
};

fs::path regressions_dir() { return fs::path(GROOM_SOURCE_DIR) / "tests" / "data" / "regressions"; }

template <class T> void put(std::string& s, T v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }

/// A 128-byte .hair header.
std::string hair_header(uint32_t strands, uint32_t points, uint32_t flags, uint32_t default_segments)
{
    std::string h = "HAIR";
    put(h, strands);
    put(h, points);
    put(h, flags);
    put(h, default_segments);
    h.resize(128, '\0');
    return h;
}

}  // namespace

TEST(RegressionFiles, EachIsRefusedCleanly)
{
    for (const FileCase& c : kFileCases) {
        const fs::path p = regressions_dir() / c.target / c.file;
        ASSERT_TRUE(fs::exists(p)) << p;
        EXPECT_EQ(refusal_problem(c.target, test::read_bytes(p.string()), c.kind, c.message), "") << p;
    }
}

TEST(RegressionFiles, EveryFileHasAnExpectation)
{
    std::set<std::string> listed;
    for (const FileCase& c : kFileCases) listed.insert(std::string(c.target) + "/" + c.file);
    if (!fs::exists(regressions_dir())) return;
    for (const auto& dir : fs::directory_iterator(regressions_dir())) {
        if (!dir.is_directory()) continue;
        EXPECT_TRUE(targets().count(dir.path().filename().string())) << "folder not named after a fuzz target: " << dir.path();
        for (const auto& f : fs::directory_iterator(dir.path())) {
            if (f.path().filename() == "README.md") continue;
            const std::string key = dir.path().filename().string() + "/" + f.path().filename().string();
            EXPECT_TRUE(listed.count(key)) << key << " has no expectation in kFileCases";
        }
    }
}

// --- Limits: absurd counts are refused before anything is allocated ----------------------------------
// Each header below claims about 4 billion items in a file of a few dozen bytes. Reading must fail
// fast with LimitExceeded naming the count; allocating for the claim first would need tens of GB.

TEST(Limits, PlyHeaderClaimingFourBillionVertices)
{
    const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
                             "property float z\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    EXPECT_EQ(refusal_problem("ply_curves", head + std::string(12, '\0'), Kind::Limit, "4000000000"), "");
    EXPECT_EQ(refusal_problem("ply_mesh", head + std::string(12, '\0'), Kind::Limit, "4000000000"), "");
    const std::string ascii = "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n"
                              "end_header\n0 0 0\n";
    EXPECT_EQ(refusal_problem("ply_mesh", ascii, Kind::Limit, "4000000000"), "");
}

TEST(Limits, HairHeaderClaimingFourBillionStrandsOrPoints)
{
    const uint32_t big = 4000000000u;
    EXPECT_EQ(refusal_problem("hair", hair_header(big, big, 1 | 2, 0) + std::string(64, '\0'), Kind::Limit, "4000000000"), "");
    EXPECT_EQ(refusal_problem("hair", hair_header(1, big, 2, big - 1) + std::string(64, '\0'), Kind::Limit, "4000000000"), "");
    // No segment array (flags without bit 1): every strand has the default segment count, so the
    // strand count is bounded only by points / (segments + 1): billions of strands of 0 points is absurd.
    EXPECT_EQ(refusal_problem("hair", hair_header(big, 0, 2, 0) + std::string(64, '\0'), Kind::Limit, "4000000000"), "");
}

TEST(Limits, OffHeaderClaimingFourBillionVerticesOrFaces)
{
    EXPECT_EQ(refusal_problem("off", "OFF\n4000000000 1 0\n0 0 0\n3 0 0 0\n", Kind::Limit, "4000000000"), "");
    EXPECT_EQ(refusal_problem("off", "OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", Kind::Limit, "4000000000"), "");
}

TEST(Limits, BinaryStlClaimingFourBillionTriangles)
{
    std::string stl(80, '\0');
    put(stl, uint32_t{4000000000u});
    stl.append(50, '\0');  // one triangle
    // A count that disagrees with the file size is how binary STL is told from ASCII, so the reader
    // reports it as a parse error; what matters is that it names the claim and allocates nothing.
    EXPECT_EQ(refusal_problem("stl", stl, Kind::Parse, "claims 4000000000 triangles"), "");
}

TEST(Limits, ObjIndexBeyondTwoBillionIsAParseError)
{
    EXPECT_EQ(refusal_problem("obj_curves", "v 0 0 0\nv 0 1 0\nl 1 4000000000\n", Kind::Parse, "4000000000"), "");
    EXPECT_EQ(refusal_problem("obj_mesh", "v 0 0 0\nf 1 1 4000000000\n", Kind::Parse, "4000000000"), "");
}

TEST(Limits, UsdaCountsThatDisagreeWithThePointsAreRefused)
{
    EXPECT_EQ(refusal_problem("usda",
                              "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n"
                              " int[] curveVertexCounts = [2000000000, 2000000000]\n point3f[] points = [(0,0,0), (1,1,1)]\n}\n",
                              Kind::Parse, "4000000000"),
              "");
}

// --- Limits: nesting ---------------------------------------------------------------------------------

TEST(Limits, DeeplyNestedUsdaPrimsAreRefusedNotAStackOverflow)
{
    // 100000 nested prims (1.4 MB): a recursive-descent parser without a depth limit overflows the
    // stack here (a crash, not a message).
    std::string s = "#usda 1.0\n";
    const int depth = 100000;
    for (int i = 0; i < depth; ++i) s += "def Xform \"x\" {\n";
    s += std::string(depth, '}');
    EXPECT_EQ(refusal_problem("usda", s, Kind::Limit, "nested"), "");
}

TEST(Limits, ModeratelyNestedUsdaPrimsStillRead)
{
    // Real scenes nest prims a few dozen levels deep; 100 levels must still read.
    std::string s = "#usda 1.0\n";
    for (int i = 0; i < 100; ++i) s += "def Xform \"x\" {\n";
    s += "def BasisCurves \"c\" {\n uniform token type = \"linear\"\n int[] curveVertexCounts = [2]\n"
         " point3f[] points = [(0,0,0), (0,1,0)]\n}\n";
    s += std::string(100, '}');
    test::TempDir dir;
    const std::string path = dir.file("nested.usda");
    test::write_text(path, s);
    const CurveSet cs = read_curves(path);
    EXPECT_EQ(cs.num_curves(), 1u);
    EXPECT_EQ(cs.num_points(), 2u);
}

TEST(Limits, DeeplyNestedUsdaValuesAreSkippedWithoutRecursion)
{
    // A property we do not keep, with a value nested 200000 brackets deep: skipped iteratively.
    std::string s = "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n custom int[] junk = ";
    s += std::string(200000, '[') + std::string(200000, ']') + "\n int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (0,1,0)]\n}\n";
    test::TempDir dir;
    const std::string path = dir.file("deep_value.usda");
    test::write_text(path, s);
    EXPECT_EQ(read_curves(path).num_points(), 2u);
}

TEST(Limits, OverlongUsdaPrimPathsAreRefused)
{
    // 500 levels of 100-character names: each open prim holds its whole path (up to 50 kB), which
    // would cost memory quadratic in the file size; refused at the 4096-character path limit.
    std::string s = "#usda 1.0\n";
    for (int i = 0; i < 500; ++i) s += "def Xform \"" + std::string(100, 'n') + "\" {\n";
    s += std::string(500, '}');
    EXPECT_EQ(refusal_problem("usda", s, Kind::Limit, "prim path longer than 4096"), "");
}

TEST(Limits, PlyIndicesAndCountsThatNoIntegerHoldsAreRefused)
{
    // Same class as ub_face_index_9e65.ply, through the other places a PLY number becomes an index
    // or a count: NaN, 1e300 and fractions in float-typed properties must be refused, not cast (UB).
    // (1e300 in a float property is refused as out of the float's range, before it is an index.)
    const std::string verts = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string head = "ply\nformat ascii 1.0\n" + verts;
    const std::string pts = "0 0 0\n0 1 0\n0 2 0\n";
    for (const char* bad : {"nan", "1e300", "-inf", "1.5"}) {
        EXPECT_EQ(refusal_problem("ply_mesh", head + "element face 1\nproperty list uchar float vertex_indices\nend_header\n" + pts +
                                                  "3 0 1 " + bad + "\n",
                                  Kind::Parse, "out of range"),
                  "")
            << bad;
        EXPECT_EQ(refusal_problem("ply_curves", head + "element edge 1\nproperty float vertex1\nproperty float vertex2\nend_header\n" +
                                                    pts + "0 " + bad + "\n",
                                  Kind::Parse, "out of range"),
                  "")
            << bad;
        EXPECT_EQ(refusal_problem("ply_curves", head + "element curve 1\nproperty double point_count\nend_header\n" + pts + bad + "\n",
                                  Kind::Parse, "is not a count of 0 to 3 vertices"),
                  "")
            << bad;
    }
}
