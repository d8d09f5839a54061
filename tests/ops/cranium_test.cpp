#include "ops/cranium.h"

#include "circle_on_sphere.h"

#include "kernel/error.h"

#include <gtest/gtest.h>

using namespace groom;

// The closed form: the scalp inside a hairline on a sphere is a cap of that sphere, so the fit
// must give the sphere back. An analytic sphere away from the origin (centre 3,-7,2, radius 8.5,
// so a fit about the origin would show), with a level and a tilted hairline below its equator:
// centre and radius within 1e-3 R. Tilted about Z, up (0,0,1) too: the rays are cast round `up`.
TEST(Cranium, FitsTheSphereUnderAHairline)
{
    const float3 c{3.0f, -7.0f, 2.0f};
    const float R = 8.5f;
    const AnalyticSphere sphere(c, R);
    for (const float3 up : {float3(0, 1, 0), float3(0, 0, 1)}) {
        for (const float tilt : {0.0f, 0.3f}) {
            const float3 n = normalize(up + any_perpendicular(up) * tilt);
            const CurveSet hairline = test::circle_on_sphere(c, R, n, -0.3f * R, 720);
            HairRegionParams hp;
            hp.up = up;
            const HairRegion region(sphere, hairline, CurveSet(), hp);
            const Cranium fit = fit_cranium(sphere, region, up);
            EXPECT_LT(distance(fit.center, c), 1e-3f * R) << "tilt " << tilt;
            EXPECT_NEAR(fit.radius, R, 1e-3f * R) << "tilt " << tilt;
            EXPECT_GT(fit.samples, 400) << "tilt " << tilt;
        }
    }
    // No hairline: nothing to fit to.
    const HairRegion none(sphere, CurveSet(), CurveSet(), HairRegionParams{});
    EXPECT_THROW(fit_cranium(sphere, none, float3(0, 1, 0)), InvalidGeometry);
}
