// cull against the exact sphere: push leaves every non-root point at least `clearance` outside;
// trim cuts a diving curve where the distance reaches the clearance; delete drops it; ids stay
// stable; 1 and 2 threads agree.
#include "ops/cull.h"

#include "kernel/error.h"
#include "kernel/parallel.h"

#include <gtest/gtest.h>

#include <cstring>

namespace groom {
namespace {

/// Curve 0 hovers outside the unit sphere; curve 1 starts on it and dives straight through the
/// centre along -x; curve 2 grazes outside.
CurveSet three_curves()
{
    const int64_t counts[3] = {3, 5, 2};
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    const float3 pts[10] = {{0, 1.5f, 0}, {0, 2, 0}, {0, 2.5f, 0}, {1, 0, 0}, {1.5f, 0, 0}, {0.5f, 0, 0}, {0, 0, 0}, {-2, 0, 0},
                            {0, 0, 1.2f}, {0, 0, 2}};
    std::copy(pts, pts + 10, P.begin());
    auto w = c.add<float>(Domain::Curve, "tag");
    w[0] = 10, w[1] = 11, w[2] = 12;
    return c;
}

TEST(Cull, PushLeavesEveryPointOutsideTheClearance)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    CullStats stats;
    const CurveSet dst = cull(three_curves(), sphere, {CullMode::Push, 0.1f}, &stats);
    EXPECT_EQ(stats.curves_affected, 1);
    EXPECT_EQ(stats.points_pushed, 2);  // (0.5,0,0), and the centre (along the sphere's fallback normal)
    for (size_t c = 0; c < dst.num_curves(); ++c) {
        const IndexRange r = dst.points_of(c);
        for (int64_t i = r.begin + 1; i < r.end; ++i) EXPECT_GE(sphere.distance(dst.positions()[i]), 0.1f - 1e-5f) << i;
    }
}

TEST(Cull, TrimCutsAtTheFirstEntry)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    CullStats stats;
    const CurveSet dst = cull(three_curves(), sphere, {CullMode::Trim, 0.2f}, &stats);
    ASSERT_EQ(dst.num_curves(), 3u);
    EXPECT_EQ(stats.curves_trimmed, 1);
    EXPECT_EQ(dst.points_in(1), 3);  // root, (1.5,0,0), the cut
    // The segment (1.5,0,0)->(0.5,0,0) is radial, so distance is linear along it: the cut is exact.
    EXPECT_NEAR(dst.positions()[dst.points_of(1).end - 1].x, 1.2f, 1e-5f);
    EXPECT_EQ(dst.find<float>(Domain::Curve, "tag")[1], 11.0f);
}

TEST(Cull, DeleteDropsOffendersAndKeepsIds)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    CullStats stats;
    const CurveSet dst = cull(three_curves(), sphere, {CullMode::Delete, 0.0f}, &stats);
    ASSERT_EQ(dst.num_curves(), 2u);
    EXPECT_EQ(stats.curves_deleted, 1);
    EXPECT_EQ(dst.curve_ids(), (std::vector<int64_t>{0, 2}));
    EXPECT_EQ(dst.find<float>(Domain::Curve, "tag")[1], 12.0f);
}

TEST(Cull, SameResultForAnyThreadCount)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    std::vector<int64_t> counts(2000, 6);
    CurveSet src = CurveSet::from_counts(counts);
    auto P = src.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = float3(std::sin(float(i)) * 2, std::cos(float(i) * 1.3f) * 2, float(i % 7) * 0.3f - 1);
    for (CullMode mode : {CullMode::Push, CullMode::Trim, CullMode::Delete}) {
        CurveSet a, b;
        {
            ThreadLimit one(1);
            a = cull(src, sphere, {mode, 0.05f});
        }
        {
            ThreadLimit two(2);
            b = cull(src, sphere, {mode, 0.05f});
        }
        ASSERT_EQ(a.num_points(), b.num_points());
        EXPECT_EQ(0, std::memcmp(a.positions().data(), b.positions().data(), a.num_points() * sizeof(float3)));
    }
}

TEST(Cull, RejectsNegativeClearance)
{
    EXPECT_THROW(cull(three_curves(), AnalyticSphere({0, 0, 0}, 1), {CullMode::Push, -0.1f}), InvalidParam);
    // Past 1e15 it reached the scalp queries as "a non-finite point", the option unnamed (a trial).
    try {
        cull(three_curves(), AnalyticSphere({0, 0, 0}, 1), {CullMode::Push, 1e20f});
        ADD_FAILURE() << "clearance 1e20 was accepted";
    } catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`clearance` must be a distance in [0, 1e15] scene units (got 1e+20)"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace groom
