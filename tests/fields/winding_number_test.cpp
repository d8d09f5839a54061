// The hierarchical winding number against its definition (the exact solid-angle sum over every
// triangle) and against closed forms: 1 inside and 0 outside a closed sphere, 1 - cap fraction
// inside a sphere with a hole, the cap's own solid angle seen from the centre of its sphere.
#include "fields/winding_number.h"
#include "kernel/rng.h"
#include "support/sphere_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

namespace groom {
namespace {

std::vector<std::array<int32_t, 3>> triangles_of(const PolygonSoup& soup)
{
    std::vector<std::array<int32_t, 3>> out;
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        const auto idx = soup.face(f);
        out.push_back({idx[0], idx[1], idx[2]});
    }
    return out;
}

double exact(const PolygonSoup& soup, const std::vector<std::array<int32_t, 3>>& tris, const float3& p)
{
    double sum = 0.0;
    for (const auto& t : tris) {
        const float3 a = soup.points[t[0]] - p, b = soup.points[t[1]] - p, c = soup.points[t[2]] - p;
        const double la = length(a), lb = length(b), lc = length(c);
        const double det = double(dot(a, cross(b, c)));
        const double den = la * lb * lc + double(dot(a, b)) * lc + double(dot(a, c)) * lb + double(dot(b, c)) * la;
        sum += 2.0 * std::atan2(det, den);
    }
    return sum / (4.0 * M_PI);
}

TEST(WindingNumber, MatchesTheExactSumAndTheClosedSphere)
{
    const PolygonSoup sphere = icosphere({0.5f, -1.0f, 2.0f}, 2.0f, 4);  // 5120 triangles
    const auto tris = triangles_of(sphere);
    const detail::WindingNumber wn(sphere.points, tris);
    double worst2 = 0.0, worst4 = 0.0, worst8 = 0.0;
    for (uint64_t i = 0; i < 3000; ++i) {
        Rng rng(9, i);
        float3 dir;
        do dir = float3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        while (length(dir) > 1.0f || length(dir) < 0.1f);
        // Radii from the centre to 3R, dense near the surface where clusters must open up.
        const float r = i % 2 ? rng.uniform(1.9f, 2.1f) : rng.uniform(0.0f, 6.0f);
        const float3 p = float3(0.5f, -1.0f, 2.0f) + normalize(dir) * r;
        const double w2 = wn(p, 2.0), w4 = wn(p, 4.0), w8 = wn(p, 8.0), w = exact(sphere, tris, p);
        worst2 = std::max(worst2, std::fabs(w2 - w));
        worst4 = std::max(worst4, std::fabs(w4 - w));
        worst8 = std::max(worst8, std::fabs(w8 - w));
        // A closed mesh's winding number is exactly 1 inside and 0 outside (to float rounding of
        // the corner vectors); the faceted surface lies within 0.2% of R of the sphere.
        if (r < 1.95f) ASSERT_NEAR(w, 1.0, 1e-6) << "r = " << r;
        if (r > 2.05f) ASSERT_NEAR(w, 0.0, 1e-6) << "r = " << r;
    }
    // The expansion's error falls as 1 / far^2 (measured: 0.071 at 2, 0.018 at 4, 0.0045 at 8 here).
    EXPECT_LT(worst2, 0.08);
    EXPECT_LT(worst4, 0.025);
    EXPECT_LT(worst8, 0.006);
    EXPECT_LT(worst8, worst2 / 8.0);
}

TEST(WindingNumber, OpenSurfacesGiveTheirSolidAngle)
{
    // A cap of half-angle 60 degrees seen from its sphere's centre subtends 2 pi (1 - cos 60) = pi:
    // winding 1/4. The sphere with that cap removed: 3/4 (inside, far from the hole, still "inside").
    const float3 c(0, 0, 0);
    const float3 axis(0, 0, 1);
    const PolygonSoup cap = sphere_cap(c, 1.0f, axis, 60.0f, 48, 96);
    const detail::WindingNumber cap_wn(cap.points, triangles_of(cap));
    EXPECT_NEAR(cap_wn(c, 8.0), 0.25, 6e-3);
    EXPECT_NEAR(cap_wn(float3(0, 0, -0.3f), 8.0), exact(cap, triangles_of(cap), float3(0, 0, -0.3f)), 6e-3);
    const PolygonSoup rest = sphere_cap(c, 1.0f, -axis, 120.0f, 48, 96);
    const detail::WindingNumber rest_wn(rest.points, triangles_of(rest));
    EXPECT_NEAR(rest_wn(c, 8.0), 0.75, 6e-3);
    EXPECT_GT(rest_wn(float3(0, 0, -0.5f)), 0.5) << "inside, across from the hole";
}

}  // namespace
}  // namespace groom
