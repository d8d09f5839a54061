// The Cem Yuksel .hair curve format (kernel/io/hair.cpp): round trips of points, width, colour and
// opacity, header defaults and malformed input checked for the error text.
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/formats.h"
#include "test_support.h"
#include "tests/kernel/curve_samples.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <vector>

using namespace groom;
using groom::test::TempDir;
using groom::test::expect_parse_error;
using groom::test::expect_points_bit_exact;
using groom::test::same_bits;
using groom::test::sample_curves;
using groom::test::write_text;

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

// Written straight to the file a block at a time: the same bytes as the in-memory encoder, and a
// curve .hair cannot hold (over 65,536 points) refused before anything lands, old file untouched.
TEST(CurveIoHair, StreamedFileEqualsTheEncodedBytesAndRefusalsLeaveNothing)
{
    TempDir dir;
    const CurveSet src = sample_curves();
    write_curves(src, dir.file("a.hair"));
    EXPECT_EQ(groom::test::read_bytes(dir.file("a.hair")), io::write_hair(src));

    CurveSet big = CurveSet::from_counts(std::vector<int64_t>{3, 70000});
    auto P = big.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(float(i), 0.0f, 0.0f);
    write_text(dir.file("old.hair"), "previous");
    try {
        write_curves(big, dir.file("old.hair"));
        FAIL() << "a 70,000-point curve was written to .hair";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("curve 1 has 70000 points"), std::string::npos) << e.what();
    }
    EXPECT_EQ(groom::test::read_bytes(dir.file("old.hair")), "previous");
    try {
        write_curves(big, dir.file("new.hair"));
    }
    catch (const InvalidParam&) {
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("new.hair")));
    size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 2u) << "a temporary was left behind";
}

namespace {

/// Curves [c0, c1) of `src` with their point columns (P, width, opacity, Cd): a block as an op
/// writing its output a block at a time hands it over.
CurveSet block_of(const CurveSet& src, size_t c0, size_t c1)
{
    std::vector<int64_t> counts;
    for (size_t c = c0; c < c1; ++c) counts.push_back(src.points_in(c));
    CurveSet b = CurveSet::from_counts(counts);
    const int64_t first = c0 < src.num_curves() ? src.points_of(c0).begin : int64_t(src.num_points());
    const auto copy = [&](auto from, auto to) {
        for (size_t i = 0; i < to.size(); ++i) to[i] = from[size_t(first) + i];
    };
    copy(src.positions(), b.positions_for_write());
    copy(src.find<float>(Domain::Point, attr::width), b.add<float>(Domain::Point, attr::width));
    copy(src.find<float>(Domain::Point, "opacity"), b.add<float>(Domain::Point, "opacity"));
    copy(src.find<float3>(Domain::Point, "Cd"), b.add<float3>(Domain::Point, "Cd"));
    return b;
}

}  // namespace

// An output written a block of strands at a time (groom curl into .hair) is the file the whole set
// makes, byte for byte, however it is cut; blocks that do not match what was announced are refused
// and an unfinished output never lands.
TEST(CurveIoHair, BlocksWrittenOneAfterAnotherMakeTheWholeFile)
{
    TempDir dir;
    CurveSet src = sample_curves();
    auto op = src.add<float>(Domain::Point, "opacity");
    for (size_t i = 0; i < op.size(); ++i) op[i] = 0.5f + 0.5f / (1.0f + i);
    std::vector<int64_t> counts;
    for (size_t c = 0; c < src.num_curves(); ++c) counts.push_back(src.points_in(c));
    const std::string whole = io::write_hair(src);
    std::ostringstream after("prefix", std::ios::ate);  // a stream that already holds bytes: the file follows them
    io::write_hair(src, after);
    EXPECT_EQ(after.str(), "prefix" + whole);
    for (const std::vector<size_t>& cuts : {std::vector<size_t>{0, 4}, {0, 1, 3, 4}, {0, 1, 2, 3, 4}, {0, 0, 2, 2, 4}}) {
        OutputBatch batch;
        CurveBlockWriter writer(dir.file("b.hair"), batch, counts);
        for (size_t k = 0; k + 1 < cuts.size(); ++k) writer.write(block_of(src, cuts[k], cuts[k + 1]));
        writer.finish();
        batch.commit();
        EXPECT_EQ(groom::test::read_bytes(dir.file("b.hair")), whole) << "blocks cut at " << cuts.size() - 2 << " places";
    }

    OutputBatch batch;
    CurveBlockWriter writer(dir.file("c.hair"), batch, counts);
    writer.write(block_of(src, 0, 1));
    CurveSet wrong = block_of(src, 2, 3);  // strand 1 announced with 5 points, this one has 2
    EXPECT_THROW(writer.write(wrong), InvalidParam);
    CurveSet bare = CurveSet::from_counts(std::vector<int64_t>{5});  // the right count, no width/opacity/Cd
    EXPECT_THROW(writer.write(bare), InvalidParam);
    EXPECT_THROW(writer.finish(), InvalidParam);  // 1 of 4 strands written
    EXPECT_THROW(CurveBlockWriter(dir.file("d.usda"), batch, counts), InvalidParam);
    EXPECT_FALSE(writes_curve_blocks(dir.file("d.usda")));
    EXPECT_TRUE(writes_curve_blocks(dir.file("d.hair")));
}

// A file on disk is read a stretch at a time straight into the curves: the same curves as the
// bytes read whole, across stretch boundaries (2^18 records a read), and a bad point past the first
// stretch is named with its own byte offset.
TEST(CurveIoHair, FileReadInStretchesEqualsTheWholeBytes)
{
    TempDir dir;
    const std::vector<int64_t> counts(3000, 100);  // 300,000 points: two stretches of points
    CurveSet src = CurveSet::from_counts(counts);
    auto P = src.positions_for_write();
    auto W = src.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(float(i), std::sqrt(float(i)), -1.0f / float(i + 1)), W[i] = 1e-3f * float(i % 7);
    write_curves(src, dir.file("big.hair"));
    const CurveSet from_file = read_curves(dir.file("big.hair"));
    io::FileBytes bytes{dir.file("big.hair"), groom::test::read_bytes(dir.file("big.hair"))};
    const CurveSet from_bytes = io::read_hair(bytes);
    expect_points_bit_exact(src, from_file);
    expect_points_bit_exact(from_bytes, from_file);
    const auto wf = from_file.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(wf.size(), W.size());
    for (size_t i = 0; i < W.size(); ++i) ASSERT_TRUE(same_bits(wf[i], W[i])) << i;

    const size_t bad = 262200, at = 128 + 2 * counts.size() + 12 * bad;
    std::string d = bytes.data;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(d.data() + at + 4, &nan, 4);
    expect_parse_error(dir.file("nan.hair"), d, "byte " + std::to_string(at) + ": point 262200 is not finite");
}
