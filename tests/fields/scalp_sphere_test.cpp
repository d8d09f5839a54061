// Accuracy of the scalp field against exact spheres: distance, normal angle and projection error
// at points inside the narrow band, for several radii, centres and tessellations, at voxel sizes
// h = R/20 .. R/200, and their convergence as h shrinks. The mesh's own chordal error (its flat
// triangles sit up to `chord` inside the sphere) bounds what any field built from it can do, so
// each tolerance is chord + a multiple of the interpolation error (h^2 / R for a trilinear field).
#include "fields/scalp_field.h"
#include "kernel/rng.h"
#include "support/similarity.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace groom {
namespace {

struct Errors {
    double distance = 0, angle_deg = 0, projection = 0;
};

/// Errors over `n` points at random directions and signed distances within +-band_frac * band * h.
Errors measure(const ScalpField& field, const AnalyticSphere& sphere, int n, float spread, uint64_t seed)
{
    Errors e;
    for (int i = 0; i < n; ++i) {
        Rng rng(seed, uint64_t(i));
        float3 dir;
        do dir = float3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        while (length(dir) > 1.0f || length(dir) < 0.1f);
        dir = normalize(dir);
        const float3 p = sphere.center() + dir * (sphere.radius() + rng.uniform(-spread, spread));
        e.distance = std::max(e.distance, double(std::fabs(field.distance(p) - sphere.distance(p))));
        const float c = std::clamp(dot(field.normal(p), sphere.normal(p)), -1.0f, 1.0f);
        e.angle_deg = std::max(e.angle_deg, std::acos(double(c)) * 180.0 / M_PI);
        e.projection = std::max(e.projection, double(distance(field.closest_point(p), sphere.closest_point(p))));
    }
    return e;
}

struct Case {
    float3 center;
    float radius;
    PolygonSoup soup;
    std::vector<float> divisions;  // h = R / division
};

TEST(ScalpSphere, AccuracyWithinStatedTolerancesAndConverges)
{
    const Case cases[] = {
        {{0, 0, 0}, 1.0f, icosphere({0, 0, 0}, 1.0f, 5), {20, 50, 100, 200}},
        {{3.5f, -2.0f, 10.0f}, 12.0f, icosphere({3.5f, -2.0f, 10.0f}, 12.0f, 4), {20, 50, 100}},
        {{0.1f, 0.2f, -0.3f}, 0.1f, uv_sphere({0.1f, 0.2f, -0.3f}, 0.1f, 48, 96), {20, 50, 100}},
    };
    for (const Case& cs : cases) {
        const PolygonSoup& soup = cs.soup;
        const float chord = sphere_chordal_error(soup, cs.center, cs.radius);
        const AnalyticSphere sphere(cs.center, cs.radius);
        double previous = 1e30;
        for (float div : cs.divisions) {
            ScalpBuildParams params;
            params.voxel_size = cs.radius / div;
            params.band_voxels = 3.0f;
            const ScalpField field = build_scalp(soup, params);
            const float h = params.voxel_size;
            const Errors e = measure(field, sphere, 2000, 1.5f * h, 7);
            SCOPED_TRACE(testing::Message() << "R=" << cs.radius << " h=R/" << div << " chord=" << chord / cs.radius
                                            << "R dist=" << e.distance / cs.radius << "R angle=" << e.angle_deg
                                            << "deg proj=" << e.projection / cs.radius << "R");
            // Distance: the mesh's chord plus trilinear interpolation error (h^2/(2R) bounds the
            // curvature term of a sphere's distance over one voxel) plus float rounding.
            const double interp = h * h / (2.0 * cs.radius);
            EXPECT_LE(e.distance, chord + interp + 1e-5 * cs.radius);
            // Projection lands on the mesh, within the chord of the sphere, plus interpolation error.
            EXPECT_LE(e.projection, chord + 2.0 * interp + 1e-5 * cs.radius);
            // Normal: the faceted mesh's normals deviate from the sphere's by up to the facet's
            // half-angle (about sqrt(2 chord / R) radians); the gradient smooths across facets.
            const double facet_deg = std::sqrt(2.0 * chord / cs.radius) * 180.0 / M_PI;
            EXPECT_LE(e.angle_deg, facet_deg + 2.0 * h / cs.radius * 180.0 / M_PI);
            const double total = e.distance + e.projection;
            EXPECT_LE(total, previous * 1.05 + chord) << "error must not grow as h shrinks";
            previous = total;
        }
    }
}

/// Largest angle (degrees) between the field's normal and the sphere's at `n` random points within
/// `spread` of the sphere.
double max_normal_angle(const Surface& field, const AnalyticSphere& sphere, int n, float spread, uint64_t seed)
{
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
        Rng rng(seed, uint64_t(i));
        float3 dir;
        do dir = float3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        while (length(dir) > 1.0f || length(dir) < 0.1f);
        dir = normalize(dir);
        const float3 p = sphere.center() + dir * (sphere.radius() + rng.uniform(-spread, spread));
        const double c = std::clamp(double(dot(field.normal(p), dir)), -1.0, 1.0);
        worst = std::max(worst, std::acos(c) * 180.0 / M_PI);
    }
    return worst;
}

// Cornrows lie along the scalp's normals (issue 21). On a finely tessellated sphere (icosphere 6,
// whose facets' normals are within 0.6 degrees of the sphere's) at h = R/60, moved, turned and
// scaled, the field's normal is within 1 degree of the sphere's everywhere within 2 voxels of it
// and within 0.25 degrees within half a voxel; the same for the field read back from its .vdb,
// whose far-query mesh is the zero crossing with voxel-sized facets. Measured: 0.55 and 0.10
// degrees (0.28 and 0.10 from the .vdb); before the band's normal reached the cells at its edge
// and the band's edge had second-order differences, 0.64 and 1.9 (.vdb) within 2 voxels.
TEST(ScalpSphere, NormalsWithinADegreeInAnyPose)
{
    const float3 center(0.31f, -0.27f, 0.14f);
    const PolygonSoup unit = icosphere(center, 1.0f, 6);
    test::TempDir dir;
    for (uint64_t pose = 0; pose < 3; ++pose) {
        const Similarity motion = pose == 0 ? Similarity{} : Similarity::random(pose, 0.05, 20.0, 100.0);
        const AnalyticSphere sphere(motion.apply(center), float(motion.scale));
        ScalpBuildParams params;
        params.voxel_size = sphere.radius() / 60.0f;
        const float h = params.voxel_size;
        const ScalpField field = build_scalp(motion.apply(unit), params);
        SCOPED_TRACE(testing::Message() << "pose " << pose << ": scale " << motion.scale);
        EXPECT_LE(max_normal_angle(field, sphere, 6000, 2.0f * h, 3), 1.0);
        EXPECT_LE(max_normal_angle(field, sphere, 3000, 0.5f * h, 4), 0.25);
        if (pose == 1) {
            write_scalp(field, dir.file("sphere.vdb"));
            const std::shared_ptr<const ScalpField> loaded = load_scalp(dir.file("sphere.vdb"));
            EXPECT_LE(max_normal_angle(*loaded, sphere, 6000, 2.0f * h, 3), 1.0);
            EXPECT_LE(max_normal_angle(*loaded, sphere, 3000, 0.5f * h, 4), 0.25);
        }
    }
}

}  // namespace
}  // namespace groom
