// project against the exact sphere: roots land at radius R + offset along the normal, whole curves
// move rigidly (root mode) or every point lands on the surface (all mode); attributes carry through;
// results are identical for 1 and 2 threads.
#include "ops/project.h"

#include "kernel/error.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"

#include <gtest/gtest.h>

#include <cstring>

namespace groom {
namespace {

CurveSet random_curves(int n, int points, uint64_t seed)
{
    std::vector<int64_t> counts(n, points);
    CurveSet c = CurveSet::from_counts(counts);
    auto P = c.positions_for_write();
    auto w = c.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < P.size(); ++i) {
        Rng rng(seed, i);
        P[i] = float3(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3));
        w[i] = float(i);
    }
    return c;
}

TEST(Project, RootModeMovesCurvesRigidlyOntoTheSphere)
{
    const AnalyticSphere sphere({1, 2, 3}, 2.0f);
    const CurveSet src = random_curves(200, 5, 1);
    ProjectStats stats;
    const CurveSet dst = project(src, sphere, {ProjectMode::Root, 0.25f}, &stats);
    EXPECT_EQ(stats.curves, 200);
    for (size_t c = 0; c < dst.num_curves(); ++c) {
        const IndexRange r = dst.points_of(c);
        const float3 root = dst.positions()[r.begin];
        EXPECT_NEAR(sphere.distance(root), 0.25f, 1e-4f);
        const float3 shift = root - src.positions()[r.begin];
        for (int64_t i = r.begin; i < r.end; ++i) {
            EXPECT_LT(length(dst.positions()[i] - src.positions()[i] - shift), 1e-4f);
        }
    }
    EXPECT_EQ(dst.find<float>(Domain::Point, attr::width)[7], 7.0f);
}

TEST(Project, AllModePutsEveryPointOnTheSurface)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.5f);
    const CurveSet dst = project(random_curves(100, 8, 2), sphere, {ProjectMode::All, 0.0f});
    for (const float3& p : dst.positions()) EXPECT_NEAR(length(p), 1.5f, 1e-5f);
    const CurveSet off = project(random_curves(100, 8, 2), AnalyticPlane({0, 1, 0}, {0, 1, 0}), {ProjectMode::All, -0.5f});
    for (const float3& p : off.positions()) EXPECT_NEAR(p.y, 0.5f, 1e-5f);
}

TEST(Project, SameResultForAnyThreadCount)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    const CurveSet src = random_curves(3000, 4, 3);
    CurveSet a, b;
    {
        ThreadLimit one(1);
        a = project(src, sphere, {ProjectMode::All, 0.1f});
    }
    {
        ThreadLimit two(2);
        b = project(src, sphere, {ProjectMode::All, 0.1f});
    }
    EXPECT_EQ(0, std::memcmp(a.positions().data(), b.positions().data(), a.num_points() * sizeof(float3)));
}

TEST(Project, RejectsNonFiniteOffset)
{
    EXPECT_THROW(project(random_curves(1, 2, 0), AnalyticSphere({0, 0, 0}, 1), {ProjectMode::Root, NAN}), InvalidParam);
}

}  // namespace
}  // namespace groom
