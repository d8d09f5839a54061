// Texture coordinates on the scalp (fields/uv_map.h through ScalpField::surface_uv): a lat-long UV
// sphere answers u = phi / 2 pi, v = 1 - theta / pi at a known latitude and longitude, a point on the
// seam gets one consistent side, the .vdb keeps the UVs bit for bit, and a real head's UVs are found.
#include "fields/scalp_field.h"
#include "fields/uv_map.h"
#include "kernel/error.h"
#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"
#include "test_support.h"
#include "tests/fields/vdb_grid_file.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace groom {
namespace {

constexpr double kPi = std::numbers::pi;

float3 on_sphere(float R, double theta, double phi)
{
    return {float(R * std::sin(theta) * std::cos(phi)), float(R * std::cos(theta)), float(R * std::sin(theta) * std::sin(phi))};
}

constexpr int kRings = 48, kSegments = 96;

}  // namespace

TEST(ScalpUv, LatLongSphereGivesTheLatitudeAndLongitude)
{
    const float R = 10.0f;
    const PolygonSoup soup = latlong_uv_sphere(R, kRings, kSegments);
    // Wound inward by mistake? The repair orients shells outward; the UVs do not care.
    const ScalpField scalp = build_scalp(soup, {0.25f, 3.0f});
    ASSERT_TRUE(scalp.has_uvs());
    // Away from the poles and the seam, at latitudes and longitudes off the mesh's vertices. u, v
    // interpolate linearly over each flat triangle, which is exact at the vertices and along a
    // ring, but a band's quad is a trapezoid (ring widths sin(theta) differ by e = cot(theta) dtheta
    // relative): split along a diagonal, u strays from the longitude by up to e / 4 of a slice at
    // the middle of the band (closed form of the affine interpolation over the trapezoid's
    // triangles). Bound: that, plus 10% and 0.5% of a slice for the facet's projection; v within 2%
    // of a band.
    const double dtheta = kPi / kRings;
    double worst_u = 0, worst_v = 0, worst_ratio = 0;
    for (int i = 0; i < 400; ++i) {
        const double theta = 0.2 + (kPi - 0.4) * ((i * 37) % 400) / 400.0;
        const double phi = 0.05 + (2 * kPi - 0.1) * ((i * 91) % 400) / 400.0;
        float u = -1, v = -1;
        ASSERT_TRUE(scalp.surface_uv(on_sphere(R, theta, phi), u, v));
        const double du = std::fabs(u - phi / (2 * kPi)), dv = std::fabs(v - (1 - theta / kPi));
        const double band_theta = std::floor(theta / dtheta) * dtheta;  // the band's wider-ring side
        const double e = std::max(std::fabs(1.0 / std::tan(band_theta)), std::fabs(1.0 / std::tan(band_theta + dtheta))) * dtheta;
        const double bound = (1.1 * e / 4 + 0.005) / kSegments;
        EXPECT_LT(du, bound) << "theta " << theta << " phi " << phi;
        EXPECT_LT(dv, 0.02 / kRings) << "theta " << theta << " phi " << phi;
        worst_u = std::max(worst_u, du);
        worst_v = std::max(worst_v, dv);
        worst_ratio = std::max(worst_ratio, du / bound);
    }
    std::printf("[ info ] lat-long sphere: worst |u - phi/2pi| %.3g (%.2f%% of a slice, %.2f of its bound), |v - (1 - theta/pi)| %.3g "
                "(%.2f%% of a band)\n",
                worst_u, 100 * worst_u * kSegments, worst_ratio, worst_v, 100 * worst_v * kRings);
    // On a ring (a vertex latitude) the closest point is on the ring's chord or a hair beside it: u
    // within 0.5% of a slice, v within 1% of a band (measured up to 0.4%: the closest point falls
    // just inside the wider band's facet).
    for (int i = 0; i < 50; ++i) {
        const double theta = dtheta * (5 + i % 38), phi = 0.07 + 0.123 * i;
        float u = -1, v = -1;
        ASSERT_TRUE(scalp.surface_uv(on_sphere(R, theta, phi), u, v));
        EXPECT_NEAR(u, phi / (2 * kPi), 0.005 / kSegments) << "theta " << theta << " phi " << phi;
        EXPECT_NEAR(v, 1 - theta / kPi, 0.01 / kRings) << "theta " << theta << " phi " << phi;
    }
    // At a vertex's own position the interpolation is exact (to float rounding of the weights).
    float u = 0, v = 0;
    ASSERT_TRUE(scalp.surface_uv(soup.points[size_t(1 + 10 * kSegments + 24)], u, v));  // ring 11, slice 24
    EXPECT_NEAR(u, 24.0 / kSegments, 1e-6);
    EXPECT_NEAR(v, 1.0 - 11.0 / kRings, 1e-6);
    // Off the surface (a root lifted 0.3 along the normal) the closest point answers: on ring 16
    // (theta = pi / 3), longitude pi / 2 (slice 24's first vertex).
    ASSERT_TRUE(scalp.surface_uv(on_sphere(R + 0.3f, kPi / 3, kPi / 2), u, v));
    EXPECT_NEAR(u, 0.25, 1e-5);
    EXPECT_NEAR(v, 1.0 - 1.0 / 3.0, 1e-5);
}

TEST(ScalpUv, SeamGivesOneConsistentSide)
{
    const float R = 10.0f;
    const ScalpField scalp = build_scalp(latlong_uv_sphere(R, kRings, kSegments), {0.25f, 3.0f});
    // On the seam (phi = 0) both sides are equally close: u is 0 or 1, the same for every latitude
    // (the lowest-numbered triangle answers), and v is the latitude's.
    std::vector<float> seam_u;
    for (int i = 1; i < 40; ++i) {
        const double theta = kPi * (i + 0.37) / 41.0;
        float u = -1, v = -1;
        ASSERT_TRUE(scalp.surface_uv(on_sphere(R, theta, 0.0), u, v));
        EXPECT_TRUE(std::fabs(u) < 1e-5f || std::fabs(u - 1) < 1e-5f) << "theta " << theta << ": u " << u;
        EXPECT_NEAR(v, 1 - theta / kPi, 0.02 / kRings);
        seam_u.push_back(std::round(u));
        // Asked again: the same bits.
        float u2 = -1, v2 = -1;
        scalp.surface_uv(on_sphere(R, theta, 0.0), u2, v2);
        EXPECT_EQ(u, u2);
        EXPECT_EQ(v, v2);
    }
    for (float s : seam_u) EXPECT_EQ(s, seam_u.front());
    // Just either side of the seam, each side's own value: no blend of 0 and 1 across it.
    float u = 0, v = 0;
    ASSERT_TRUE(scalp.surface_uv(on_sphere(R, kPi / 2 + 0.01, 1e-3), u, v));
    EXPECT_NEAR(u, 1e-3 / (2 * kPi), 1e-4);
    ASSERT_TRUE(scalp.surface_uv(on_sphere(R, kPi / 2 + 0.01, -1e-3), u, v));
    EXPECT_NEAR(u, 1 - 1e-3 / (2 * kPi), 1e-4);
}

TEST(ScalpUv, VdbKeepsTheUvsAndOldFilesReadWithout)
{
    test::TempDir dir;
    const float R = 10.0f;
    const ScalpField built = build_scalp(latlong_uv_sphere(R, 24, 48), {0.5f, 3.0f});
    write_scalp(built, dir.file("uv.vdb"));
    const ScalpField loaded = read_scalp_vdb(dir.file("uv.vdb"));
    ASSERT_TRUE(loaded.has_uvs());
    for (int i = 0; i < 50; ++i) {
        const float3 p = on_sphere(R + 0.1f * float(i % 3), 0.1 + 0.06 * i, 0.13 * i);
        float u0 = 0, v0 = 0, u1 = 1, v1 = 1;
        ASSERT_TRUE(built.surface_uv(p, u0, v0));
        ASSERT_TRUE(loaded.surface_uv(p, u1, v1));
        EXPECT_EQ(u0, u1);  // shortest round-trip text: the same floats
        EXPECT_EQ(v0, v1);
    }
    // A mesh without UVs, and a file written before UVs were kept: no UVs, no error.
    PolygonSoup plain = latlong_uv_sphere(R, 24, 48);
    plain.uvs.clear();
    plain.face_uv_indices.clear();
    const ScalpField no_uv = build_scalp(plain, {0.5f, 3.0f});
    EXPECT_FALSE(no_uv.has_uvs());
    float u = 7, v = 7;
    EXPECT_FALSE(no_uv.surface_uv(float3(0, R, 0), u, v));
    EXPECT_EQ(u, 7.0f);
    write_scalp(no_uv, dir.file("plain.vdb"));
    EXPECT_FALSE(read_scalp_vdb(dir.file("plain.vdb")).has_uvs());
}

TEST(ScalpUv, DamagedUvMetadataIsAParseErrorNamingTheFile)
{
    test::TempDir dir;
    const ScalpField built = build_scalp(latlong_uv_sphere(10.0f, 12, 24), {1.0f, 3.0f});
    write_scalp(built, dir.file("uv.vdb"));
    openvdb::FloatGrid::Ptr g = test::read_scalp_grid(dir.file("uv.vdb"));
    const std::string good = g->metaValue<std::string>("groom_uv_mesh");
    auto refused = [&](const std::string& text, const char* why) {
        const std::string path = test::write_grid_with(g, "groom_uv_mesh", openvdb::StringMetadata(text), dir.file("bad.vdb"));
        try {
            read_scalp_vdb(path);
            ADD_FAILURE() << why << ": read without an error";
        }
        catch (const ParseError& e) {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("groom_uv_mesh"), std::string::npos) << e.what();
        }
    };
    refused(good.substr(0, good.size() / 2), "truncated");
    refused("groom-uv-mesh 1 3 3 99999999\n", "counts larger than the text");
    std::string nan = good;
    nan.replace(nan.find('\n') + 1, 1, "nan");
    refused(nan, "a NaN coordinate");
    refused("groom-uv-mesh 2 1 1 1\n0 0 0\n0 0\n0 0 0 0 0 0\n", "a newer version");
    refused("groom-uv-mesh 1 1 1 1\n0 0 0\n0 0\n0 0 1 0 0 0\n", "a vertex index out of range");
    g->removeMeta("groom_uv_mesh");
    g->insertMeta("groom_uv_mesh", openvdb::FloatMetadata(1.0f));
    openvdb::io::File out(dir.file("float.vdb"));
    out.write(openvdb::GridCPtrVec{g});
    out.close();
    EXPECT_THROW(read_scalp_vdb(dir.file("float.vdb")), ParseError);
}

TEST(ScalpUv, RealHeadLooksUpItsOwnFacesUvs)
{
    GROOM_REQUIRE_SHARED(path, "lee_perry_smith/LeePerrySmith.obj");
    const PolygonSoup soup = read_mesh(path);
    ASSERT_TRUE(soup.has_uvs());
    const ScalpField scalp = build_scalp(soup);
    ASSERT_TRUE(scalp.has_uvs());
    // A point inside each face: the centroid of the face's first triangle as the repair (and the
    // UV lookup) splits it, quads along the shorter diagonal. There the UV is the mean of those
    // three corners' UVs, unless another face passes as close (overlapping folds of the scan).
    int64_t checked = 0, matched = 0, in_unit_square = 0;
    for (size_t f = 0; f < soup.num_faces(); f += 3) {
        const auto idx = soup.face(f);
        const int32_t* t = soup.face_uv_indices.data() + soup.face_offsets[f];
        if (idx.size() < 3 || idx.size() > 4) continue;
        int k0 = 0, k1 = 1, k2 = 2;
        if (idx.size() == 4 && length_squared(soup.points[idx[1]] - soup.points[idx[3]]) < length_squared(soup.points[idx[0]] - soup.points[idx[2]])) {
            k0 = 1, k1 = 2, k2 = 3;
        }
        if (t[k0] < 0 || t[k1] < 0 || t[k2] < 0) continue;
        const float3 c = (soup.points[idx[k0]] + soup.points[idx[k1]] + soup.points[idx[k2]]) / 3.0f;
        float eu = 0, ev = 0;
        for (int k : {k0, k1, k2}) eu += soup.uvs[2 * t[k]] / 3.0f, ev += soup.uvs[2 * t[k] + 1] / 3.0f;
        float u = -1, v = -1;
        ASSERT_TRUE(scalp.surface_uv(c, u, v));
        ++checked;
        matched += std::fabs(u - eu) < 1e-4f && std::fabs(v - ev) < 1e-4f;
        in_unit_square += u >= 0 && u <= 1 && v >= 0 && v <= 1;
    }
    std::printf("[ info ] Lee Perry-Smith: %lld of %lld face points got their own face's UV (1e-4); %lld in [0,1]^2\n",
                (long long)matched, (long long)checked, (long long)in_unit_square);
    EXPECT_GT(checked, 2000);
    EXPECT_GE(double(matched), 0.99 * double(checked));
    EXPECT_EQ(in_unit_square, checked);
}

}  // namespace groom
