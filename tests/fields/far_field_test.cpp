// Queries outside the narrow band that need no exact distance (ScalpField::distance_within and the
// FarField certificates behind it), against closed forms: the sign and the bound of points far
// outside, far inside a closed sphere and at 1e20, on tessellated spheres whose exact surface is
// known; and against the exact query itself, whose answers they must reproduce to every
// comparison, on an open cap (rims signed by the winding number) and on Sintel's open head.
#include "fields/scalp_field.h"
#include "fields/scalp_impl.h"
#include "kernel/io/mesh_io.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace groom {
namespace {

float3 random_direction(Rng& rng)
{
    float3 d;
    do d = float3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    while (length(d) > 1.0f || length(d) < 0.1f);
    return normalize(d);
}

/// The certificate's own answer at p (0: none, the exact query answers there).
float certified(const ScalpField& field, const float3& p) { return field.impl().far().bound(p); }

/// True where the narrow band answers p (the certificates are for the points it does not).
bool in_band(const ScalpField& field, const float3& p)
{
    float d;
    float3 g;
    return field.impl().sample(p, d, g) && length_squared(g) > 0.25f;
}

TEST(FarField, SignAndBoundAgainstTheSphereOutsideAndFarInside)
{
    const float R = 1.0f;
    const PolygonSoup soup = icosphere({0, 0, 0}, R, 4);
    const float chord = sphere_chordal_error(soup, {0, 0, 0}, R);
    const ScalpField field = build_scalp(soup, {0.02f, 3.0f});
    const float h = field.voxel_size();
    int outside = 0, inside = 0, answered_out = 0, answered_in = 0;
    for (int i = 0; i < 6000; ++i) {
        Rng rng(21, uint64_t(i));
        const float3 dir = random_direction(rng);
        // Beyond the band (3 voxels) out to 4 R, and inside from the band down to the centre.
        const float r = i % 2 ? R + rng.uniform(4.0f * h, 3.0f * R) : rng.uniform(0.0f, R - 4.0f * h);
        const float3 p = dir * r;
        const float exact = r - R;  // the sphere's signed distance; the mesh's is within `chord` of it
        const float v = field.distance_within(p, 0.0f);
        ASSERT_EQ(v < 0.0f, exact < 0.0f) << "r=" << r;
        // A bound never exceeds the distance: the sphere's, and the mesh's own.
        ASSERT_LE(std::fabs(v), std::fabs(exact) + chord + 1e-5f) << "r=" << r;
        ASSERT_LE(std::fabs(v), std::fabs(field.distance(p)) * (1.0f + 1e-6f)) << "r=" << r;
        const float b = certified(field, p);
        (exact > 0 ? outside : inside) += 1;
        if (b != 0.0f) (exact > 0 ? answered_out : answered_in) += 1;
        // Where a certificate answers, its bound is the distance at the cell's centre less the way
        // to the point: short of the distance by at most the diagonal of a cell (8 voxels at most).
        if (b != 0.0f) ASSERT_GE(std::fabs(b), std::fabs(exact) - chord - std::sqrt(3.0f) * 8.0f * h) << "r=" << r;
    }
    // A sphere has no folds and no rims: certificates answer nearly everything out there.
    EXPECT_GT(answered_out, outside * 95 / 100);
    EXPECT_GT(answered_in, inside * 95 / 100);
}

TEST(FarField, ComparisonsAgreeWithTheExactDistanceOnAClosedAndAnOpenSurface)
{
    const float3 c(1, 2, 3), axis = normalize(float3(0.3f, 1.0f, 0.2f));
    const float R = 2.0f;
    const ScalpField sphere = build_scalp(uv_sphere(c, R, 24, 48), {R / 40, 3.0f});
    // An open cap: beyond its rim the exact query signs by the winding number, which flips across
    // the rim's seam; certificates must stay off the rims or agree.
    const ScalpField cap = build_scalp(sphere_cap(c, R, axis, 60.0f, 40, 96), {R / 50, 3.0f});
    for (const ScalpField* field : {&sphere, &cap}) {
        const float h = field->voxel_size();
        int certified_points = 0, off_band = 0;
        for (int i = 0; i < 4000; ++i) {
            Rng rng(22, uint64_t(i));
            const float3 p = c + random_direction(rng) * rng.uniform(0.0f, 2.5f * R);
            const float d = field->distance(p);
            ASSERT_EQ(field->distance_within(p, 0.0f) < 0.0f, d < 0.0f) << p.x << "," << p.y << "," << p.z;
            // Thresholds in (-reach, reach]: the bound answers each comparison as the distance does.
            for (const float reach : {0.5f * h, 3.0f * h, 20.0f * h}) {
                const float v = field->distance_within(p, reach);
                if (std::fabs(d) < reach) ASSERT_EQ(std::memcmp(&v, &d, sizeof v), 0) << "exact below the reach";
                for (const float t : {-0.99f * reach, 0.0f, 0.5f * reach, reach}) ASSERT_EQ(v < t, d < t) << "t=" << t << " d=" << d;
            }
            if (in_band(*field, p)) continue;
            ++off_band;
            certified_points += certified(*field, p) != 0.0f;
        }
        // Nearly all of the closed sphere's space is certified. Around the 60-degree cap, every
        // point whose closest point is on the rim (most of the space away from the cap's cone) is
        // signed by the winding number and left to the exact query. (24.8% since every rim vertex
        // counts as one: OpenMesh's is_boundary(vertex), used before, missed most of them.)
        EXPECT_GT(certified_points, off_band * (field == &sphere ? 97 : 22) / 100);
    }
}

TEST(FarField, PointsAt1e20AreAnsweredFromTheStandIn)
{
    const ScalpField field = build_scalp(icosphere({0, 0, 0}, 1.0f, 4), {0.02f, 3.0f});
    for (const float3 dir : {float3(1, 0, 0), normalize(float3(-1, 2, -3)), normalize(float3(0.2f, -1, 0.1f))}) {
        for (const float far : {1e20f, 1e30f}) {
            const float3 p = dir * far;
            float3 n, closest;
            const float d = field.query(p, n, closest);
            // The distance of a point that far from a unit sphere is its own length, to float rounding.
            EXPECT_GT(d, 0.0f);
            EXPECT_NEAR(d / far, 1.0f, 1e-6f);
            EXPECT_GT(dot(n, dir), 0.999999f);
            EXPECT_NEAR(length(closest), 1.0f, 0.01f);
            EXPECT_GT(dot(normalize(closest), dir), 0.99f);  // the sphere's point facing it
            EXPECT_GT(field.distance_within(p, 1.0f), 1.0f);
            EXPECT_FALSE(field.inside(p));
            EXPECT_FALSE(field.inside(-p));
        }
    }
    // The same query just inside the stand-in's radius answers through the tree as before.
    const float3 near(3000.0f, 0, 0);
    EXPECT_NEAR(field.distance(near), 2999.0f, 0.01f);
}

TEST(FarField, AnswersDoNotDependOnOrderOrThreads)
{
    const PolygonSoup soup = sphere_cap({0, 0, 0}, 1.0f, {0, 1, 0}, 100.0f, 30, 64);
    std::vector<float3> points(20000);
    for (size_t i = 0; i < points.size(); ++i) {
        Rng rng(23, i);
        points[i] = random_direction(rng) * rng.uniform(0.0f, 2.0f);
    }
    // Two fields, their certificates made in opposite orders, one serially, one in parallel.
    const ScalpField a = build_scalp(soup, {0.02f, 3.0f}), b = build_scalp(soup, {0.02f, 3.0f});
    std::vector<float> va(points.size()), vb(points.size());
    {
        const ThreadLimit one(1);
        for (size_t i = 0; i < points.size(); ++i) va[i] = a.distance_within(points[i], 0.01f);
    }
    parallel_for(int64_t(points.size()), 64, [&](int64_t begin, int64_t end) {
        for (int64_t i = end - 1; i >= begin; --i) {
            const size_t j = points.size() - 1 - size_t(i);
            vb[j] = b.distance_within(points[j], 0.01f);
        }
    });
    EXPECT_EQ(std::memcmp(va.data(), vb.data(), va.size() * sizeof(float)), 0);
}

TEST(FarFieldReal, SintelsOpenHeadAnswersAsTheExactQuery)
{
    const std::string path = test::shared_file("sintel_tressfx_opengl/sintel.obj");
    if (path.empty()) GTEST_SKIP() << "../shared/datasets is absent";
    // Open at the neck, the eyes, the mouth and the arms: the exact query signs rims by the winding
    // number and everything else by pseudo-normals; the certificates must agree everywhere.
    const ScalpField field = build_scalp(read_mesh(path));
    const Bounds3 box = field.bounds();
    const float3 size = box.hi - box.lo;
    int certified_points = 0, off_band = 0, inside = 0;
    for (int i = 0; i < 20000; ++i) {
        Rng rng(24, uint64_t(i));
        // The head's box grown by a third on each side, where hair goes.
        const float3 p = box.lo - size / 3.0f + float3(rng.uniform() * size.x, rng.uniform() * size.y, rng.uniform() * size.z) * (5.0f / 3.0f);
        const float d = field.distance(p), v = field.distance_within(p, 0.0f);
        ASSERT_EQ(v < 0.0f, d < 0.0f) << p.x << "," << p.y << "," << p.z;
        ASSERT_LE(std::fabs(v), std::fabs(d));
        inside += d < 0.0f;
        if (in_band(field, p)) continue;
        ++off_band;
        certified_points += certified(field, p) != 0.0f;
    }
    EXPECT_GT(inside, 500);
    // The rest lie nearest the rims (the neck and arm cuts leave the bust open below), at folds,
    // or straddle the surface between the band's voxels. 63% since all 148 rim vertices count as
    // rims (OpenMesh's is_boundary(vertex) had missed them: over 80% were certified, signed by a
    // pseudo-normal whose fan stops at the rim); the hair of `generate` on this head is as fast.
    EXPECT_GT(certified_points, off_band * 60 / 100);
}

}  // namespace
}  // namespace groom
