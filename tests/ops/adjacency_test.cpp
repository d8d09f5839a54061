// Tests for ops/adjacency: the neighbour searches partition uses, against closed forms on an exact
// sphere and plane, and against brute-force searches on random inputs.
#include "ops/adjacency.h"

#include "fields/surface.h"
#include "kernel/rng.h"
#include "tests/ops/guide_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace groom;
using namespace groom::test;

namespace {

constexpr float kPi = 3.14159265358979f;

}  // namespace

TEST(Adjacency, ThreeMeridianArcsHaveTheirNeighboursOnTheRightSides)
{
    const std::vector<Arc> arcs = {{-0.3f, -0.5f, 0.5f}, {0.0f, -0.5f, 0.5f}, {0.3f, -0.5f, 0.5f}};
    const auto adj = find_adjacent_guides(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f));
    ASSERT_EQ(adj.size(), 3u);
    // Longitude grows to the left (normal x tangent = +Z at lat 0, lon 0).
    EXPECT_EQ(adj[0].left, 1);
    EXPECT_EQ(adj[0].right, -1);
    EXPECT_EQ(adj[1].left, 2);
    EXPECT_EQ(adj[1].right, 0);
    EXPECT_EQ(adj[2].left, -1);
    EXPECT_EQ(adj[2].right, 1);
}

TEST(Adjacency, MeridiansAllRoundTheSphereNeverPickTheFarSide)
{
    // 12 meridians 30 degrees apart, given out of order: each has both neighbours, never a guide
    // across the head (which is nearer in 3-D than some neighbours' far ends but points inwards).
    std::vector<Arc> arcs;
    const int order[12] = {5, 0, 7, 2, 9, 11, 1, 3, 6, 8, 10, 4};
    for (int k : order) arcs.push_back({2 * kPi * k / 12, -0.7f, 0.7f});
    const auto adj = find_adjacent_guides(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f));
    auto index_of = [&](int k) { return int(std::find(order, order + 12, (k + 12) % 12) - order); };
    for (int c = 0; c < 12; ++c) {
        EXPECT_EQ(adj[c].left, index_of(order[c] + 1)) << "guide " << c;
        EXPECT_EQ(adj[c].right, index_of(order[c] - 1)) << "guide " << c;
    }
}

TEST(Adjacency, MaxGapLeavesDistantGuidesOut)
{
    const CurveSet guides = straight_guides({0.0f, 1.0f, 3.0f});
    const AnalyticPlane plane({0, 0, 0}, {0, 1, 0});
    auto adj = find_adjacent_guides(guides, plane);
    EXPECT_EQ(adj[1].left, 2);
    EXPECT_EQ(adj[1].right, 0);
    adj = find_adjacent_guides(guides, plane, 1.5f);  // guide 2 is 2 units from guide 1
    EXPECT_EQ(adj[1].left, -1);
    EXPECT_EQ(adj[1].right, 0);
    EXPECT_EQ(adj[2].right, -1);
}

TEST(Adjacency, AutomaticGapIgnoresAGuideFarOffTheLayout)
{
    // Gaps 1, 1, 1, 10: the typical gap is 1, so the search reaches 4 and guide 3 is nobody's neighbour.
    const CurveSet guides = straight_guides({0.0f, 1.0f, 2.0f, 12.0f});
    const AnalyticPlane plane({0, 0, 0}, {0, 1, 0});
    EXPECT_FLOAT_EQ(typical_guide_gap(guides, GuidePointIndex(guides)), 1.0f);
    auto adj = find_adjacent_guides(guides, plane);
    EXPECT_EQ(adj[2].left, -1);
    EXPECT_EQ(adj[2].right, 1);
    EXPECT_EQ(adj[3].left, -1);
    EXPECT_EQ(adj[3].right, -1);
    adj = find_adjacent_guides(guides, plane, 20.0f);  // an explicit gap reaches it
    EXPECT_EQ(adj[2].left, 3);
    EXPECT_EQ(adj[3].right, 2);
}

TEST(Adjacency, AGuideCrossingNearTheTipIsNotANeighbour)
{
    // Guide 0 runs along +Z; guide 1 lies beside it on the left (+X); guide 2 is short and crosses
    // guide 0 just before its tip, so it is nearest on the right only at the last few stations.
    std::vector<int64_t> counts = {5, 5, 2};
    CurveSet guides = CurveSet::from_counts(counts);
    auto P = guides.positions_for_write();
    for (int i = 0; i < 5; ++i) {
        P[i] = float3(0, 0.2f, float(i));
        P[5 + i] = float3(1, 0.2f, float(i));
    }
    P[10] = float3(-0.3f, 0.2f, 3.8f);
    P[11] = float3(0.3f, 0.2f, 4.2f);
    const auto adj = find_adjacent_guides(guides, AnalyticPlane({0, 0, 0}, {0, 1, 0}));
    EXPECT_EQ(adj[0].left, 1);
    EXPECT_EQ(adj[0].right, -1);  // guide 2 is nearest there at < kAdjacencyMinVotes stations
}

TEST(Adjacency, ClassifySideUsesTheTangentPlane)
{
    const float3 n(0, 1, 0), left(1, 0, 0);
    EXPECT_EQ(classify_side({1, 0, 0}, n, left), 0);
    EXPECT_EQ(classify_side({-1, 0.2f, 0.3f}, n, left), 1);
    EXPECT_EQ(classify_side({0.1f, 0, 1}, n, left), -1);    // ahead along the guide
    EXPECT_EQ(classify_side({0.3f, -1, 0}, n, left), -1);   // through the head
    EXPECT_EQ(classify_side({0, 0, 0}, n, left), -1);
}

TEST(Adjacency, PolylineClosestPointEqualsBruteForceOnRandomInputs)
{
    for (int trial = 0; trial < 40; ++trial) {
        Rng rng(7, uint64_t(trial));
        const int n = 1 + int(rng.below(60));
        std::vector<float3> pts(n);
        float3 p(0, 0, 0);
        for (int i = 0; i < n; ++i) {
            // Random walk with occasional repeated points (zero-length segments) and long jumps.
            if (i > 0 && rng.below(10) == 0) { pts[i] = pts[i - 1]; continue; }
            const float step = rng.below(8) == 0 ? 3.0f : 0.3f;
            p += float3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) * step;
            pts[i] = p;
        }
        const PolylineNearest index(pts);
        for (int k = 0; k < 200; ++k) {
            const float3 q(rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-6, 6));
            double best = INFINITY;
            for (int s = 0; s + 1 < std::max(n, 2); ++s) {
                const float3 a = pts[s], b = pts[std::min(s + 1, n - 1)];
                const float3 ab = b - a;
                const float len2 = length_squared(ab);
                const float t = len2 > 0 ? std::clamp(dot(q - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
                const float3 x = lerp(a, b, t);
                const double d = distance(q, x);
                best = std::min(best, d);
            }
            const PolylineNearest::Hit hit = index.closest(q);
            ASSERT_NEAR(hit.distance, best, 1e-5 * (1 + best)) << "trial " << trial << " query " << k;
            // Near-ties between segments make the point itself ill-posed; the distance is not. So the
            // point must lie on the polyline at the reported distance from q.
            EXPECT_NEAR(distance(hit.point, q), hit.distance, 1e-5f * (1 + hit.distance));
            const float3 a = pts[hit.segment], b = pts[std::min<int64_t>(hit.segment + 1, n - 1)];
            EXPECT_NEAR3(hit.point, lerp(a, b, hit.t), 1e-5f);
            EXPECT_GE(hit.t, 0.0f);
            EXPECT_LE(hit.t, 1.0f);
        }
    }
}

TEST(Adjacency, NearestOnSidesEqualsBruteForceOnRandomInputs)
{
    Rng rng(11, 0);
    std::vector<int64_t> counts(20);
    for (auto& c : counts) c = 1 + rng.below(30);
    CurveSet guides = CurveSet::from_counts(counts);
    for (float3& p : guides.positions_for_write()) p = float3(rng.uniform(-5, 5), rng.uniform(-1, 1), rng.uniform(-5, 5));
    const GuidePointIndex index(guides);
    const auto P = guides.positions();
    int found = 0;
    for (int k = 0; k < 500; ++k) {
        const float3 q(rng.uniform(-5, 5), rng.uniform(-1, 1), rng.uniform(-5, 5));
        const float3 n = normalize(float3(rng.uniform(-0.3f, 0.3f), 1, rng.uniform(-0.3f, 0.3f)));
        const float3 left = left_direction(n, normalize(float3(rng.uniform(-1, 1), 0, rng.uniform(-1, 1)), {0, 0, 1}));
        const int32_t exclude = int32_t(rng.below(20));
        const float max_gap = k % 2 ? 0.0f : rng.uniform(0.5f, 3.0f);
        GuidePointIndex::SideHit brute[2];
        for (size_t c = 0; c < guides.num_curves(); ++c) {
            if (int32_t(c) == exclude) continue;
            for (int64_t i = guides.points_of(c).begin; i < guides.points_of(c).end; ++i) {
                const int side = classify_side(P[i] - q, n, left);
                const float d = distance(P[i], q);
                if (side < 0 || (max_gap > 0 && d > max_gap)) continue;
                if (d < brute[side].distance) brute[side] = {int32_t(c), i, d};
            }
        }
        const auto hits = index.nearest_on_sides(q, n, left, exclude, max_gap);
        for (int side = 0; side < 2; ++side) {
            ASSERT_EQ(hits[side].point, brute[side].point) << "query " << k << " side " << side;
            EXPECT_EQ(hits[side].guide, brute[side].guide);
            if (brute[side].guide >= 0) {
                EXPECT_NEAR(hits[side].distance, brute[side].distance, 1e-5f);
                ++found;
            }
        }
    }
    EXPECT_GT(found, 500);  // the comparison is not vacuous
}
