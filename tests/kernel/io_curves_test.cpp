// Curve file formats: exact USD and OBJ round trips, real guide strands, cubic USD against closed
// forms, malformed input checked for the error text, and truncated or corrupted files of every format.
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/math/spline.h"
#include "test_support.h"
#include "tests/kernel/curve_samples.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

using namespace groom;
using groom::test::TempDir;
using groom::test::expect_attributes_equal;
using groom::test::expect_parse_error;
using groom::test::expect_points_bit_exact;
using groom::test::read_bytes;
using groom::test::sample_curves;
using groom::test::write_text;

TEST(CurveIoUsda, RoundTripKeepsEveryPointAndAttributeBitExactly)
{
    TempDir dir;
    const CurveSet src = sample_curves();
    write_curves(src, dir.file("a.usda"));
    const CurveSet back = read_curves(dir.file("a.usda"));
    expect_points_bit_exact(src, back);
    expect_attributes_equal(src, back);
}

TEST(CurveIoUsda, ReadThenWrittenAgainIsTheSameFileByteForByte)
{
    // Attributes keep the order they were written in, not their names' order (z before a here):
    // `groom convert` of a .usda, and shards merged by `groom merge`, give the file back unchanged.
    TempDir dir;
    CurveSet src = CurveSet::from_counts(std::vector<int64_t>{3, 2});
    auto P = src.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(float(i), 0.5f * float(i), 0.0f);
    auto z = src.add<int32_t>(Domain::Point, "zeta");
    auto a = src.add<float>(Domain::Point, "alpha");
    auto zc = src.add<int32_t>(Domain::Curve, "zc");
    auto ac = src.add<float>(Domain::Curve, "ac");
    for (size_t i = 0; i < z.size(); ++i) z[i] = int32_t(i), a[i] = 0.25f * float(i);
    zc[0] = 7, zc[1] = 8, ac[0] = 1.5f, ac[1] = -2.0f;
    write_curves(src, dir.file("a.usda"));
    write_curves(read_curves(dir.file("a.usda")), dir.file("b.usda"));
    EXPECT_EQ(read_bytes(dir.file("a.usda")), read_bytes(dir.file("b.usda")));
}

TEST(CurveIoUsda, WritesSchemaRulesFromNotes)
{
    TempDir dir;
    write_curves(sample_curves(), dir.file("a.usda"));
    const std::string text = read_bytes(dir.file("a.usda"));
    EXPECT_EQ(text.rfind("#usda 1.0\n", 0), 0u);
    EXPECT_NE(text.find("upAxis = \"Y\""), std::string::npos);
    EXPECT_NE(text.find("defaultPrim = \"groom\""), std::string::npos);
    EXPECT_NE(text.find("def BasisCurves \"groom\""), std::string::npos);
    EXPECT_NE(text.find("uniform token type = \"linear\""), std::string::npos);
    EXPECT_NE(text.find("float[] widths = ["), std::string::npos);
    EXPECT_NE(text.find("int64[] primvars:id = ["), std::string::npos);
    EXPECT_NE(text.find("float3[] primvars:Cd = ["), std::string::npos);
    EXPECT_NE(text.find("string primvars:source = \"groom test \\\"quoted\\\"\\nsecond"), std::string::npos);
    // One BasisCurves prim only.
    EXPECT_EQ(text.find("def BasisCurves", text.find("def BasisCurves") + 1), std::string::npos);
}

TEST(CurveIoUsda, ReadsPrimsInsideXformWithCommentsMetadataAndOtherPrims)
{
    TempDir dir;
    const std::string text = R"(#usda 1.0
(
    defaultPrim = "root"   # trailing comment
    metersPerUnit = 0.01
    customLayerData = { string creator = "hand (written) [test]" }
)

def Xform "root" (
    kind = "component"
    prepend apiSchemas = ["MaterialBindingAPI"]
)
{
    double3 xformOp:translate = (0, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
    def Mesh "ignored" { int[] faceVertexCounts = [3] point3f[] points = [(0,0,0), (1,0,0), (0,1,0)] }
    def BasisCurves "hair" (
        doc = """a
multi-line doc"""
    )
    {
        uniform token type = "linear"
        int[] curveVertexCounts = [2, 3]
        point3f[] points = [(0, 0, 0), (0, 1, 0),
                            (1, 0, 0), (1, 1, 0), (1, 2.5, -0)]  // second curve
        float[] widths = [0.1] (interpolation = "constant")
        color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (
            interpolation = "uniform"
        )
        float[] primvars:u = [0, 1, 0, 0.5, 1] (interpolation = "vertex")
        rel material:binding = </root/mat>
        float3[] extent.timeSamples = { 1: [(0,0,0),(1,2.5,0)], }
    }
}
)";
    write_text(dir.file("x.usda"), text);
    const CurveSet cs = read_curves(dir.file("x.usda"));
    ASSERT_EQ(cs.num_curves(), 2u);
    ASSERT_EQ(cs.num_points(), 5u);
    EXPECT_EQ(cs.positions()[4], float3(1, 2.5f, 0));
    auto w = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), 5u);
    for (float v : w) EXPECT_EQ(v, 0.1f);
    auto color = cs.find<float3>(Domain::Curve, "displayColor");
    ASSERT_EQ(color.size(), 2u);
    EXPECT_EQ(color[1], float3(0, 1, 0));
    auto u = cs.find<float>(Domain::Point, "u");
    ASSERT_EQ(u.size(), 5u);
    EXPECT_EQ(u[3], 0.5f);
}

TEST(CurveIoUsda, ArraysWithCommentsSpecialValuesAndTinyNumbersParse)
{
    // These defeat the fast array scanner on purpose; the token parser must take over.
    TempDir dir;
    write_text(dir.file("s.usda"), R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "linear"
    int[] curveVertexCounts = [ # two curves
        1, 2, ]
    point3f[] points = [(0, 0, 0), # root
                        (1e-50, +2, -3), (4.5, 1E3, 0)]
    float[] primvars:f = [inf, -inf, nan] (interpolation = "vertex")
    bool[] primvars:b = [true, false] (interpolation = "uniform")
}
)");
    const CurveSet cs = read_curves(dir.file("s.usda"));
    ASSERT_EQ(cs.num_curves(), 2u);
    EXPECT_EQ(cs.positions()[1], float3(0, 2, -3));  // 1e-50 underflows to 0 in float
    EXPECT_EQ(cs.positions()[2], float3(4.5f, 1000, 0));
    auto f = cs.find<float>(Domain::Point, "f");
    ASSERT_EQ(f.size(), 3u);
    EXPECT_TRUE(std::isinf(f[0]) && f[0] > 0);
    EXPECT_TRUE(std::isnan(f[2]));
    auto b = cs.find<int32_t>(Domain::Curve, "b");
    ASSERT_EQ(b.size(), 2u);
    EXPECT_EQ(b[0], 1);
}

TEST(CurveIoUsda, ConcatenatesEveryBasisCurvesPrim)
{
    TempDir dir;
    write_text(dir.file("two.usda"), R"(#usda 1.0
def BasisCurves "a" { uniform token type = "linear" int[] curveVertexCounts = [2] point3f[] points = [(0,0,0),(0,1,0)] }
def Scope "s" { def BasisCurves "b" { uniform token type = "linear" int[] curveVertexCounts = [3] point3f[] points = [(1,0,0),(1,1,0),(1,2,0)] } }
)");
    const CurveSet cs = read_curves(dir.file("two.usda"));
    ASSERT_EQ(cs.num_curves(), 2u);
    EXPECT_EQ(cs.points_in(1), 3);
    EXPECT_EQ(cs.positions()[4], float3(1, 2, 0));
}

TEST(CurveIoUsda, CubicCatmullRomMatchesClosedForm)
{
    // Control points on the parabola y = x^2 at x = -1, 0, 1, 2: the Catmull-Rom segment between
    // x = 0 and x = 1 reproduces a quadratic exactly (the basis reproduces polynomials up to degree 2).
    TempDir dir;
    write_text(dir.file("c.usda"), R"(#usda 1.0
def BasisCurves "c" {
    uniform token type = "cubic"
    uniform token basis = "catmullRom"
    int[] curveVertexCounts = [4]
    point3f[] points = [(-1, 1, 0), (0, 0, 0), (1, 1, 0), (2, 4, 0)]
    float[] widths = [1, 2, 3, 4] (interpolation = "vertex")
})");
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 10;
    const CurveSet cs = read_curves(dir.file("c.usda"), opt);
    ASSERT_EQ(cs.num_curves(), 1u);
    ASSERT_EQ(cs.num_points(), 11u);
    auto P = cs.positions();
    auto w = cs.find<float>(Domain::Point, attr::width);
    for (int j = 0; j <= 10; ++j) {
        const float x = j / 10.0f;
        EXPECT_NEAR(P[j].x, x, 1e-6f);
        EXPECT_NEAR(P[j].y, x * x, 1e-6f);
        EXPECT_NEAR(w[j], 2.0f + x, 1e-6f);  // widths are linear in the index: reproduced exactly
    }
}

TEST(CurveIoUsda, CubicBsplinePinnedMatchesClosedForm)
{
    // A uniform cubic B-spline over collinear, evenly spaced control points is the straight line
    // through them at uniform speed; pinned ends (phantom 2*p0 - p1) keep that, so the curve runs
    // exactly from the first to the last control point.
    TempDir dir;
    write_text(dir.file("b.usda"), R"(#usda 1.0
def BasisCurves "b" {
    uniform token type = "cubic"
    uniform token basis = "bspline"
    uniform token wrap = "pinned"
    int[] curveVertexCounts = [3]
    point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0)]
})");
    CurveReadOptions opt;
    opt.cubic_samples_per_segment = 4;
    const CurveSet cs = read_curves(dir.file("b.usda"), opt);
    ASSERT_EQ(cs.num_points(), 9u);  // 2 segments x 4 + 1
    auto P = cs.positions();
    for (int j = 0; j <= 8; ++j) {
        EXPECT_NEAR(P[j].x, 0.0f, 1e-6f);
        EXPECT_NEAR(P[j].y, j * 0.25f, 1e-6f);
    }
}

TEST(CurveIoUsda, RejectsMalformedInputNamingFileLineExpectedAndFound)
{
    TempDir dir;
    const std::string head = "#usda 1.0\ndef BasisCurves \"c\" {\n uniform token type = \"linear\"\n";
    expect_parse_error(dir.file("empty.usda"), "", "empty");
    expect_parse_error(dir.file("noheader.usda"), "def BasisCurves \"c\" {}\n", "expected the '#usda 1.0' header");
    expect_parse_error(dir.file("trunc.usda"), head + " int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (1,",
                       "trunc.usda:5: expected a number, found end of file");
    expect_parse_error(dir.file("count.usda"), head + " int[] curveVertexCounts = [3]\n point3f[] points = [(0,0,0), (1,1,1)]\n}\n",
                       "count.usda:4: curveVertexCounts sum to 3 but 'points' (line 5) has 2 points");
    expect_parse_error(dir.file("nan.usda"), head + " int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (nan,1,1)]\n}\n",
                       "nan.usda:5: points[1] is not finite");
    expect_parse_error(dir.file("widths.usda"),
                       head + " int[] curveVertexCounts = [2]\n point3f[] points = [(0,0,0), (1,1,1)]\n float[] widths = [1,2,3] (interpolation = \"vertex\")\n}\n",
                       "widths.usda:6: widths has 3 values but interpolation 'vertex' needs 2");
    expect_parse_error(dir.file("brace.usda"), head + " int[] curveVertexCounts = [2]\n", "expected '}' closing prim </c>, found end of file");
    expect_parse_error(dir.file("none.usda"), "#usda 1.0\ndef Xform \"x\" {}\n", "expected a 'def BasisCurves' or 'def NurbsCurves' prim, found none");
    expect_parse_error(dir.file("short.usda"), "#usda 1.0\ndef BasisCurves \"c\" { uniform token type = \"cubic\" uniform token basis = \"bspline\"\n int[] curveVertexCounts = [3] point3f[] points = [(0,0,0),(0,0,0),(0,0,0)] }\n",
                       "short.usda:2: BasisCurves </c>: cubic bspline nonperiodic curve 0 has 3 points; it needs at least 4");
    expect_parse_error(dir.file("wrap.usda"), head + " uniform token wrap = \"spiral\" int[] curveVertexCounts = [2] point3f[] points = [(0,0,0),(0,0,1)] }\n",
                       "wrap 'spiral' is not supported (expected nonperiodic, periodic or pinned)");
}

TEST(CurveIoUsda, RefusesNamesUsdCannotHoldWithoutLeavingAFile)
{
    TempDir dir;
    CurveSet cs = sample_curves(false);
    cs.add<float>(Domain::Point, "bad name");
    EXPECT_THROW(write_curves(cs, dir.file("o.usda")), InvalidParam);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(CurveIoObj, RoundTripKeepsEveryPointBitExactly)
{
    TempDir dir;
    const CurveSet src = sample_curves(false);
    write_curves(src, dir.file("a.obj"));
    const CurveSet back = read_curves(dir.file("a.obj"));
    expect_points_bit_exact(src, back);
}

TEST(CurveIoObj, UsdaToObjToUsdaKeepsPoints)
{
    TempDir dir;
    const CurveSet src = sample_curves();
    write_curves(src, dir.file("a.usda"));
    write_curves(read_curves(dir.file("a.usda")), dir.file("b.obj"));
    write_curves(read_curves(dir.file("b.obj")), dir.file("c.usda"));
    expect_points_bit_exact(src, read_curves(dir.file("c.usda")));
}

TEST(CurveIoObj, ReadsNegativeIndicesSlashFormsAndComments)
{
    TempDir dir;
    write_text(dir.file("a.obj"), "# c\no strands\nv 0 0 0\nv 0 1 0 1.0\nv 0 2 0\nl -3 -2/5 -1  # tail\nvt 0 0\nv 5 5 5\nv 6 6 6\nl 4 5\n");
    const CurveSet cs = read_curves(dir.file("a.obj"));
    ASSERT_EQ(cs.num_curves(), 2u);
    EXPECT_EQ(cs.points_in(0), 3);
    EXPECT_EQ(cs.positions()[2], float3(0, 2, 0));
    EXPECT_EQ(cs.positions()[4], float3(6, 6, 6));
}

TEST(CurveIoObj, RejectsMalformedInput)
{
    TempDir dir;
    expect_parse_error(dir.file("empty.obj"), "", "file is empty");
    expect_parse_error(dir.file("range.obj"), "v 0 0 0\nv 1 1 1\nl 1 2 3\n", "range.obj:3: vertex index 3 out of range (2 vertices)");
    expect_parse_error(dir.file("nan.obj"), "v 0 0 0\nv nan 1 1\nl 1 2\n", "nan.obj:2: vertex coordinate is not finite");
    expect_parse_error(dir.file("trunc.obj"), "v 0 0 0\nv 1 1\n", "trunc.obj:2: expected 3 vertex coordinates, found end of line");
    expect_parse_error(dir.file("zero.obj"), "v 0 0 0\nl 0 1\n", "zero.obj:2: vertex index 0 is invalid");
    expect_parse_error(dir.file("word.obj"), "v 0 0 0\nbogus 1\n", "word.obj:2: expected an OBJ record");
    expect_parse_error(dir.file("mesh.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "this is a mesh");
    expect_parse_error(dir.file("neg.obj"), "v 0 0 0\nl -1 -2\n", "neg.obj:2: relative vertex index -2 reaches before the first vertex");
}

TEST(CurveIo, UnknownExtensionIsRefused)
{
    TempDir dir;
    EXPECT_THROW(write_curves(sample_curves(false), dir.file("a.abc")), InvalidParam);
    write_text(dir.file("a.txt"), "x");
    EXPECT_THROW(read_curves(dir.file("a.txt")), IoError);
    EXPECT_THROW(read_curves(dir.file("missing.usda")), IoError);
}

TEST(CurveIoReal, SintelGuidesHave228StrandsOf32Points)
{
    GROOM_REQUIRE_SHARED(path, "sintel_tressfx_opengl/sintel_guides.obj");
    const CurveSet cs = read_curves(path);
    EXPECT_EQ(cs.num_curves(), 228u);
    EXPECT_EQ(cs.num_points(), 228u * 32u);
    for (size_t c = 0; c < cs.num_curves(); ++c) ASSERT_EQ(cs.points_in(c), 32);
    EXPECT_EQ(cs.positions()[0], float3(-8.315415f, 34.92955f, -2.681878f));  // first `v` line of the file
}

TEST(CurveIoReal, PonytailGuidesHave16PointsPerStrand)
{
    const std::pair<const char*, size_t> files[] = {{"amd_tressfx_ponytail/front_top_guides.obj", 876},
                                                    {"amd_tressfx_ponytail/side_guides.obj", 3066},
                                                    {"amd_tressfx_ponytail/back_guides.obj", 517},
                                                    {"amd_tressfx_ponytail/tail_guides.obj", 474}};
    size_t total = 0;
    for (const auto& [rel, strands] : files) {
        GROOM_REQUIRE_SHARED(path, rel);
        const CurveSet cs = read_curves(path);
        EXPECT_EQ(cs.num_curves(), strands) << rel;
        EXPECT_EQ(cs.num_points(), strands * 16) << rel;
        total += cs.num_curves();
    }
    EXPECT_EQ(total, 4933u);  // the dataset README's count
}

TEST(CurveIoReal, MohawkGuidesHave2228StrandsOf32Points)
{
    GROOM_REQUIRE_SHARED(path, "ratboy_mohawk_tressfx/mohawk_guides.obj");
    const CurveSet cs = read_curves(path);
    EXPECT_EQ(cs.num_curves(), 2228u);
    EXPECT_EQ(cs.num_points(), 2228u * 32u);
}

TEST(CurveIoReal, SintelGuidesRoundTripThroughUsdaExactly)
{
    GROOM_REQUIRE_SHARED(path, "sintel_tressfx_opengl/sintel_guides.obj");
    TempDir dir;
    const CurveSet src = read_curves(path);
    write_curves(src, dir.file("s.usda"));
    expect_points_bit_exact(src, read_curves(dir.file("s.usda")));
}

namespace {
size_t n_flip_stride(size_t size) { return std::max<size_t>(1, size / 150) | 1; }
}  // namespace

TEST(CurveIo, TruncatedOrCorruptedFilesFailWithParseErrorsNeverCrash)
{
    // Every prefix (binary formats) or many prefixes (text formats) of a valid file, and single-byte
    // corruptions, either parse or throw one of groom's errors naming the file: no other exception,
    // no crash (run under GROOM_SANITIZE to catch out-of-bounds reads).
    TempDir dir;
    const CurveSet src = sample_curves();
    CurveWriteOptions ascii;
    ascii.ply_encoding = PlyEncoding::Ascii;
    const std::pair<std::string, CurveWriteOptions> formats[] = {{"a.usda", {}}, {"a.ply", {}}, {"b.ply", ascii}, {"a.hair", {}}, {"a.obj", {}}};
    for (const auto& format : formats) {
        const std::string& name = format.first;  // not a structured binding: clang 14 cannot capture those
        write_curves(src, dir.file(name), format.second);
        const std::string bytes = read_bytes(dir.file(name));
        size_t k = 0;
        // Every header byte, then a sample of the body (odd strides hit every alignment).
        const size_t stride = std::max<size_t>(1, bytes.size() / 300) | 1;
        auto check = [&](const std::string& content, const std::string& what) {
            // A fresh name each time: rewriting one file with O_TRUNC makes ext4 flush it on close.
            const std::string bad = dir.file(std::to_string(k++) + "_" + name);
            write_text(bad, content);
            struct Remove {
                std::string path;
                ~Remove() { std::filesystem::remove(path); }
            } remove_after{bad};
            try {
                read_curves(bad);
            }
            catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << what << ": " << e.what();
            }
            catch (const std::exception& e) {
                ADD_FAILURE() << name << " " << what << ": unexpected " << typeid(e).name() << ": " << e.what();
            }
        };
        for (size_t n = 0; n < bytes.size(); n += n < 200 ? 1 : stride) check(bytes.substr(0, n), "prefix " + std::to_string(n));
        for (size_t i = 0; i < bytes.size(); i += n_flip_stride(bytes.size())) {
            std::string c = bytes;
            c[i] = static_cast<char>(c[i] ^ 0x5a);
            check(c, "byte " + std::to_string(i) + " flipped");
        }
    }
}
