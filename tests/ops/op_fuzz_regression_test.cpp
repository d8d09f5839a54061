// Regressions found by the op fuzz harness (fuzz/ops_fuzz.cpp, scripts/fuzz.sh op_<command>): each
// test rebuilds the fuzzer's input from a small construction and checks the op's clean answer.
#include "kernel/error.h"
#include "ops/braid.h"
#include "ops/braid_weave.h"
#include "ops/curl.h"
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

}  // namespace
}  // namespace groom
