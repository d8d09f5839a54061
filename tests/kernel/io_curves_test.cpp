// Curve file formats: exact round trips, real guide strands, cubic USD against closed forms, and
// malformed input checked for the error text.
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/math/spline.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

using namespace groom;
using groom::test::TempDir;
using groom::test::read_bytes;
using groom::test::write_text;

namespace {

/// Awkward floats on purpose: values with no short decimal form, tiny and huge magnitudes, -0.
CurveSet sample_curves(bool with_attributes = true)
{
    const std::vector<int64_t> counts{3, 5, 2, 4};
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) {
        const float t = static_cast<float>(i);
        P[i] = {std::nextafter(0.1f * t, 1.0f), std::sin(t) * 1e-7f + 1.0f / 3.0f, -1234.5678f * t - 1e-30f};
    }
    P[0].z = -0.0f;
    if (!with_attributes) return cs;
    auto w = cs.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < w.size(); ++i) w[i] = 0.01f / (1.0f + static_cast<float>(i));
    auto cd = cs.add<float3>(Domain::Point, "Cd");
    for (size_t i = 0; i < cd.size(); ++i) cd[i] = {0.1f * i, 0.7f, 1.0f / (i + 3.0f)};
    auto seg = cs.add<int32_t>(Domain::Point, "segment");
    for (size_t i = 0; i < seg.size(); ++i) seg[i] = static_cast<int32_t>(i) - 5;
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    for (size_t c = 0; c < id.size(); ++c) id[c] = (int64_t(1) << 40) + static_cast<int64_t>(c) * 7;
    auto len = cs.add<float>(Domain::Curve, "clump");
    for (size_t c = 0; c < len.size(); ++c) len[c] = 1.0f / (c + 7.0f);
    cs.add<float3>(Domain::Curve, "root_uv")[2] = {0.25f, 0.5f, 0.0f};
    cs.set_detail_string("source", "groom test \"quoted\"\nsecond line \\ backslash");
    cs.add<float>(Domain::Detail, "scale")[0] = 0.017f;
    cs.add<int32_t>(Domain::Detail, "seed")[0] = -42;
    cs.add<float3>(Domain::Detail, "up")[0] = {0.0f, 1.0f, 0.0f};
    return cs;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_points_bit_exact(const CurveSet& a, const CurveSet& b)
{
    ASSERT_EQ(a.num_curves(), b.num_curves());
    ASSERT_EQ(a.num_points(), b.num_points());
    for (size_t c = 0; c <= a.num_curves(); ++c) EXPECT_EQ(a.offsets()[c], b.offsets()[c]);
    auto pa = a.positions(), pb = b.positions();
    for (size_t i = 0; i < pa.size(); ++i) {
        EXPECT_TRUE(same_bits(pa[i].x, pb[i].x) && same_bits(pa[i].y, pb[i].y) && same_bits(pa[i].z, pb[i].z))
            << "point " << i << ": " << pa[i].x << "," << pa[i].y << "," << pa[i].z << " vs " << pb[i].x << "," << pb[i].y << "," << pb[i].z;
    }
}

/// Every column of `a` exists in `b` with the same domain, type and bit-identical values.
void expect_attributes_equal(const CurveSet& a, const CurveSet& b)
{
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
        for (const Attribute& col : a.attributes(d).all()) {
            const Attribute* other = b.attributes(d).find(col.name);
            ASSERT_NE(other, nullptr) << domain_name(d) << " attribute " << col.name << " lost";
            ASSERT_EQ(other->type(), col.type()) << col.name;
            ASSERT_EQ(other->size(), col.size()) << col.name;
            std::visit(
                [&](const auto& va) {
                    using V = std::decay_t<decltype(va)>;
                    const V& vb = std::get<V>(other->data);
                    if constexpr (std::is_same_v<V, std::vector<std::string>>) {
                        EXPECT_EQ(va, vb) << col.name;
                    }
                    else {
                        EXPECT_EQ(std::memcmp(va.data(), vb.data(), va.size() * sizeof(va[0])), 0) << col.name;
                    }
                },
                col.data);
        }
        EXPECT_EQ(a.attributes(d).count(), b.attributes(d).count()) << "extra attributes on " << domain_name(d);
    }
}

void expect_parse_error(const std::string& path, const std::string& text, const std::string& needle)
{
    write_text(path, text);
    try {
        read_curves(path);
        ADD_FAILURE() << "no error reading " << path;
    }
    catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what() << "\nexpected to contain: " << needle;
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << "message does not name the file: " << e.what();
    }
}

}  // namespace

TEST(CurveIoUsda, RoundTripKeepsEveryPointAndAttributeBitExactly)
{
    TempDir dir;
    const CurveSet src = sample_curves();
    write_curves(src, dir.file("a.usda"));
    const CurveSet back = read_curves(dir.file("a.usda"));
    expect_points_bit_exact(src, back);
    expect_attributes_equal(src, back);
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
    expect_parse_error(dir.file("none.usda"), "#usda 1.0\ndef Xform \"x\" {}\n", "expected a 'def BasisCurves' prim, found none");
    expect_parse_error(dir.file("bezier.usda"), "#usda 1.0\ndef BasisCurves \"c\" { int[] curveVertexCounts = [4] point3f[] points = [(0,0,0),(0,0,0),(0,0,0),(0,0,0)] }\n",
                       "cubic basis 'bezier' is not supported");
    expect_parse_error(dir.file("short.usda"), "#usda 1.0\ndef BasisCurves \"c\" { uniform token type = \"cubic\" uniform token basis = \"bspline\"\n int[] curveVertexCounts = [3] point3f[] points = [(0,0,0),(0,0,0),(0,0,0)] }\n",
                       "short.usda:3: cubic nonperiodic curve 0 has 3 points; it needs at least 4");
    expect_parse_error(dir.file("periodic.usda"), head + " uniform token wrap = \"periodic\" int[] curveVertexCounts = [2] point3f[] points = [(0,0,0),(0,0,1)] }\n",
                       "wrap 'periodic'");
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

// --- PLY ---------------------------------------------------------------------------------------------

TEST(CurveIoPly, BinaryAndAsciiRoundTripsKeepEveryAttributeBitExactly)
{
    TempDir dir;
    const CurveSet src = sample_curves();
    for (PlyEncoding enc : {PlyEncoding::Binary, PlyEncoding::Ascii}) {
        CurveWriteOptions opt;
        opt.ply_encoding = enc;
        write_curves(src, dir.file("a.ply"), opt);
        const CurveSet back = read_curves(dir.file("a.ply"));
        expect_points_bit_exact(src, back);
        expect_attributes_equal(src, back);
    }
}

TEST(CurveIoPly, UsdaToPlyToUsdaKeepsEverything)
{
    TempDir dir;
    const CurveSet src = sample_curves();
    write_curves(src, dir.file("a.usda"));
    write_curves(read_curves(dir.file("a.usda")), dir.file("b.ply"));
    write_curves(read_curves(dir.file("b.ply")), dir.file("c.usda"));
    const CurveSet back = read_curves(dir.file("c.usda"));
    expect_points_bit_exact(src, back);
    expect_attributes_equal(src, back);
}

TEST(CurveIoPly, WritesVertexAndEdgeElementsOtherReadersUnderstand)
{
    TempDir dir;
    CurveWriteOptions opt;
    opt.ply_encoding = PlyEncoding::Ascii;
    write_curves(sample_curves(), dir.file("a.ply"), opt);
    const std::string text = read_bytes(dir.file("a.ply"));
    EXPECT_NE(text.find("element vertex 14\nproperty float x\nproperty float y\nproperty float z\nproperty float width\n"), std::string::npos);
    EXPECT_NE(text.find("property float Cd_x\nproperty float Cd_y\nproperty float Cd_z\n"), std::string::npos);
    EXPECT_NE(text.find("element edge 10\nproperty int vertex1\nproperty int vertex2\n"), std::string::npos);  // 2 + 4 + 1 + 3 segments
    EXPECT_NE(text.find("\n0 1\n1 2\n3 4\n"), std::string::npos);  // edges join consecutive points within a curve only
}

TEST(CurveIoPly, RebuildsChainsFromForeignEdgeOnlyFiles)
{
    // Two curves written by another program: vertices out of order, edges pointing root -> tip,
    // plus an isolated vertex (a one-point curve) and an extra float property.
    TempDir dir;
    write_text(dir.file("f.ply"), "ply\nformat ascii 1.0\ncomment from elsewhere\nelement vertex 6\nproperty double x\nproperty double y\nproperty double z\n"
                                  "property uchar flag\nelement edge 3\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                                  "0 2 0 1\n0 1 0 2\n0 0 0 3\n5 0 0 4\n5 1 0 5\n9 9 9 6\n"
                                  "2 1\n1 0\n3 4\n");
    const CurveSet cs = read_curves(dir.file("f.ply"));
    ASSERT_EQ(cs.num_curves(), 3u);
    EXPECT_EQ(cs.points_in(0), 3);
    EXPECT_EQ(cs.positions()[0], float3(0, 0, 0));  // root: the vertex no edge points to
    EXPECT_EQ(cs.positions()[2], float3(0, 2, 0));
    EXPECT_EQ(cs.points_in(1), 2);
    EXPECT_EQ(cs.points_in(2), 1);
    auto flag = cs.find<int32_t>(Domain::Point, "flag");
    ASSERT_EQ(flag.size(), 6u);
    EXPECT_EQ(flag[0], 3);
}

TEST(CurveIoPly, ReadsBigEndianBinary)
{
    TempDir dir;
    std::string text = "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                       "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    auto be32 = [&](uint32_t u) { for (int s = 24; s >= 0; s -= 8) text += static_cast<char>((u >> s) & 0xff); };
    auto bef = [&](float f) { uint32_t u; std::memcpy(&u, &f, 4); be32(u); };
    for (float f : {1.5f, -2.0f, 0.1f, 3.0f, 4.0f, 5.0f}) bef(f);
    be32(0);
    be32(1);
    write_text(dir.file("be.ply"), text);
    const CurveSet cs = read_curves(dir.file("be.ply"));
    ASSERT_EQ(cs.num_curves(), 1u);
    EXPECT_EQ(cs.positions()[0], float3(1.5f, -2.0f, 0.1f));
    EXPECT_EQ(cs.positions()[1], float3(3, 4, 5));
}

TEST(CurveIoPly, RejectsMalformedInput)
{
    TempDir dir;
    const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    expect_parse_error(dir.file("huge.ply"), head + std::string(24, '\0'), "header claims 4000000000 vertex rows");
    const std::string two = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                            "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    expect_parse_error(dir.file("trunc.ply"), two + std::string(24 + 5, '\0'), "trunc.ply: byte 196: header claims 1 edge rows (at least 8 bytes each) but only 5 bytes follow");
    // A list element cannot be sized up front: truncation inside it is found while reading.
    const std::string mesh = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                             "element edge 1\nproperty list uchar int vertex_indices\nend_header\n";
    expect_parse_error(dir.file("list.ply"), mesh + std::string("\3\0\0\0\0\0", 6), "list.ply: byte 170: truncated: expected 12 bytes for edge 0 property 'vertex_indices', found 5");
    const std::string ascii = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                              "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    expect_parse_error(dir.file("range.ply"), ascii + "0 0 0\n1 1 1\n0 7\n", "edge 0 joins vertex 0 and 7: index out of range (2 vertices)");
    expect_parse_error(dir.file("nan.ply"), ascii + "0 0 0\nnan 1 1\n0 1\n", "vertex 1 has a non-finite position");
    expect_parse_error(dir.file("short.ply"), ascii + "0 0 0\n1 1\n", "short.ply:13: expected a number for vertex 1 property 'z', found end of file");
    expect_parse_error(dir.file("word.ply"), ascii + "0 0 0\n1 x 1\n0 1\n", "word.ply:12: expected a number for vertex 1 property 'y', found 'x'");
    expect_parse_error(dir.file("magic.ply"), "plx\n", "magic.ply:1: expected 'ply' magic");
    expect_parse_error(dir.file("header.ply"), "ply\nformat ascii 1.0\nelement vertex 1\n", "expected 'end_header', found end of file");
    expect_parse_error(dir.file("type.ply"), "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
                       "type.ply:4: expected a PLY type");
    expect_parse_error(dir.file("noedge.ply"), "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
                       "expected an 'edge' element");
    expect_parse_error(dir.file("fork.ply"), ascii.substr(0, ascii.find("element edge")) + "element edge 3\nproperty int vertex1\nproperty int vertex2\nend_header\n0 0 0\n1 1 1\n0 1\n0 1\n0 1\n",
                       "has more than two edges");
}

TEST(CurveIoPly, RefusesInt64BeyondDoublePrecisionWithoutLeavingAFile)
{
    TempDir dir;
    CurveSet cs = sample_curves(false);
    cs.add<int64_t>(Domain::Curve, attr::id)[1] = (int64_t(1) << 60) + 1;
    try {
        write_curves(cs, dir.file("o.ply"));
        ADD_FAILURE() << "no error";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("int64 attribute 'id'"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

// --- .hair -------------------------------------------------------------------------------------------

TEST(CurveIoHair, RoundTripKeepsPointsWidthColourAndOpacity)
{
    TempDir dir;
    CurveSet src = sample_curves();
    auto op = src.add<float>(Domain::Point, "opacity");
    // opacity = 1 - transparency is exact both ways for opacities in [0.5, 1] (Sterbenz).
    for (size_t i = 0; i < op.size(); ++i) op[i] = 0.5f + 0.5f / (1.0f + i);
    write_curves(src, dir.file("a.hair"));
    const CurveSet back = read_curves(dir.file("a.hair"));
    expect_points_bit_exact(src, back);
    for (const char* name : {"width", "opacity"}) {
        std::span<const float> a = src.find<float>(Domain::Point, name), b = back.find<float>(Domain::Point, name);
        ASSERT_EQ(a.size(), b.size()) << name;
        for (size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(same_bits(a[i], b[i])) << name << " " << i;
    }
    std::span<const float3> ca = src.find<float3>(Domain::Point, "Cd"), cb = back.find<float3>(Domain::Point, "Cd");
    ASSERT_EQ(ca.size(), cb.size());
    for (size_t i = 0; i < ca.size(); ++i) EXPECT_EQ(ca[i], cb[i]);
    EXPECT_EQ(back.attributes(Domain::Curve).count(), 0u);  // .hair has no curve attributes
}

TEST(CurveIoHair, ReadsDefaultSegmentsAndThickness)
{
    // Two strands of 2 segments each from the header defaults (no segments or thickness arrays).
    TempDir dir;
    std::string d = "HAIR";
    auto u32 = [&](uint32_t v) { d.append(reinterpret_cast<const char*>(&v), 4); };
    auto f32 = [&](float v) { d.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2), u32(6), u32(2), u32(2), f32(0.25f), f32(0), f32(1), f32(1), f32(1);
    d.resize(128, '\0');
    for (int i = 0; i < 6; ++i) f32(float(i)), f32(0), f32(0);
    write_text(dir.file("d.hair"), d);
    const CurveSet cs = read_curves(dir.file("d.hair"));
    ASSERT_EQ(cs.num_curves(), 2u);
    EXPECT_EQ(cs.points_in(1), 3);
    EXPECT_EQ(cs.positions()[5], float3(5, 0, 0));
    auto w = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(w.size(), 6u);
    EXPECT_EQ(w[3], 0.25f);
}

TEST(CurveIoHair, RejectsMalformedInput)
{
    TempDir dir;
    std::string d = "HAIR";
    auto u32 = [&](uint32_t v) { d.append(reinterpret_cast<const char*>(&v), 4); };
    u32(4000000000u), u32(4000000000u), u32(3), u32(0);
    d.resize(128, '\0');
    d += std::string(64, '\0');
    expect_parse_error(dir.file("huge.hair"), d, "header claims 4000000000 strands");
    expect_parse_error(dir.file("short.hair"), std::string("HAIR\1\0\0\0", 8), "truncated: expected a 128-byte .hair header, found 8 bytes");
    expect_parse_error(dir.file("sig.hair"), std::string("HAIX") + std::string(124, '\0'), "expected the 'HAIR' signature");
    std::string counts = "HAIR";
    auto c32 = [&](uint32_t v) { counts.append(reinterpret_cast<const char*>(&v), 4); };
    c32(1), c32(5), c32(3), c32(0);
    counts.resize(128, '\0');
    counts.append("\x02\x00", 2);  // 2 segments = 3 points, but the header says 5
    counts += std::string(60, '\0');
    expect_parse_error(dir.file("count.hair"), counts, "strand segment counts add up to 3 points but the header says 5");
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
