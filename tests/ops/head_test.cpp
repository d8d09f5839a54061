#include "ops/head.h"

#include "kernel/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace groom;

namespace {
Bounds3 bounds_of(const PolygonSoup& s)
{
    Bounds3 b;
    for (const float3& p : s.points) b.extend(p);
    return b;
}
}  // namespace

TEST(Head, ClosedAndConsistentlyOriented)
{
    HeadParams params;
    params.resolution = 32;
    const PolygonSoup head = make_head(params);
    // Every directed edge once and its reverse once: closed, manifold, consistently wound.
    std::map<std::pair<int32_t, int32_t>, int> directed;
    for (size_t f = 0; f < head.num_faces(); ++f) {
        const auto face = head.face(f);
        for (size_t k = 0; k < face.size(); ++k) ++directed[{face[k], face[(k + 1) % face.size()]}];
    }
    for (const auto& [edge, n] : directed) {
        EXPECT_EQ(n, 1) << edge.first << "->" << edge.second;
        EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "boundary edge " << edge.first << "-" << edge.second;
    }
    // Euler characteristic 2 (a sphere): V - E + F.
    const int64_t V = int64_t(head.points.size()), E = int64_t(directed.size() / 2), F = int64_t(head.num_faces());
    EXPECT_EQ(V - E + F, 2);
    // Outward: positive signed volume (divergence theorem over the fan triangles).
    double volume = 0.0;
    for (size_t f = 0; f < head.num_faces(); ++f) {
        const auto face = head.face(f);
        for (size_t k = 1; k + 1 < face.size(); ++k) {
            const float3 a = head.points[face[0]], b = head.points[face[k]], c = head.points[face[k + 1]];
            volume += dot(a, cross(b, c)) / 6.0;
        }
    }
    // An adult head and a neck stump: a few litres.
    EXPECT_GT(volume, 3000.0);
    EXPECT_LT(volume, 9000.0);
}

TEST(Head, VerticesLieOnTheBlendedSurface)
{
    HeadParams params;
    params.resolution = 24;
    const PolygonSoup head = make_head(params);
    for (const float3& p : head.points) ASSERT_LT(std::fabs(head_distance(p)), 2e-3f) << p.x << "," << p.y << "," << p.z;
}

TEST(Head, CrownMatchesTheCraniumEllipsoid)
{
    // The top pole lies on the ray x = 0, z = -0.5 from the sampling centre; there only the cranium
    // ellipsoid (centre (0, 3, -1), radii (7.4, 9, 9.8)) is present: y = 3 + 9 sqrt(1 - (0.5/9.8)^2).
    const PolygonSoup head = make_head(HeadParams{});
    const double expected = 3.0 + 9.0 * std::sqrt(1.0 - (0.5 / 9.8) * (0.5 / 9.8));
    EXPECT_NEAR(head.points.front().y, expected, 1e-3);
    // The highest point of the ellipsoid, (0, 12, -1), bounds every vertex from above.
    EXPECT_LE(bounds_of(head).hi.y, 12.0f + 1e-3f);
}

TEST(Head, ProportionsOfAnAdultHead)
{
    HeadParams params;
    params.ears = false;
    const PolygonSoup head = make_head(params);
    const Bounds3 b = bounds_of(head);
    // Breadth of the cranium (no ears) ~15 cm, length ~20 cm, flat neck cut at y = -22.
    EXPECT_NEAR(b.hi.x - b.lo.x, 14.8, 0.6);
    EXPECT_GT(b.hi.z - b.lo.z, 19.0);
    EXPECT_LT(b.hi.z - b.lo.z, 23.0);
    EXPECT_NEAR(b.lo.y, -22.0, 1e-2);
    // The nose is the frontmost point, on the mid-line, below the eyes.
    const float3* front = &head.points[0];
    for (const float3& p : head.points)
        if (p.z > front->z) front = &p;
    EXPECT_LT(std::fabs(front->x), 1.0f);
    EXPECT_GT(front->y, -5.5f);
    EXPECT_LT(front->y, -1.0f);
    // Ears widen the head.
    const Bounds3 with_ears = bounds_of(make_head(HeadParams{}));
    EXPECT_GT(with_ears.hi.x - with_ears.lo.x, b.hi.x - b.lo.x + 1.0f);
}

TEST(Head, ScaleMultipliesEveryCoordinate)
{
    HeadParams cm;
    cm.resolution = 16;
    HeadParams m = cm;
    m.scale = 0.01f;
    const PolygonSoup a = make_head(cm), b = make_head(m);
    ASSERT_EQ(a.points.size(), b.points.size());
    ASSERT_EQ(a.face_indices, b.face_indices);
    for (size_t i = 0; i < a.points.size(); ++i) {
        EXPECT_NEAR(b.points[i].x, a.points[i].x * 0.01f, 1e-6f);
        EXPECT_NEAR(b.points[i].y, a.points[i].y * 0.01f, 1e-6f);
        EXPECT_NEAR(b.points[i].z, a.points[i].z * 0.01f, 1e-6f);
    }
}

TEST(Head, InvalidParamsAreRejected)
{
    HeadParams p;
    p.resolution = 4;
    EXPECT_THROW(make_head(p), InvalidParam);
    p.resolution = 5000;
    EXPECT_THROW(make_head(p), InvalidParam);
    p = HeadParams{};
    p.scale = 0.0f;
    EXPECT_THROW(make_head(p), InvalidParam);
    p.scale = std::nanf("");
    try {
        make_head(p);
        FAIL();
    } catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`scale`"), std::string::npos);
    }
}
