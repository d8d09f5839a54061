// ScalpField beyond the clean closed sphere: open caps (sign on both sides), messy meshes repaired to
// the same answers, far-field queries, sampling, .vdb round trip, the independent Sintel SDF and
// every real head in ../shared/datasets.
#include "fields/scalp_field.h"
#include "kernel/io/mesh_io.h"
#include "kernel/error.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

namespace groom {
namespace {

float3 random_direction(Rng& rng)
{
    float3 d;
    do d = float3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    while (length(d) > 1.0f || length(d) < 0.1f);
    return normalize(d);
}

TEST(ScalpCap, SignCorrectOnBothSidesOfAnOpenCap)
{
    const float3 c(1, 2, 3), axis = normalize(float3(0.3f, 1.0f, 0.2f));
    const float R = 2.0f;
    const ScalpField field = build_scalp(sphere_cap(c, R, axis, 60.0f, 40, 96), {R / 50, 3.0f});
    const AnalyticSphere sphere(c, R);
    const float h = field.voxel_size();
    int checked = 0;
    for (int i = 0; i < 4000; ++i) {
        Rng rng(11, uint64_t(i));
        const float3 dir = random_direction(rng);
        // Points whose closest cap point is inside the cap (not on its rim), at 0.3h..2.5h either side,
        // and further out (fallback path) up to R/2 outside and R/2 inside.
        if (dot(dir, axis) < std::cos(55.0f * float(M_PI) / 180.0f)) continue;
        const float s = (i % 2 ? 1.0f : -1.0f) * (i % 3 ? rng.uniform(0.3f * h, 2.5f * h) : rng.uniform(0.3f * h, R * 0.5f));
        const float3 p = c + dir * (R + s);
        ASSERT_EQ(field.distance(p) < 0.0f, sphere.distance(p) < 0.0f) << "s=" << s << " h=" << h;
        ASSERT_LT(std::fabs(field.distance(p) - sphere.distance(p)), 0.01f * R);
        ++checked;
    }
    EXPECT_GT(checked, 700);  // about 21% of directions lie within 55 degrees of the axis
}

TEST(ScalpMessy, MessySphereGivesTheCleanAnswers)
{
    const float3 c(-1, 0.5f, 2);
    const float R = 1.5f;
    const int rings = 24, segments = 48;
    const PolygonSoup clean = uv_sphere(c, R, rings, segments);
    const PolygonSoup dirty = messy_uv_sphere(clean, rings, segments, c, R);
    const ScalpBuildParams params{R / 60, 3.0f};
    RepairReport report;
    const ScalpField a = build_scalp(clean, params);
    const ScalpField b = build_scalp(dirty, params, &report);
    EXPECT_GT(report.duplicate_vertices_merged, 0);
    EXPECT_GT(report.faces_flipped, 0);
    EXPECT_EQ(report.ngons_triangulated, segments + 1);
    EXPECT_GE(report.degenerate_faces_removed, 2);
    EXPECT_GT(report.non_manifold_edges + report.non_manifold_vertices, 0);
    EXPECT_EQ(report.enclosed_shells_removed, 1);
    EXPECT_EQ(report.boundary_loops, 2);  // the hole, and the fin's cut-off edges
    const float h = params.voxel_size;
    // Compare away from the hole and the fin (within 4h of them the surfaces really differ).
    const float3 hole = lerp(clean.points[1 + 7 * segments], clean.points[1 + 8 * segments], 0.5f);
    const float3 fin = clean.points[1 + 9 * segments + 3];
    const float chord = sphere_chordal_error(clean, c, R);
    int compared = 0;
    for (int i = 0; i < 3000; ++i) {
        Rng rng(5, uint64_t(i));
        const float3 p = c + random_direction(rng) * (R + rng.uniform(-2.0f * h, 2.0f * h));
        if (distance(p, hole) < 0.25f * R || distance(p, fin) < 0.15f * R) continue;
        ASSERT_NEAR(a.distance(p), b.distance(p), chord + 0.02f * h) << i;
        ASSERT_LT(distance(a.closest_point(p), b.closest_point(p)), 2.0f * chord + 0.05f * h) << i;
        ASSERT_GT(dot(a.normal(p), b.normal(p)), std::cos(3.0f * float(M_PI) / 180.0f)) << i;
        ++compared;
    }
    EXPECT_GT(compared, 2000);
}

// distance() and query() give one answer: keep_outside decides by the one and moves by the other.
// A sheet thinner than a voxel (an ear, a lip) has a short band gradient, where query() answers
// from the mesh; distance() used to read the band there, up to 0.09 units (0.4 voxel) inside on
// Sintel's ears at points query() had put on the surface, so they were never found clear.
TEST(ScalpField, DistanceAgreesWithQueryOnAThinSheet)
{
    // A closed slab 2 x 2 and 0.03 thick, against a voxel of 0.1.
    PolygonSoup slab;
    for (int i = 0; i < 8; ++i) slab.points.emplace_back(i & 1 ? 1.0f : -1.0f, i & 2 ? 0.015f : -0.015f, i & 4 ? 1.0f : -1.0f);
    const int32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) slab.add_face(q);
    const ScalpField field = build_scalp(slab, {0.1f, 3.0f});
    int thin = 0;
    for (int i = 0; i < 2000; ++i) {
        Rng rng(21, uint64_t(i));
        const float3 p(rng.uniform(-0.8f, 0.8f), rng.uniform(-0.25f, 0.25f), rng.uniform(-0.8f, 0.8f));
        float3 n, c;
        const float d = field.query(p, n, c);
        ASSERT_EQ(field.distance(p), d) << p.x << " " << p.y << " " << p.z;
        thin += std::fabs(d - (std::fabs(p.y) - 0.015f)) < 1e-5f;  // the mesh's exact answer
    }
    EXPECT_GT(thin, 200);
}

TEST(ScalpField, FarQueriesAreExactFromTheMesh)
{
    const ScalpField field = build_scalp(icosphere({0, 0, 0}, 1.0f, 4), {0.02f, 3.0f});
    const PolygonSoup soup = icosphere({0, 0, 0}, 1.0f, 4);
    const float chord = sphere_chordal_error(soup, {0, 0, 0}, 1.0f);
    for (const float3 p : {float3(10, 0, 0), float3(-3, 4, 0), float3(0, 0.3f, 0), float3(0.1f, -0.2f, 0.05f)}) {
        EXPECT_NEAR(field.distance(p), length(p) - 1.0f, chord + 1e-5f);
        EXPECT_NEAR(length(field.closest_point(p)), 1.0f, chord + 1e-5f);
        EXPECT_GT(dot(field.normal(p), normalize(p)), 0.99f);
    }
}

TEST(ScalpField, SampleBallIsAreaUniformDeterministicAndThreadIndependent)
{
    const ScalpField field = build_scalp(icosphere({0, 0, 0}, 1.0f, 4), {0.02f, 3.0f});
    const float3 center(0, 1, 0);
    std::vector<SurfaceSample> one, two;
    {
        ThreadLimit limit(1);
        one = field.sample_ball(center, 0.5f, 4000, 42);
    }
    {
        ThreadLimit limit(2);
        two = field.sample_ball(center, 0.5f, 4000, 42);
    }
    ASSERT_EQ(one.size(), 4000u);
    ASSERT_EQ(two.size(), one.size());
    EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(SurfaceSample)));
    // On the surface, inside the ball, normals outward; area-uniform: half the samples lie within the
    // spherical cap of half the ball's cap area (cap area is linear in height on a sphere).
    const float h_full = 0.125f;  // ball radius 0.5 around the pole cuts the unit sphere at y = 1 - 0.5^2/2
    int upper = 0;
    for (const SurfaceSample& s : one) {
        EXPECT_LE(distance(s.position, center), 0.5f + 1e-5f);
        EXPECT_NEAR(length(s.position), 1.0f, 0.01f);
        EXPECT_GT(dot(s.normal, normalize(s.position)), 0.99f);
        upper += s.position.y > 1.0f - h_full * 0.5f;
    }
    EXPECT_NEAR(double(upper) / one.size(), 0.5, 0.04);
    EXPECT_TRUE(field.sample_ball(float3(5, 5, 5), 0.1f, 10, 1).empty());
}

// meshToVolume starts during the repair (on another thread when there is one): before CGAL's
// orientation when the soup needs it, and again when an enclosed shell is then removed (here: one
// face wound the wrong way, and an eye inside, so the first band is cancelled and restarted).
// Either way the field must not depend on the thread count (to the bit), and the eye and the
// flipped face, both repaired, must change nothing (to float rounding).
TEST(ScalpField, BuildIsThreadIndependentWithOrWithoutTheEarlyBand)
{
    const PolygonSoup clean = icosphere({0, 0, 0}, 1.0f, 4);
    PolygonSoup with_eye = clean;
    std::swap(with_eye.face_indices[with_eye.face_offsets[7] + 1], with_eye.face_indices[with_eye.face_offsets[7] + 2]);
    const PolygonSoup eye = icosphere({0.3f, 0.2f, 0.1f}, 0.2f, 2);
    const int32_t base = int32_t(with_eye.points.size());
    with_eye.points.insert(with_eye.points.end(), eye.points.begin(), eye.points.end());
    for (size_t f = 0; f < eye.num_faces(); ++f) {
        const auto idx = eye.face(f);
        const std::array<int32_t, 3> shifted{idx[0] + base, idx[1] + base, idx[2] + base};
        with_eye.add_face(shifted);
    }
    std::vector<float3> probes;
    for (uint64_t i = 0; i < 2000; ++i) {
        Rng rng(12, i);
        probes.push_back(random_direction(rng) * rng.uniform(0.9f, 1.1f));
    }
    auto answers = [&](const PolygonSoup& soup, int threads) {
        ThreadLimit limit(threads);
        RepairReport report;
        const ScalpField field = build_scalp(soup, {0.02f, 3.0f}, &report);
        std::vector<float> out;
        for (const float3& p : probes) {
            float3 n, c;
            out.push_back(field.query(p, n, c));
            out.insert(out.end(), {n.x, n.y, n.z, c.x, c.y, c.z});
        }
        EXPECT_EQ(report.faces_flipped, &soup == &clean ? 0 : 1);
        return std::make_pair(out, report.enclosed_shells_removed);
    };
    const auto [clean1, removed_clean] = answers(clean, 1);
    const auto [clean2, unused] = answers(clean, 2);
    const auto [eye1, removed_eye] = answers(with_eye, 1);
    const auto [eye2, unused2] = answers(with_eye, 2);
    EXPECT_EQ(removed_clean, 0);
    EXPECT_EQ(removed_eye, 1);
    EXPECT_EQ(clean1, clean2);
    EXPECT_EQ(eye1, eye2);
    // The turned face lists its corners in another order than the clean one: the same answers to
    // float rounding (1e-5 of the radius), not to the bit.
    ASSERT_EQ(clean1.size(), eye1.size());
    for (size_t i = 0; i < clean1.size(); ++i) ASSERT_NEAR(clean1[i], eye1[i], 1e-5f) << "an enclosed eye, removed, and a flipped face, turned, must change nothing";
}

TEST(ScalpField, VdbRoundTripGivesTheSameField)
{
    test::TempDir dir;
    const ScalpField built = build_scalp(icosphere({0, 0, 0}, 1.0f, 4), {0.02f, 3.0f});
    write_scalp(built, dir.file("s.vdb"));
    const std::shared_ptr<const ScalpField> loaded = load_scalp(dir.file("s.vdb"));
    // The file carries the repaired mesh (grid metadata groom_source_mesh): the same answers everywhere.
    EXPECT_TRUE(loaded->has_source_mesh());
    EXPECT_FLOAT_EQ(loaded->voxel_size(), 0.02f);
    for (int i = 0; i < 500; ++i) {
        Rng rng(3, uint64_t(i));
        const float3 dir = random_direction(rng);
        const float3 near = dir * (1.0f + rng.uniform(-0.03f, 0.03f));
        EXPECT_FLOAT_EQ(loaded->distance(near), built.distance(near));
        const float3 far = dir * rng.uniform(1.2f, 3.0f);
        EXPECT_EQ(loaded->distance(far), built.distance(far));
    }
}

TEST(ScalpField, RejectsBadInput)
{
    PolygonSoup empty;
    EXPECT_THROW(build_scalp(empty), InvalidGeometry);
    PolygonSoup nan = icosphere({0, 0, 0}, 1, 1);
    nan.points[3].y = NAN;
    EXPECT_THROW(build_scalp(nan), InvalidGeometry);
    PolygonSoup range = icosphere({0, 0, 0}, 1, 1);
    range.face_indices[5] = 999;
    EXPECT_THROW(build_scalp(range), InvalidGeometry);
    EXPECT_THROW(build_scalp(icosphere({0, 0, 0}, 1, 1), {-1.0f, 3.0f}), InvalidParam);
    EXPECT_THROW(build_scalp(icosphere({0, 0, 0}, 1, 1), {0.1f, 0.5f}), InvalidParam);
    ScalpBuildParams huge{1e-5f, 3.0f};
    try {
        build_scalp(icosphere({0, 0, 0}, 1, 1), huge);
        FAIL() << "expected LimitExceeded";
    }
    catch (const LimitExceeded& e) {
        EXPECT_NE(std::string(e.what()).find("use `voxel`"), std::string::npos) << e.what();
    }
}

TEST(ScalpField, NonFiniteQueryPointIsAnErrorNotASignal)
{
    // Exact queries outside the band convert the point to GMP rationals, which raise SIGFPE on inf
    // and NaN: an op whose arithmetic overflowed (braid --width 3e38) died of it.
    const ScalpField field = build_scalp(icosphere({0, 0, 0}, 10, 2), {1.0f, 3.0f});
    for (const float bad : {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
        EXPECT_THROW(field.distance(float3(bad, 0, 0)), InvalidGeometry);
        float3 n, c;
        EXPECT_THROW(field.query(float3(0, -bad, 1), n, c), InvalidGeometry);
    }
    // Far but finite points are answered.
    EXPECT_NEAR(field.distance(float3(1e15f, 0, 0)), 1e15f, 1e9f);
}

TEST(ScalpField, MeshWhoseSizeOverflowsFloatIsRefused)
{
    PolygonSoup huge = icosphere({0, 0, 0}, 1e30f, 2);
    ScalpBuildParams p;
    p.source = "huge.obj";
    try {
        build_scalp(huge, p);
        FAIL() << "no error";
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("huge.obj: the mesh is"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("scale it down"), std::string::npos) << e.what();
    }
    PolygonSoup far = icosphere({1e12f, 0, 0}, 10, 2);
    EXPECT_THROW(build_scalp(far, p), InvalidGeometry);
    // The same sphere near the origin, and far with a voxel float can still resolve there, convert.
    EXPECT_NO_THROW(build_scalp(icosphere({1e5f, 0, 0}, 10, 2), p));
}

TEST(ScalpReal, SintelColliderMatchesIndependentSdf)
{
    GROOM_REQUIRE_SHARED(obj, "sintel_frostbitten/sintel-collider.obj");
    GROOM_REQUIRE_SHARED(bin, "sintel_frostbitten/sintel-sdf.bin");
    std::ifstream in(bin, std::ios::binary);
    uint64_t n = 0;
    float lo[3], hi[3];
    in.read(reinterpret_cast<char*>(&n), 8);
    in.read(reinterpret_cast<char*>(lo), 12);
    in.read(reinterpret_cast<char*>(hi), 12);
    ASSERT_TRUE(in && n > 0 && n <= 512);
    std::vector<float> ref(n * n * n);
    in.read(reinterpret_cast<char*>(ref.data()), std::streamsize(ref.size() * 4));
    ASSERT_TRUE(in);
    const ScalpField field = build_scalp(read_mesh(obj));
    const float h = field.voxel_size();
    double worst = 0, sum = 0;
    int64_t count = 0, sign_errors = 0;
    for (uint64_t k = 0; k < n; ++k)
        for (uint64_t j = 0; j < n; ++j)
            for (uint64_t i = 0; i < n; ++i) {
                const float3 p(lo[0] + (float(i) + 0.5f) * (hi[0] - lo[0]) / float(n), lo[1] + (float(j) + 0.5f) * (hi[1] - lo[1]) / float(n),
                               lo[2] + (float(k) + 0.5f) * (hi[2] - lo[2]) / float(n));
                const float r = ref[(k * n + j) * n + i];
                const float d = field.distance(p);
                const double e = std::fabs(double(d) - double(r));
                worst = std::max(worst, e);
                sum += e;
                ++count;
                sign_errors += (std::fabs(r) > h) && ((d < 0) != (r < 0));
            }
    // The reference is an exact distance sampled at cell centres; ours is trilinear in the band
    // (error ~ h^2 / curvature radius) and exact outside it.
    EXPECT_EQ(sign_errors, 0);
    EXPECT_LT(worst, 0.25 * h) << "mean " << sum / double(count) << " h " << h;
}

TEST(ScalpReal, EveryHeadConverts)
{
    const char* heads[] = {"amd_tressfx_ponytail/ponytail_head.obj", "demosthenes_scan/demosthenes-low-res.obj",
                           "ict_facekit/generic_neutral_mesh.obj",   "lee_perry_smith/LeePerrySmith.obj",
                           "makehuman/base.obj",                      "nefertiti_scan/nefertiti-lowres.obj",
                           "ratboy_mohawk_tressfx/Ratboy_body.obj",   "sintel_frostbitten/sintel.obj"};
    GROOM_REQUIRE_SHARED(first, heads[0]);
    for (const char* head : heads) {
        SCOPED_TRACE(head);
        const std::string path = test::shared_file(head);
        const PolygonSoup soup = read_mesh(path);
        Bounds3 box;
        for (const float3& p : soup.points) box.extend(p);
        RepairReport report;
        // Coarse voxels keep the test quick; the conversion path is the same at any size.
        const ScalpField field = build_scalp(soup, {length(box.size()) / 96.0f, 3.0f}, &report);
        EXPECT_GT(field.num_faces(), soup.num_faces() / 2);
        // Well above the top of the head (+Y up in every file) is outside, by about the gap.
        const float3 above = float3(box.center().x, box.hi.y, box.center().z) + float3(0, 0.5f * box.size().y, 0);
        EXPECT_GT(field.distance(above), 0.4f * box.size().y);
    }
}

TEST(ScalpReal, NoHeadIsRefusedForItsAutomaticVoxel)
{
    // The automatic voxel is refused when the head (the largest shell) spans fewer than 64 of them
    // (a stray part far away; tests/cli ScalpCli.AutomaticVoxelMadeCoarseByAStrayPartIsRefusedNamingIt).
    // No real head may be: each converts at its default, at the voxel of its own diagonal / 256,
    // and its largest shell spans at least 200 voxels (measured: 212 for the ponytail head, whose
    // jacket and hair bands reach past the head; 251 to 256 for the others).
    const char* heads[] = {"amd_tressfx_ponytail/ponytail_head.obj", "demosthenes_scan/demosthenes-low-res.obj",
                           "ict_facekit/generic_neutral_mesh.obj",   "lee_perry_smith/LeePerrySmith.obj",
                           "makehuman/base.obj",                      "nefertiti_scan/nefertiti-lowres.obj",
                           "ratboy_mohawk_tressfx/Ratboy_body.obj",   "sintel_frostbitten/sintel.obj",
                           "sintel_frostbitten/sintel-collider.obj",  "sintel_tressfx_opengl/sintel.obj"};
    GROOM_REQUIRE_SHARED(first, heads[0]);
    for (const char* head : heads) {
        SCOPED_TRACE(head);
        RepairReport report;
        ScalpField field;
        ASSERT_NO_THROW(field = build_scalp(read_mesh(test::shared_file(head)), {}, &report));
        Bounds3 box;
        for (const RepairReport::Shell& s : report.shell_list) {
            if (s.removed) continue;
            box.extend(float3(s.lo[0], s.lo[1], s.lo[2]));
            box.extend(float3(s.hi[0], s.hi[1], s.hi[2]));
        }
        EXPECT_NEAR(field.voxel_size(), length(box.size()) / 256.0f, 1e-3f * field.voxel_size());
        const RepairReport::Shell* largest = nullptr;
        for (const RepairReport::Shell& s : report.shell_list)
            if (!s.removed && !largest) largest = &s;
        ASSERT_NE(largest, nullptr);
        const float3 size(largest->hi[0] - largest->lo[0], largest->hi[1] - largest->lo[1], largest->hi[2] - largest->lo[2]);
        EXPECT_GT(length(size) / field.voxel_size(), 200.0f);
    }
}

}  // namespace
}  // namespace groom
