// root_uv: hairs grown on a scalp with texture coordinates carry each root's scalp UV; the lat-long
// sphere gives it in closed form (u = phi / 2 pi, v = 1 - theta / pi at the root's direction).
#include "ops/root_uv.h"

#include "fields/scalp_field.h"
#include "kernel/parallel.h"
#include "ops/generate.h"
#include "support/sphere_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

using namespace groom;

namespace {

constexpr float kR = 10.0f;
constexpr int kRings = 48, kSegments = 96;

/// Four straight guides at latitude 60 degrees from +Y, longitudes 40..130 degrees: away from the
/// seam (phi = 0) and the poles.
CurveSet guides()
{
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(4, 6));
    auto P = cs.positions_for_write();
    for (int g = 0; g < 4; ++g) {
        const double th = std::numbers::pi / 3, ph = (40.0 + 30.0 * g) * std::numbers::pi / 180;
        const float3 n(float(std::sin(th) * std::cos(ph)), float(std::cos(th)), float(std::sin(th) * std::sin(ph)));
        for (int i = 0; i < 6; ++i) P[size_t(6 * g + i)] = n * (kR + 0.5f * float(i));
    }
    return cs;
}

}  // namespace

TEST(RootUv, GeneratedHairsCarryTheirRootsLatitudeAndLongitude)
{
    const ScalpField scalp = build_scalp(latlong_uv_sphere(kR, kRings, kSegments), {0.25f, 3.0f});
    GenerateParams p;
    p.count = 500;
    p.seed = 3;
    const CurveSet hair = generate(guides(), scalp, scalp_root_sampler(scalp), p);
    const auto uv = hair.find<float3>(Domain::Curve, "root_uv");
    ASSERT_EQ(uv.size(), hair.num_curves());
    double worst_u = 0, worst_v = 0;
    for (size_t c = 0; c < hair.num_curves(); ++c) {
        const float3 d = normalize(hair.positions()[size_t(hair.points_of(c).begin)]);
        double phi = std::atan2(double(d.z), double(d.x));
        if (phi < 0) phi += 2 * std::numbers::pi;
        const double theta = std::acos(std::clamp(double(d.y), -1.0, 1.0));
        // The closed form's bound (tests/fields/scalp_uv_test.cpp): linear interpolation over a
        // band's trapezoid strays by up to cot(theta) dtheta / 4 of a slice in u; v within 2% of a band.
        const double dtheta = std::numbers::pi / kRings, band = std::floor(theta / dtheta) * dtheta;
        const double e = std::max(std::fabs(1 / std::tan(band)), std::fabs(1 / std::tan(band + dtheta))) * dtheta;
        const double du = std::fabs(uv[c].x - phi / (2 * std::numbers::pi)), dv = std::fabs(uv[c].y - (1 - theta / std::numbers::pi));
        EXPECT_LT(du, (1.1 * e / 4 + 0.005) / kSegments) << "root " << c << " theta " << theta << " phi " << phi;
        EXPECT_LT(dv, 0.02 / kRings) << "root " << c;
        worst_u = std::max(worst_u, du);
        worst_v = std::max(worst_v, dv);
        EXPECT_EQ(uv[c].z, 0.0f);
    }
    std::printf("[ info ] generate on the lat-long sphere: worst root |u - phi/2pi| %.3g, |v - (1 - theta/pi)| %.3g\n", worst_u, worst_v);
}

TEST(RootUv, NothingWrittenWithoutUvsAndSameForAnyThreadCount)
{
    PolygonSoup plain = latlong_uv_sphere(kR, 24, 48);
    plain.uvs.clear();
    plain.face_uv_indices.clear();
    const ScalpField no_uv = build_scalp(plain, {0.5f, 3.0f});
    CurveSet hair = guides();
    add_root_uvs(hair, no_uv);
    EXPECT_EQ(hair.attributes(Domain::Curve).find("root_uv"), nullptr);

    const ScalpField scalp = build_scalp(latlong_uv_sphere(kR, 24, 48), {0.5f, 3.0f});
    CurveSet many = CurveSet::from_counts(std::vector<int64_t>(3000, 2));
    auto P = many.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = normalize(float3(std::sin(0.37f * float(i)), std::cos(0.11f * float(i)), 0.3f)) * kR;
    CurveSet one = many, all = many;
    {
        ThreadLimit limit(1);
        add_root_uvs(one, scalp);
    }
    add_root_uvs(all, scalp);
    const auto a = one.find<float3>(Domain::Curve, "root_uv"), b = all.find<float3>(Domain::Curve, "root_uv");
    ASSERT_EQ(a.size(), 3000u);
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float3)));
}
