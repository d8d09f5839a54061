// Regressions found by the op fuzz harness (fuzz/ops_fuzz.cpp, scripts/fuzz.sh op_<command>): each
// test rebuilds the fuzzer's input from a small construction and checks the op's clean answer.
#include "kernel/error.h"
#include "ops/braid.h"
#include "ops/braid_weave.h"
#include "ops/curl.h"
#include "ops/hair_widths.h"
#include "ops/render.h"
#include "kernel/memory_budget.h"

#include <gtest/gtest.h>

namespace groom {
namespace {

// op_braid: `--strands 198` (documented ">= 2", no upper bound) ran for minutes: the weave's crossings
// and closest approach cost about N^3 (80 strands 8 s, 198 about two minutes, for one guide). The
// range is closed at kMaxStrands for every pattern, before any work.
TEST(OpFuzz, BraidStrandsPastTheCapAreRefusedBeforeWeaving)
{
    BraidParams p;
    p.strands = 198;
    EXPECT_THROW(p.validate(), InvalidParam);
    EXPECT_THROW(BraidWeave(BraidPattern::Plait, 198, BraidHand::Over), InvalidParam);
    p.strands = kMaxStrands + 1;
    EXPECT_THROW(p.validate(), InvalidParam);
    p.strands = kMaxStrands;
    EXPECT_NO_THROW(p.validate());
    p.pattern = BraidPattern::Round;  // even, >= 4: 32 suits it
    EXPECT_NO_THROW(p.validate());
}

// op_curl: one guide point at y = 16777216 (a 1.7e7-unit curve) with the default curl asked for
// about 5e8 output points, allocated without an estimate (killed past 2 GB). Now LimitExceeded
// naming `frequency` and `samples` before allocating, under a 64 MiB budget.
TEST(OpFuzz, CurlOfAVeryLongCurveIsRefusedBeforeAllocating)
{
    const int64_t counts[] = {3};
    CurveSet guide = CurveSet::from_counts(counts);
    auto P = guide.positions_for_write();
    P[0] = {6.6f, 7.7f, 4.1f};
    P[1] = {0.0f, 16777216.0f, 10.3f};
    P[2] = {4.9f, -0.4f, -11.3f};
    const MemoryLimit limit(64ull << 20);
    try {
        curl(guide, CurlParams{});
        FAIL() << "a 1.7e7-unit curve was curled";
    }
    catch (const LimitExceeded& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("`frequency`"), std::string::npos) << m;
        EXPECT_NE(m.find("`samples`"), std::string::npos) << m;
    }
    // The same curve 1e4 times shorter fits: 16 samples a cycle at the type's frequency.
    for (float3& p : P) p = p * 1e-4f;
    const CurveSet out = curl(guide, CurlParams{});
    EXPECT_EQ(out.num_curves(), 1u);
    EXPECT_GT(out.num_points(), 3u);
}

// op_braid (found while writing the op seeds): `--taper 1,0,0` (each value >= 0, as documented) gave
// negative strand widths (-0.0006 on a 5-unit guide), refused only when the output was written
// ("point 97 has width -0.000584"): the taper's spline overshoots below 0 between its values.
TEST(OpFuzz, BraidTaperThatDipsBelowZeroBetweenItsValuesGivesNoNegativeWidth)
{
    const int64_t counts[] = {5};
    CurveSet guide = CurveSet::from_counts(counts);
    auto P = guide.positions_for_write();
    for (int i = 0; i < 5; ++i) P[i] = {0.0f, 10.0f - float(i), float(i)};
    BraidParams p;
    p.taper = {1.0f, 0.0f, 0.0f};
    const BraidResult b = braid(guide, p);
    const auto w = b.curves.find<float>(Domain::Point, "width");
    ASSERT_FALSE(w.empty());
    for (size_t i = 0; i < w.size(); ++i) ASSERT_GE(w[i], 0.0f) << "point " << i;
    EXPECT_NO_THROW(b.curves.validate("braid"));
}

// op_populate (found while writing the op seeds): `--radius 0` around a guide of width 1e30 puts
// fibers 1e30 apart, whose segments measured in float are inf, so the taper's arc-length fractions
// were inf / inf and the widths NaN (refused when written). Lengths are measured in double.
TEST(OpFuzz, TaperOfACurveWhoseSegmentsOverflowFloatIsFinite)
{
    const int64_t counts[] = {3};
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    P[0] = {-1e30f, 0.0f, 0.0f};
    P[1] = {1e30f, 0.0f, 0.0f};
    P[2] = {3e30f, 0.0f, 0.0f};
    taper_widths(c, 0.008f, 0.004f);
    const auto w = c.find<float>(Domain::Point, "width");
    ASSERT_EQ(w.size(), 3u);
    EXPECT_EQ(w[0], 0.008f);
    EXPECT_FLOAT_EQ(w[1], 0.006f);
    EXPECT_EQ(w[2], 0.004f);
}

// op_curl (found while writing the op seeds): `--root-ease 1e30` puts every point's cycle coordinate
// near -1e30, and its cycle index was converted to int64 before clamping (undefined; UBSan stops
// there). The index is clamped first: an ease longer than the curve leaves the curve uncurled, each
// point in cycle 0.
TEST(OpFuzz, CurlWithAHugeRootEaseClampsItsCycleIndexBeforeConverting)
{
    const int64_t counts[] = {3};
    CurveSet guide = CurveSet::from_counts(counts);
    auto P = guide.positions_for_write();
    P[0] = {0.0f, 0.0f, 0.0f};
    P[1] = {0.0f, 1.0f, 0.0f};
    P[2] = {0.0f, 2.0f, 0.0f};
    CurlParams p;
    p.root_ease = 1e30f;
    const CurveSet out = curl(guide, p);
    ASSERT_EQ(out.num_curves(), 1u);
    for (const float3& q : out.positions()) {
        EXPECT_EQ(q.x, 0.0f);
        EXPECT_EQ(q.z, 0.0f);
    }
    for (const int32_t c : out.find<int32_t>(Domain::Point, "cycle")) EXPECT_EQ(c, 0);
}

// op_render (found while writing the op seeds): a point of width 1e30 made a segment's box reach
// -8e28 pixels, converted to int for its first tile (undefined; UBSan stops there). The box is
// clamped to the image before converting: the curve paints, the picture is whole.
TEST(OpFuzz, RenderOfAHugeWidthClampsItsTilesBeforeConverting)
{
    const int64_t counts[] = {4};
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    P[0] = {-1.0f, 0.0f, 0.0f};
    P[1] = {-0.5f, 0.1f, 0.0f};
    P[2] = {0.5f, 0.2f, 0.0f};
    P[3] = {1.0f, 0.3f, 0.0f};
    auto w = c.add<float>(Domain::Point, "width");
    for (float& x : w) x = 0.01f;
    w[1] = 1e30f;
    RenderScene scene;
    scene.curves = {&c};
    RenderParams p;
    p.width = p.height = 64;
    p.supersample = 1;
    const RgbImage im = render(scene, Camera{}, p);
    ASSERT_EQ(im.width, 64);
    ASSERT_EQ(im.height, 64);
    // The huge round cap covers the whole picture: no pixel is left the background's grey.
    int background = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) background += im.at(x, y)[0] == static_cast<uint8_t>(p.background.x * 255.0f + 0.5f);
    EXPECT_EQ(background, 0);
}

}  // namespace
}  // namespace groom
