// Surface::known_clear, ScalpField's shortcut for "is this point at least `need` outside?" from one
// worked-out lower bound per voxel (fields/clear_cells.h). It may only ever say yes where the full
// question (distance_within) says yes, and the exact distance agrees: checked on a closed sphere, an
// open cap (rims signed by the winding number) and Sintel's open head, at points packed into few
// voxels (so most answers come from a byte another point's question filled). keep_outside must come out bit for bit as when every point is asked in full (curl's
// use: tests/ops/curl_test.cpp).
#include "fields/clear_cells.h"
#include "fields/keep_outside.h"
#include "fields/scalp_field.h"
#include "kernel/io/curve_io.h"
#include "support/ask_every_point.h"
#include "kernel/io/mesh_io.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace groom {
namespace {

/// Points near the surface where hair lies: `voxels` voxels picked within `spread` voxels of the
/// surface (by the closest point of a random point), each given the 8 corners of a voxel-sized
/// box around it and 12 random points in that box, so a voxel's byte is filled by one of them and
/// read by the rest.
std::vector<float3> points_in_voxels(const ScalpField& field, const float3& lo, const float3& hi, int voxels, float spread, uint64_t seed)
{
    const float h = field.voxel_size();
    std::vector<float3> points;
    for (int i = 0; i < voxels; ++i) {
        Rng rng(seed, uint64_t(i));
        const float3 q(rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z));
        float3 n, c;
        field.query(q, n, c);
        const float3 p = c + n * (rng.uniform(-0.5f, spread) * h);
        for (int k = 0; k < 20; ++k) {
            const float3 jitter = k < 8 ? float3(k & 1 ? 0.5f : -0.5f, k & 2 ? 0.5f : -0.5f, k & 4 ? 0.5f : -0.5f) * (h * 0.999f)
                                        : float3(rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f)) * h;
            points.push_back(p + jitter);
        }
    }
    return points;
}

/// Every "known clear" is clear to the full question and to the exact distance; returns how many
/// of the points were known clear at `need`.
int check_never_wrong(const ScalpField& field, const std::vector<float3>& points, float need)
{
    int known = 0;
    for (const float3& p : points) {
        if (!field.known_clear(p, need)) continue;
        ++known;
        EXPECT_GE(field.distance_within(p, need), need) << "need " << need << " at " << p.x << "," << p.y << "," << p.z;
        EXPECT_GE(field.distance(p), need) << "need " << need << " at " << p.x << "," << p.y << "," << p.z;
        if (::testing::Test::HasFailure()) return known;
    }
    return known;
}

TEST(ClearCells, CodesNeverStandForMoreThanTheirBound)
{
    const int64_t lo[3] = {-2, -2, -2}, n[3] = {4, 4, 4};
    const detail::ClearCells cells(lo, n, 0.1f);
    EXPECT_EQ(cells.encode(0.0f), detail::ClearCells::kNothing);
    EXPECT_EQ(cells.encode(-1.0f), detail::ClearCells::kNothing);
    EXPECT_EQ(cells.encode(std::nanf("")), detail::ClearCells::kNothing);
    EXPECT_EQ(cells.encode(0.1f / 16.0f * 0.99f), detail::ClearCells::kNothing);  // under a 16th of a voxel
    for (int i = 1; i < 4000; ++i) {
        const float lower = float(i) * 0.00037f;
        const uint8_t code = cells.encode(lower);
        ASSERT_LE(cells.decode(code), lower) << lower;
        if (lower >= 0.1f / 16.0f * 1.0001f && lower < 254.0f * 0.1f / 16.0f) {
            ASSERT_GT(code, detail::ClearCells::kNothing);
            ASSERT_GT(cells.decode(code), lower - 0.1f / 16.0f - 1e-6f) << lower;  // rounded down by under a 16th of a voxel
        }
    }
    EXPECT_EQ(cells.decode(cells.encode(1e9f)), 254.0f * (0.1f / 16.0f));
    // The box: blocks -2..1 hold voxels -16..15 on each axis.
    EXPECT_NE(cells.slot(-16, 15, 0), nullptr);
    EXPECT_EQ(cells.slot(16, 0, 0), nullptr);
    EXPECT_EQ(cells.slot(0, -17, 0), nullptr);
    EXPECT_EQ(cells.blocks(), 1);
    EXPECT_EQ(*cells.slot(-16, 15, 0), detail::ClearCells::kUnknown);
}

TEST(ClearCells, KnownClearOnlyWhereTheFullQuestionAgreesOnAClosedAndAnOpenSurface)
{
    const float3 c(1, 2, 3), axis = normalize(float3(0.3f, 1.0f, 0.2f));
    const float R = 2.0f;
    const ScalpField sphere = build_scalp(uv_sphere(c, R, 24, 48), {R / 40, 3.0f});
    // Beyond the cap's rim the sign comes from the winding number and jumps across the rim's seam.
    const ScalpField cap = build_scalp(sphere_cap(c, R, axis, 60.0f, 40, 96), {R / 50, 3.0f});
    for (const ScalpField* field : {&sphere, &cap}) {
        const float h = field->voxel_size();
        const float3 lo = c - float3(1.6f * R, 1.6f * R, 1.6f * R), hi = c + float3(1.6f * R, 1.6f * R, 1.6f * R);
        const std::vector<float3> points = points_in_voxels(*field, lo, hi, 600, 12.0f, field == &sphere ? 31 : 32);
        for (const float need : {0.0f, 0.3f * h, 2.0f * h, 6.0f * h, 20.0f * h}) {
            check_never_wrong(*field, points, need);
            if (HasFailure()) return;
        }
    }
    // Useful where it should be: the closed sphere's points from 1.5 voxels out are nearly all
    // known clear at need 0 (their voxels lie wholly outside); none inside ever is.
    const float h = sphere.voxel_size(), chord = sphere_chordal_error(uv_sphere(c, R, 24, 48), c, R);
    int outside = 0, known = 0;
    for (int i = 0; i < 5000; ++i) {
        Rng rng(33, uint64_t(i));
        float3 d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        if (length(d) < 0.1f) continue;
        d = normalize(d);
        const float r = i % 2 ? R + chord + rng.uniform(1.5f * h, 10.0f * h) : rng.uniform(0.0f, R - chord - 0.01f * h);
        const bool k = sphere.known_clear(c + d * r, 0.0f);
        if (r > R) {
            ++outside;
            known += k;
        }
        else {
            ASSERT_FALSE(k) << "a point inside the sphere, r = " << r;
        }
    }
    EXPECT_GT(known, outside * 95 / 100);
}

TEST(ClearCells, AnswersDoNotDependOnOrderOrThreads)
{
    const PolygonSoup soup = sphere_cap({0, 0, 0}, 1.0f, {0, 1, 0}, 100.0f, 30, 64);
    const ScalpField a = build_scalp(soup, {0.02f, 3.0f}), b = build_scalp(soup, {0.02f, 3.0f});
    const std::vector<float3> points = points_in_voxels(a, float3(-1.5f, -1.5f, -1.5f), float3(1.5f, 1.5f, 1.5f), 1000, 8.0f, 34);
    std::vector<uint8_t> ka(points.size()), kb(points.size());
    {
        const ThreadLimit one(1);
        for (size_t i = 0; i < points.size(); ++i) ka[i] = a.known_clear(points[i], 0.01f);
    }
    parallel_for(int64_t(points.size()), 64, [&](int64_t begin, int64_t end) {
        for (int64_t i = end - 1; i >= begin; --i) {
            const size_t j = points.size() - 1 - size_t(i);
            kb[j] = b.known_clear(points[j], 0.01f);
        }
    });
    EXPECT_EQ(ka, kb);
    EXPECT_GT(std::count(ka.begin(), ka.end(), uint8_t(1)), int64_t(points.size()) / 4);
}

TEST(ClearCellsReal, SintelsOpenHeadNeverWrongAndKeepOutsideAsWhenEveryPointIsAsked)
{
    GROOM_REQUIRE_SHARED(head, "sintel_tressfx_opengl/sintel.obj");
    GROOM_REQUIRE_SHARED(guides_path, "sintel_tressfx_opengl/sintel_guides.obj");
    const ScalpField field = build_scalp(read_mesh(head));
    const Bounds3 box = field.bounds();
    const float3 size = box.hi - box.lo;
    // Open at the neck, eyes, mouth and arms: 2,707 seam voxels and rims signed by the winding number.
    const std::vector<float3> points = points_in_voxels(field, box.lo - size * 0.2f, box.hi + size * 0.2f, 3000, 16.0f, 35);
    const float h = field.voxel_size();
    for (const float need : {0.0f, 0.5f * h, 3.0f * h}) {
        const int known = check_never_wrong(field, points, need);
        if (HasFailure()) return;
        if (need == 0.0f) EXPECT_GT(known, int(points.size()) / 2);
    }
    // And the rule on whole curves (generate, cull, puff): the guides sunk a unit (4 voxels) toward the middle of the head.
    const CurveSet guides = read_curves(guides_path);
    const test::AskEveryPoint every(field);
    CurveSet sunk_quick = guides, sunk_full = guides;
    const float3 centre = (box.lo + box.hi) * 0.5f;
    for (CurveSet* s : {&sunk_quick, &sunk_full}) {
        for (float3& p : s->positions_for_write()) p += normalize(centre - p) * 1.0f;
    }
    const KeepOutside rule{0.05f, 1e-4f, 4};
    const KeepOutsideCount moved = keep_outside(sunk_quick, field, rule);
    keep_outside(sunk_full, every, rule);
    EXPECT_GT(moved.points, 1000);
    const auto sq = sunk_quick.positions(), sf = sunk_full.positions();
    EXPECT_EQ(std::memcmp(sq.data(), sf.data(), sq.size() * sizeof(float3)), 0);
}

}  // namespace
}  // namespace groom
