// PointIndex on points along a straight line, where the nearest points and their order are known.
#include "fields/point_index.h"

#include <gtest/gtest.h>

#include <vector>

namespace groom {
namespace {

/// Points at x = 0, 1, ..., n - 1 on the x axis.
std::vector<float3> line(int n)
{
    std::vector<float3> pts;
    for (int i = 0; i < n; ++i) pts.push_back(float3(float(i), 0, 0));
    return pts;
}

TEST(PointIndex, NearestOnALineInDistanceOrder)
{
    const PointIndex index(line(10));
    EXPECT_EQ(index.size(), 10u);
    std::vector<PointIndex::Neighbour> hits;
    index.nearest(float3(3.25f, 0, 0), 3, hits);
    ASSERT_EQ(hits.size(), 3u);
    EXPECT_EQ(hits[0].index, 3u);
    EXPECT_EQ(hits[1].index, 4u);
    EXPECT_EQ(hits[2].index, 2u);
    EXPECT_DOUBLE_EQ(hits[0].distance, 0.25);
    EXPECT_DOUBLE_EQ(hits[1].distance, 0.75);
    EXPECT_DOUBLE_EQ(hits[2].distance, 1.25);
    // Off the line: the distance is the hypotenuse.
    index.nearest(float3(7, 0, 0.75f), 1, hits);
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_EQ(hits[0].index, 7u);
    EXPECT_DOUBLE_EQ(hits[0].distance, 0.75);
    // Asking for more than there are gives them all.
    index.nearest(float3(-5, 0, 0), 50, hits);
    ASSERT_EQ(hits.size(), 10u);
    for (uint32_t i = 0; i < 10; ++i) EXPECT_EQ(hits[i].index, i);
}

TEST(PointIndex, EqualDistancesComeInIndexOrder)
{
    // Halfway between 4 and 5, and a duplicate of point 2 appended as point 10.
    std::vector<float3> pts = line(10);
    pts.push_back(float3(2, 0, 0));
    const PointIndex index(pts);
    std::vector<PointIndex::Neighbour> hits;
    index.nearest(float3(4.5f, 0, 0), 2, hits);
    ASSERT_EQ(hits.size(), 2u);
    EXPECT_EQ(hits[0].index, 4u);
    EXPECT_EQ(hits[1].index, 5u);
    EXPECT_EQ(hits[0].distance, hits[1].distance);
    index.nearest(float3(2, 1, 0), 2, hits);
    ASSERT_EQ(hits.size(), 2u);
    EXPECT_EQ(hits[0].index, 2u);
    EXPECT_EQ(hits[1].index, 10u);
}

TEST(PointIndex, WalkVisitsOutwardUntilTold)
{
    const PointIndex index(line(10));
    std::vector<uint32_t> seen;
    std::vector<double> d2;
    index.walk(float3(6.1f, 0, 0), [&](uint32_t i, double dd) {
        seen.push_back(i);
        d2.push_back(dd);
        return seen.size() < 4;
    });
    EXPECT_EQ(seen, (std::vector<uint32_t>{6, 7, 5, 8}));
    for (size_t k = 1; k < d2.size(); ++k) EXPECT_LE(d2[k - 1], d2[k]);
    EXPECT_NEAR(d2[0], 0.01, 1e-6);  // squared, from the float 6.1
    // Without a stop it visits every point once.
    int count = 0;
    index.walk(float3(0, 0, 0), [&](uint32_t, double) {
        ++count;
        return true;
    });
    EXPECT_EQ(count, 10);
}

TEST(PointIndex, EmptyAnswersNothing)
{
    const PointIndex index(std::vector<float3>{});
    std::vector<PointIndex::Neighbour> hits{{1, 1.0}};
    index.nearest(float3(0, 0, 0), 3, hits);
    EXPECT_TRUE(hits.empty());
    bool called = false;
    index.walk(float3(0, 0, 0), [&](uint32_t, double) { return called = true; });
    EXPECT_FALSE(called);
}

}  // namespace
}  // namespace groom
