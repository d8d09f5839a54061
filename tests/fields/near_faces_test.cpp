// NearFaces (the closest face outside the band from per-cell candidates) against a brute-force
// search of every face in double: the same face, the smallest distance and the lowest index at
// ties, on a sphere and on Sintel's open head, for every cell size; the same distance as the AABB
// tree's face; no candidates on a mesh whose faces are small for the cells (the tree answers
// there). MeshQuery::faces_seen_from, which cuts the lists, against brute force on a sphere: every
// face that is some point's closest is listed, and far out the list is a small patch.
#include "fields/scalp_field.h"
#include "fields/scalp_impl.h"
#include "kernel/io/mesh_io.h"
#include "kernel/rng.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace groom {
namespace {

/// Face f's distance from p: closest_on_triangle's float point, measured in double (independent of
/// NearFaces' own projection in double; the two agree to float rounding).
float3 random_direction(Rng& rng)
{
    const float z = rng.uniform(-1.0f, 1.0f), phi = rng.uniform(0.0f, 6.2831853f), s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {s * std::cos(phi), s * std::sin(phi), z};
}

double face_distance(const detail::MeshGeometry& g, int32_t f, const float3& p)
{
    detail::Feature feature;
    const float3 c = detail::closest_on_triangle(p, g.points[g.tris[f][0]], g.points[g.tris[f][1]], g.points[g.tris[f][2]], feature);
    const double dx = double(p.x) - c.x, dy = double(p.y) - c.y, dz = double(p.z) - c.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// Checks `count` points of the box grown by `grow` of its size: NearFaces' face is at the
/// brute-force minimum distance (to the float rounding of closest_on_triangle, 1e-6 relative) and
/// the tree's face is at that distance too. Returns how many points had a candidate list.
int check_against_brute_force(const ScalpField& field, int count, float grow, uint64_t seed, int level)
{
    const auto& im = field.impl();
    const auto& g = im.geometry;
    const Bounds3 box = field.bounds();
    const float3 size = box.hi - box.lo;
    int listed = 0;
    for (int i = 0; i < count; ++i) {
        Rng rng(seed, uint64_t(i));
        const float3 p = box.lo - size * grow + float3(rng.uniform() * size.x, rng.uniform() * size.y, rng.uniform() * size.z) * (1.0f + 2.0f * grow);
        const int32_t face = im.near(level).closest_face(p);
        if (face < 0) continue;
        ++listed;
        double best = INFINITY;
        for (int32_t f = 0; f < int32_t(g.tris.size()); ++f) best = std::min(best, face_distance(g, f, p));
        const double tol = 1e-6 * (best + std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}));
        EXPECT_NEAR(face_distance(g, face, p), best, tol) << p.x << "," << p.y << "," << p.z;
        EXPECT_NEAR(face_distance(g, im.query->tree_closest_face(p), p), best, tol) << p.x << "," << p.y << "," << p.z;
        // A pure function of p: asked again (from its cell, now made) the same face.
        EXPECT_EQ(im.near(level).closest_face(p), face);
        // query_dense answers as query() does, to float rounding at ties between faces.
        float3 n1, c1, n2, c2;
        const float d1 = field.query(p, n1, c1), d2 = field.query_dense(p, n2, c2, level);
        EXPECT_NEAR(d1, d2, 1e-5f * (1.0f + std::fabs(d1)));
        EXPECT_LE(length(c1 - c2), 1e-5f * (1.0f + length(p)));
        EXPECT_GT(dot(n1, n2), 0.99999f);
    }
    return listed;
}

TEST(NearFaces, SameFaceAsBruteForceAroundASphere)
{
    // Icosphere 4 of radius 1 at voxel 0.03: faces of 4.8 cell faces, lists for every cell within 48 voxels.
    const ScalpField field = build_scalp(icosphere({0.3f, -0.2f, 0.1f}, 1.0f, 4), {0.03f, 3.0f});
    for (int level = 0; level < ScalpField::kDenseLevels; ++level) {
        const int listed = check_against_brute_force(field, 3000, 0.4f, 5 + uint64_t(level), level);
        EXPECT_GT(listed, 2000) << "level " << level;
        const auto counts = field.impl().near(level).counts();
        EXPECT_GT(counts.cells, 0);
        EXPECT_LE(counts.candidates, counts.cells * int64_t(detail::NearFaces::kMaxCandidates));
    }
}

// A ball of radius r at distance D from a sphere of radius R: faces_seen_from must list every face
// a point of the ball is closest to (checked by brute force over 400 points of the ball), and far
// out keep far fewer faces than the ball of |c - s0| + 2 r around the centre that faces_within lists
// (a cap of half-angle 0.54 rad at D = 2R, r = 0.1R; the ball's points see a cap of 0.067 rad).
TEST(FacesSeenFrom, EveryClosestFaceOfTheBallAndFarFewerFarOut)
{
    const float R = 1.0f;
    const ScalpField field = build_scalp(icosphere({0, 0, 0}, R, 4), {0.03f, 3.0f});
    const auto& im = field.impl();
    const auto& g = im.geometry;
    for (const float D : {0.05f, 0.5f, 2.0f}) {
        const float r = 0.1f;
        const float3 axis = normalize(float3(0.3f, 0.8f, -0.5f));
        const float3 c = axis * (R + D);
        int32_t nearest = -1;
        double best = INFINITY;
        for (int32_t f = 0; f < int32_t(g.tris.size()); ++f) {
            const double d = face_distance(g, f, c);
            if (d < best) best = d, nearest = f;
        }
        detail::Feature feature;
        const float3 s0f = detail::closest_on_triangle(c, g.points[g.tris[nearest][0]], g.points[g.tris[nearest][1]], g.points[g.tris[nearest][2]], feature);
        const double s0[3] = {s0f.x, s0f.y, s0f.z};
        std::vector<int32_t> faces, all;
        std::vector<double> dist, all_dist;
        im.query->faces_seen_from(c, r, s0, 1e-6, faces, dist);
        im.query->faces_within(c, best + 2.0 * r, all, &all_dist);
        std::sort(faces.begin(), faces.end());
        for (int i = 0; i < 400; ++i) {
            Rng rng(77, uint64_t(i));
            const float3 p = c + random_direction(rng) * (r * std::cbrt(rng.uniform()));
            int32_t closest = -1;
            double d = INFINITY;
            for (int32_t f = 0; f < int32_t(g.tris.size()); ++f) {
                const double e = face_distance(g, f, p);
                if (e < d) d = e, closest = f;
            }
            ASSERT_TRUE(std::binary_search(faces.begin(), faces.end(), closest)) << "D " << D << " point " << i;
        }
        if (D >= 2.0f) EXPECT_LT(faces.size() * 3, all.size()) << faces.size() << " of " << all.size();
    }
}

TEST(NearFaces, FacesSmallForTheCellsLeaveItToTheTree)
{
    // Icosphere 6 (81,920 faces) at the automatic voxel: 0.21 cell faces each, below kMinFaceArea.
    const ScalpField field = build_scalp(icosphere({0, 0, 0}, 1.0f, 6));
    for (int i = 0; i < 200; ++i) {
        Rng rng(9, uint64_t(i));
        const float3 p(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
        ASSERT_EQ(field.impl().near().closest_face(p), -1);
    }
    EXPECT_EQ(field.impl().near().counts().cells, 0);
}

TEST(NearFacesReal, SintelsOpenHeadSameFaceAsBruteForce)
{
    const std::string path = test::shared_file("sintel_tressfx_opengl/sintel.obj");
    if (path.empty()) GTEST_SKIP() << "../shared/datasets is absent";
    const ScalpField field = build_scalp(read_mesh(path));
    // Where hair is: the head's box grown by a fifth on each side.
    for (int level = 0; level < ScalpField::kDenseLevels; ++level) EXPECT_GT(check_against_brute_force(field, 1500, 0.2f, 31, level), 1000);
}

}  // namespace
}  // namespace groom
