// Open rims and their filling (fields/rims.h, `groom scalp --fill-holes`): a sphere missing its top
// cap, whose rim is a regular polygon in the plane y = cos(20 degrees). Filled, the hole is that
// plane's disc, so the distance along the axis is the closed form y - cos(20 degrees).
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "support/sphere_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace groom {
namespace {

constexpr int kRings = 48, kSegments = 64;
const double kRimAngle = 20.0 * std::numbers::pi / 180.0;

/// A unit sphere without the cap within 20 degrees of +Y.
PolygonSoup open_sphere() { return sphere_cap({0, 0, 0}, 1.0f, {0, -1, 0}, 160.0f, kRings, kSegments); }

TEST(ScalpRims, RimLengthsAreReported)
{
    RepairReport report;
    build_scalp(open_sphere(), {0.02f, 3.0f}, &report);
    ASSERT_EQ(report.rim_lengths.size(), 1u);
    // The perimeter of the regular 64-gon inscribed in the rim circle.
    const double perimeter = 2.0 * kSegments * std::sin(kRimAngle) * std::sin(std::numbers::pi / kSegments);
    EXPECT_NEAR(report.rim_lengths[0], perimeter, 1e-5);
    EXPECT_EQ(report.holes_filled, 0);
    // A closed sphere has none.
    RepairReport closed;
    build_scalp(uv_sphere({0, 0, 0}, 1.0f, 16, 32), {0.02f, 3.0f}, &closed);
    EXPECT_TRUE(closed.rim_lengths.empty());
}

TEST(ScalpRims, FilledHoleIsThePlaneOfItsRim)
{
    const PolygonSoup open = open_sphere();
    ScalpBuildParams params{0.02f, 3.0f};
    RepairReport before;
    const ScalpField unfilled = build_scalp(open, params, &before);
    const double perimeter = before.rim_lengths.at(0);

    params.fill_holes = float(0.99 * perimeter);  // shorter than the rim: left open
    RepairReport short_of;
    build_scalp(open, params, &short_of);
    EXPECT_EQ(short_of.holes_filled, 0);
    EXPECT_EQ(short_of.output_faces, before.output_faces);

    params.fill_holes = float(1.01 * perimeter);
    RepairReport report;
    const ScalpField filled = build_scalp(open, params, &report);
    EXPECT_EQ(report.holes_filled, 1);
    EXPECT_EQ(report.faces_added_by_fill, kSegments - 2);  // a polygon of n corners, no new vertex
    EXPECT_EQ(report.output_faces, before.output_faces + kSegments - 2);

    // Along the axis: above the disc, and just under it (inside the sphere, nearer the disc than
    // the sphere). Exact from the mesh beyond the band; trilinear within it (0.25 voxel).
    const double plane = std::cos(kRimAngle);
    for (const double y : {2.0, 1.5, 1.2, 0.97, 0.9}) {
        const double expect = y - plane;
        const double tol = std::fabs(expect) > 3.0 * params.voxel_size ? 1e-4 : 0.25 * params.voxel_size;
        EXPECT_NEAR(filled.distance({0, float(y), 0}), expect, tol) << "y " << y;
    }
    // Unfilled, just under the hole is inside by the distance to the rim, not to the disc.
    const double to_rim = std::hypot(std::sin(kRimAngle), plane - 0.9);
    EXPECT_NEAR(unfilled.distance({0, 0.9f, 0}), -to_rim, 0.01);
    // Away from the hole nothing changes: the sphere's own distance (its chordal error, 0.002).
    for (const float3 p : {float3(0, -1.5f, 0), float3(1.3f, 0, 0), float3(0, 0, -0.5f)}) {
        EXPECT_NEAR(filled.distance(p), unfilled.distance(p), 1e-6f);
        EXPECT_NEAR(filled.distance(p), length(p) - 1.0f, 0.003f);
    }
}

TEST(ScalpRims, NegativeOrNonFiniteLengthIsRefused)
{
    for (const float bad : {-1.0f, std::nanf(""), INFINITY}) {
        ScalpBuildParams params;
        params.fill_holes = bad;
        EXPECT_THROW(params.validate(), InvalidParam) << bad;
    }
}

}  // namespace
}  // namespace groom
