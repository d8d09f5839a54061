// surface_path against the closed form: on a sphere the path is the great circle arc.
#include "fields/surface_path.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace groom;

namespace {

const float3 kC{1.0f, -2.0f, 0.5f};
constexpr float kR = 7.0f;

}  // namespace

TEST(SurfacePath, FollowsTheGreatCircleOnASphere)
{
    const AnalyticSphere sphere(kC, kR);
    const float3 a = kC + normalize(float3(1, 0.3f, 0.2f)) * kR, b = kC + normalize(float3(-0.4f, 0.8f, -0.6f)) * kR;
    const float step = 0.2f;
    std::vector<float3> path;
    ASSERT_TRUE(surface_path(sphere, a, b, step, 0.0f, path));
    // The great circle lies in the plane through the centre, a and b.
    const float3 plane = normalize(cross(a - kC, b - kC));
    double length = 0.0;
    for (size_t i = 0; i < path.size(); ++i) {
        EXPECT_NEAR(distance(path[i], kC), kR, 1e-4f * kR) << i;  // on the surface
        EXPECT_NEAR(dot(path[i] - kC, plane), 0.0f, 1e-3f * kR) << i;  // on the great circle
        if (i > 0) {
            const float s = distance(path[i], path[i - 1]);
            EXPECT_LE(s, step * 1.0001f) << i;
            if (i + 1 < path.size()) EXPECT_NEAR(s, step, 1e-3f * step) << i;
            length += s;
        }
    }
    EXPECT_LT(distance(path.front(), a), 1e-4f * kR);
    EXPECT_LT(distance(path.back(), b), 1e-4f * kR);
    // Arc length R * angle; the chords of a polyline with step 0.2 on R = 7 fall short by < 0.01%.
    const double angle = std::acos(std::clamp(double(dot(normalize(a - kC), normalize(b - kC))), -1.0, 1.0));
    EXPECT_NEAR(length, kR * angle, 1e-3 * kR * angle);
}

TEST(SurfacePath, LiftsAlongTheNormalAndPassesThroughWaypoints)
{
    const AnalyticSphere sphere(kC, kR);
    const std::vector<float3> way{kC + float3(0, 0, 2 * kR), kC + float3(0, 2 * kR, 0), kC + float3(0, 0, -2 * kR)};
    std::vector<float3> path;
    ASSERT_TRUE(surface_path_through(sphere, way, 0.3f, 0.05f, path));
    for (const float3& p : path) {
        EXPECT_NEAR(distance(p, kC), kR + 0.05f, 1e-4f * kR);
        EXPECT_NEAR(p.x, kC.x, 1e-3f);  // the x = const great circle through all three
    }
    // The middle waypoint (projected and lifted) is one of the points; no point repeats at the joint.
    int at_top = 0;
    for (const float3& p : path) at_top += distance(p, kC + float3(0, kR + 0.05f, 0)) < 1e-3f;
    EXPECT_EQ(at_top, 1);
    EXPECT_NEAR(distance(path.front(), kC + float3(0, 0, kR + 0.05f)), 0.0f, 1e-3f);
    EXPECT_NEAR(distance(path.back(), kC + float3(0, 0, -kR - 0.05f)), 0.0f, 1e-3f);
}

TEST(SurfacePath, OneLongStepAndAStallAtAGap)
{
    // A step longer than the whole path ends at the target at once.
    const AnalyticPlane plane({0, 0, 0}, {0, 1, 0});
    std::vector<float3> path;
    ASSERT_TRUE(surface_path(plane, {0, 1, 0}, {10, -1, 0}, 100.0f, 0.0f, path));
    ASSERT_EQ(path.size(), 2u);
    EXPECT_EQ(path.back(), float3(10, 0, 0));
    // Two pieces of a plane with a gap between x = 1 and x = 2: the walk stalls at the gap's edge.
    struct Gap final : Surface {
        float3 closest_point(const float3& p) const override
        {
            const float x = p.x > 1.0f && p.x < 2.0f ? (p.x < 1.5f ? 1.0f : 2.0f) : p.x;
            return {x, 0, p.z};
        }
        float distance(const float3& p) const override { return groom::distance(p, closest_point(p)) * (p.y < 0 ? -1.0f : 1.0f); }
        float3 normal(const float3&) const override { return {0, 1, 0}; }
    } point;
    // 1.0 + 0.4 projects back to 1.0: stalled, the walk finishes along the chord, on the surface.
    EXPECT_TRUE(surface_path(point, {0, 0, 0}, {5, 0, 0}, 0.4f, 0.0f, path));
    EXPECT_EQ(path.back(), float3(5, 0, 0));
    for (const float3& p : path) EXPECT_EQ(point.closest_point(p), p);
    int at_edge = 0;
    for (const float3& p : path) at_edge += p.x == 1.0f;
    EXPECT_GE(at_edge, 8);  // it did stall there first
}
