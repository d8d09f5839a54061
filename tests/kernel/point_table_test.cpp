// Point lists in (`x y z` text, NumPy .npy) and number tables out (CSV, .npy): what is accepted,
// the exact errors (file:line for text, the file and what was found for .npy), files larger than
// the parallel chunks, and bytes that do not depend on the thread count.
#include "kernel/io/point_table.h"

#include "kernel/error.h"
#include "kernel/parallel.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>

namespace groom {
namespace {

using test::TempDir;
using test::write_text;

/// The error message of parse_points_text(text, name), or "" when it parses.
std::string text_error(const std::string& text, const std::string& name = "pts.txt")
{
    try {
        parse_points_text(text, name);
    }
    catch (const ParseError& e) {
        return e.what();
    }
    return {};
}

/// A .npy file: magic, version, header dict padded to 64 bytes, then `data`.
std::string npy(const std::string& dict, const std::string& data, int major = 1)
{
    std::string head = dict;
    const size_t prefix = major == 1 ? 10 : 12;
    head.append((64 - (prefix + head.size() + 1) % 64) % 64, ' ');
    head += '\n';
    std::string out("\x93NUMPY", 6);
    out += char(major);
    out += char(0);
    const uint32_t len = uint32_t(head.size());
    out.append(reinterpret_cast<const char*>(&len), major == 1 ? 2 : 4);
    return out + head + data;
}

template <class T> std::string raw(std::initializer_list<T> values)
{
    std::string s(values.size() * sizeof(T), '\0');
    std::memcpy(s.data(), std::data(values), s.size());
    return s;
}

std::string npy_error(const std::string& bytes, const std::string& name = "pts.npy")
{
    try {
        parse_points_npy(bytes, name);
    }
    catch (const ParseError& e) {
        return e.what();
    }
    return {};
}

TEST(PointTable, TextTakesCommasTabsCommentsAndCrlf)
{
    const auto p = parse_points_text("# header\n1 2 3\n\n  4,5,6\r\n\t7\t8\t9  \n   # indented comment\n+1e2 -0.5 .25", "t");
    ASSERT_EQ(p.size(), 4u);
    EXPECT_EQ(p[0], float3(1, 2, 3));
    EXPECT_EQ(p[1], float3(4, 5, 6));
    EXPECT_EQ(p[2], float3(7, 8, 9));
    EXPECT_EQ(p[3], float3(100, -0.5f, 0.25f));
    EXPECT_TRUE(parse_points_text("", "t").empty());
    EXPECT_TRUE(parse_points_text("# nothing\n\n", "t").empty());
}

TEST(PointTable, TextErrorsNameFileLineAndTheLine)
{
    EXPECT_EQ(text_error("1 2 3\n1 2\n"), "pts.txt:2: expected three finite numbers 'x y z', got '1 2'");
    EXPECT_EQ(text_error("1 2 3\n\n1,2,3,4\n"), "pts.txt:3: expected three finite numbers 'x y z', got '1 2 3 4'");
    EXPECT_EQ(text_error("1 nan 3\n"), "pts.txt:1: expected three finite numbers 'x y z', got '1 nan 3'");
    EXPECT_EQ(text_error("1 2 1e39\n"), "pts.txt:1: expected three finite numbers 'x y z', got '1 2 1e39'");
    EXPECT_EQ(text_error("1.5.3 2 3\n"), "pts.txt:1: expected three finite numbers 'x y z', got '1.5.3 2 3'");
    EXPECT_EQ(text_error("1 2 3 # trailing comment\n"), "pts.txt:1: expected three finite numbers 'x y z', got '1 2 3 # trailing comment'");
    EXPECT_EQ(text_error("x y z\r\n"), "pts.txt:1: expected three finite numbers 'x y z', got 'x y z '");
}

TEST(PointTable, BigTextParsesAcrossChunksAndReportsTheFirstBadLine)
{
    // 200,000 lines (about 5 MiB: several 1 MiB chunks, each parsed on its own).
    std::string text;
    const int n = 200000;
    for (int i = 0; i < n; ++i) text += std::to_string(i) + " -" + std::to_string(i) + ".5 0.125\n";
    ThreadLimit two(2);
    const auto p = parse_points_text(text, "big.txt");
    ASSERT_EQ(p.size(), size_t(n));
    for (int i = 0; i < n; i += 997) ASSERT_EQ(p[i], float3(float(i), -float(i) - 0.5f, 0.125f)) << i;
    // Two bad lines in different chunks: the first one is reported, with its line number.
    std::string bad = text;
    const size_t at1 = bad.find("\n150000 ") + 1, at2 = bad.find("\n30000 ") + 1;
    bad.replace(at1, 6, "15000x");
    bad.replace(at2, 5, "3000y");
    EXPECT_EQ(text_error(bad, "big.txt"), "big.txt:30001: expected three finite numbers 'x y z', got '3000y -30000.5 0.125'");
    EXPECT_EQ(text_error(text + "1 2\n", "big.txt"), "big.txt:200001: expected three finite numbers 'x y z', got '1 2'");
}

TEST(PointTable, NpyFloat32AndFloat64InAnyVersion)
{
    const auto f4 = parse_points_npy(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", raw<float>({1, 2, 3, 4, 5, 6.5f})), "a");
    ASSERT_EQ(f4.size(), 2u);
    EXPECT_EQ(f4[1], float3(4, 5, 6.5f));
    const auto f8 = parse_points_npy(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 3), }", raw<double>({0.1, -2, 1e-3}), 2), "a");
    ASSERT_EQ(f8.size(), 1u);
    EXPECT_EQ(f8[0], float3(0.1f, -2.0f, 1e-3f));  // rounded to nearest float
    EXPECT_TRUE(parse_points_npy(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (0, 3), }", ""), "a").empty());
    EXPECT_EQ(parse_points_npy(npy("{\"descr\": \"<f4\", \"shape\": (1,3), \"fortran_order\": False}", raw<float>({7, 8, 9}), 3), "a")[0],
              float3(7, 8, 9));
}

TEST(PointTable, NpyRefusesNamingTheFileAndWhatWasFound)
{
    const std::string f4x2 = raw<float>({1, 2, 3, 4, 5, 6});
    const std::string head = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }";
    auto has = [](const std::string& msg, const std::string& part) { return msg.find(part) != std::string::npos; };
    std::string e = npy_error(npy("{'descr': '>f4', 'fortran_order': False, 'shape': (2, 3), }", f4x2));
    EXPECT_TRUE(has(e, "pts.npy: dtype '>f4' is big-endian; expected little-endian float32 '<f4' or float64 '<f8'")) << e;
    e = npy_error(npy("{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3), }", f4x2));
    EXPECT_TRUE(has(e, "pts.npy: dtype '<i4'; expected float32 '<f4' or float64 '<f8'")) << e;
    e = npy_error(npy("{'descr': [('x', '<f4')], 'fortran_order': False, 'shape': (2, 3), }", f4x2));
    EXPECT_TRUE(has(e, "pts.npy: dtype [('x', '<f4')]; expected")) << e;
    e = npy_error(npy("{'descr': '<f4', 'fortran_order': True, 'shape': (2, 3), }", f4x2));
    EXPECT_TRUE(has(e, "pts.npy: Fortran (column-major) order; expected C order")) << e;
    e = npy_error(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (6,), }", f4x2));
    EXPECT_TRUE(has(e, "pts.npy: shape (6,); expected (N, 3)")) << e;
    e = npy_error(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (3, 2), }", f4x2));
    EXPECT_TRUE(has(e, "pts.npy: shape (3, 2); expected (N, 3)")) << e;
    e = npy_error(npy(head, f4x2.substr(0, 20)));
    EXPECT_TRUE(has(e, "pts.npy: shape (2, 3) of '<f4' needs more than 20 bytes of data, the file has 20 (cut short)")) << e;
    e = npy_error(npy(head, f4x2 + "xxxx"));
    EXPECT_TRUE(has(e, "pts.npy: shape (2, 3) of '<f4' needs 24 bytes of data, the file has 28 (trailing bytes)")) << e;
    e = npy_error(npy("{'descr': '<f4', 'fortran_order': False, 'shape': (99999999999999, 3), }", f4x2));
    EXPECT_TRUE(has(e, "needs more than 24 bytes")) << e;
    e = npy_error("PK\x03\x04 a zip file, not an array");
    EXPECT_TRUE(has(e, "pts.npy: not a NumPy .npy file")) << e;
    e = npy_error(npy(head, raw<float>({1, 2, 3, 4, NAN, 6})));
    EXPECT_TRUE(has(e, "pts.npy: row 1 (counting from 0): expected three finite numbers, found (4, nan, 6)")) << e;
    e = npy_error(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 3), }", raw<double>({1, 1e300, 0})));
    EXPECT_TRUE(has(e, "row 0 (counting from 0): expected three finite numbers within float32's range, found (1, inf, 0)")) << e;
    std::string v9 = npy(head, f4x2);
    v9[6] = 9;
    EXPECT_TRUE(has(npy_error(v9), "pts.npy: .npy format version 9.0")) << npy_error(v9);
}

TEST(PointTable, ReadPointsPicksTheReaderByExtensionAndNamesTheFile)
{
    TempDir dir;
    write_text(dir.file("p.xyz"), "1 2 3\n");  // .xyz: text, as CloudCompare and MeshLab write it
    EXPECT_EQ(read_points(dir.file("p.xyz"))[0], float3(1, 2, 3));
    write_text(dir.file("p.NPY"), npy("{'descr': '<f4', 'fortran_order': False, 'shape': (1, 3), }", raw<float>({4, 5, 6})));
    EXPECT_EQ(read_points(dir.file("p.NPY"))[0], float3(4, 5, 6));
    write_text(dir.file("bad.npy"), "1 2 3\n");
    try {
        read_points(dir.file("bad.npy"));
        FAIL();
    }
    catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find(dir.file("bad.npy") + ": not a NumPy .npy file"), std::string::npos) << e.what();
    }
    EXPECT_THROW(read_points(dir.file("missing.txt")), IoError);
}

TEST(PointTable, CsvIsShortestRoundTripTextTheSameForAnyThreadCount)
{
    std::ostringstream small;
    const float v[] = {0.1f, -2.0f, 1e-30f, 3.4028235e38f, -0.0f, 1.17549435e-38f};
    write_csv_table(small, "a,b,c", v, 3);
    EXPECT_EQ(small.str(), "a,b,c\n0.1,-2,1e-30\n3.4028235e+38,-0,1.1754944e-38\n");
    EXPECT_THROW(write_csv_table(small, "a", v, 4), InvalidParam);

    // 300,000 rows: several chunks and batches; every value parses back to the same float.
    std::vector<float> big(300000 * 4);
    for (size_t i = 0; i < big.size(); ++i) big[i] = std::ldexp(float(i % 1000) * 1.37f - 400.0f, int(i % 50) - 25);
    std::string texts[2];
    for (int t = 1; t <= 2; ++t) {
        ThreadLimit limit(t);
        std::ostringstream s;
        write_csv_table(s, "h", big, 4);
        texts[t - 1] = s.str();
    }
    EXPECT_EQ(texts[0], texts[1]);
    std::istringstream in(texts[0]);
    std::string line;
    std::getline(in, line);
    size_t i = 0;
    for (; std::getline(in, line); ++i) {
        for (char& c : line)
            if (c == ',') c = ' ';
        std::istringstream row(line);
        for (int k = 0; k < 4; ++k) {
            double d;
            row >> d;
            ASSERT_EQ(float(d), big[i * 4 + size_t(k)]) << line;
        }
    }
    EXPECT_EQ(i, 300000u);
}

TEST(PointTable, NpyOutReadsBackBitwise)
{
    std::vector<float> values(3 * 1000);
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(i) * 0.37f - 100.0f;
    std::ostringstream s;
    write_npy_table(s, values, 3);
    const std::string bytes = s.str();
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
    const size_t header = size_t(uint8_t(bytes[8])) | size_t(uint8_t(bytes[9])) << 8;
    EXPECT_EQ((10 + header) % 64, 0u);  // the data starts aligned, as numpy writes it
    const auto p = parse_points_npy(bytes, "t.npy");
    ASSERT_EQ(p.size(), 1000u);
    for (size_t i = 0; i < p.size(); ++i) ASSERT_EQ(p[i], float3(values[3 * i], values[3 * i + 1], values[3 * i + 2]));
}

}  // namespace
}  // namespace groom
