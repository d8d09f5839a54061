// The repair's linear oriented-manifold check decides whether CGAL's orientation runs at all, so it
// must agree with CGAL's own PMP::is_polygon_soup_a_polygon_mesh: on closed and open spheres, on
// each defect the repair meets, and on many random soups over a few vertices (where every
// configuration of shared edges and pinched fans turns up).
#include "fields/scalp_impl.h"
#include "kernel/rng.h"
#include "support/sphere_mesh.h"

#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <gtest/gtest.h>

#include <algorithm>

namespace groom {
namespace {

using Soup = std::vector<std::vector<size_t>>;

Soup triangles_of(const PolygonSoup& soup)
{
    Soup out;
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        const auto idx = soup.face(f);
        out.emplace_back(idx.begin(), idx.end());
    }
    return out;
}

bool cgal_says(const Soup& tris) { return CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(tris); }

TEST(ManifoldCheck, AgreesWithCgalOnSpheresAndTheirDefects)
{
    const PolygonSoup sphere = icosphere({0, 0, 0}, 1.0f, 2);
    Soup tris = triangles_of(sphere);
    const size_t n = sphere.points.size();
    EXPECT_TRUE(detail::is_oriented_manifold(tris, n));
    EXPECT_TRUE(cgal_says(tris));

    Soup flipped = tris;  // one face wound against its neighbours
    std::swap(flipped[7][1], flipped[7][2]);
    EXPECT_FALSE(detail::is_oriented_manifold(flipped, n));
    EXPECT_EQ(detail::is_oriented_manifold(flipped, n), cgal_says(flipped));

    Soup holed = tris;  // an open boundary is still a manifold
    holed.erase(holed.begin() + 3);
    EXPECT_TRUE(detail::is_oriented_manifold(holed, n));
    EXPECT_TRUE(cgal_says(holed));

    Soup fin = tris;  // a third face on an edge
    fin.push_back({tris[0][1], tris[0][0], n});
    EXPECT_FALSE(detail::is_oriented_manifold(fin, n + 1));
    EXPECT_EQ(detail::is_oriented_manifold(fin, n + 1), cgal_says(fin));

    Soup doubled = tris;  // the same face twice
    doubled.push_back(tris[5]);
    EXPECT_FALSE(detail::is_oriented_manifold(doubled, n));
    EXPECT_EQ(detail::is_oriented_manifold(doubled, n), cgal_says(doubled));

    // Two spheres touching at one vertex: each fan is fine, the shared vertex has two.
    const PolygonSoup other = icosphere({2, 0, 0}, 1.0f, 1);
    Soup pinched = tris;
    for (auto t : triangles_of(other)) {
        for (size_t& v : t) v = (v == 0) ? 0 : v + n;
        pinched.push_back(t);
    }
    EXPECT_FALSE(detail::is_oriented_manifold(pinched, n + other.points.size()));
    EXPECT_EQ(detail::is_oriented_manifold(pinched, n + other.points.size()), cgal_says(pinched));
}

TEST(ManifoldCheck, AgreesWithCgalOnRandomSoups)
{
    int manifold = 0, not_manifold = 0;
    for (uint64_t trial = 0; trial < 20000; ++trial) {
        Rng rng(31, trial);
        const size_t vertices = 4 + size_t(rng.uniform() * 4.0f);
        const size_t faces = 1 + size_t(rng.uniform() * 8.0f);
        Soup tris;
        for (size_t f = 0; f < faces; ++f) {
            std::vector<size_t> t(3);
            do {
                for (size_t& v : t) v = std::min(vertices - 1, size_t(rng.uniform() * float(vertices)));
            } while (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]);
            tris.push_back(t);
        }
        const bool ours = detail::is_oriented_manifold(tris, vertices);
        ASSERT_EQ(ours, cgal_says(tris)) << "trial " << trial;
        (ours ? manifold : not_manifold) += 1;
    }
    // Both answers must be common, or the comparison proves little.
    EXPECT_GT(manifold, 2000);
    EXPECT_GT(not_manifold, 2000);
}

}  // namespace
}  // namespace groom
