#include "ops/generate.h"

#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"
#include "ops/sphere_cap_sampler.h"
#include "support/sphere_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numeric>
#include <set>

using namespace groom;

namespace {

const float3 kC(0, 0, 0);
constexpr float kR = 10.0f;

/// The sphere point in direction (polar angle theta from +Y, azimuth phi), radians.
float3 on_sphere(double theta, double phi)
{
    return kC + float3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi))) * kR;
}

/// A guide rooted at `root` on the sphere: out along the normal, bending towards `lean` (a
/// direction), `length` long in `n` points.
void add_guide(std::vector<std::vector<float3>>& g, const float3& root, const float3& lean, float length, int n)
{
    const float3 nr = normalize(root - kC);
    const float3 t = normalize(lean - nr * dot(lean, nr));
    std::vector<float3> pts(n);
    for (int i = 0; i < n; ++i) {
        const float s = length * float(i) / float(n - 1);
        pts[i] = root + nr * s + t * (0.3f * s * s / length);
    }
    g.push_back(pts);
}

CurveSet to_curves(const std::vector<std::vector<float3>>& g)
{
    std::vector<int64_t> counts;
    for (const auto& c : g) counts.push_back(int64_t(c.size()));
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    size_t k = 0;
    for (const auto& c : g)
        for (const float3& p : c) P[k++] = p;
    return cs;
}

/// Five guides around the north pole of the test sphere, leaning different ways.
CurveSet pole_guides(int points = 12)
{
    std::vector<std::vector<float3>> g;
    add_guide(g, on_sphere(0.0, 0.0), float3(1, 0, 0), 4.0f, points);
    for (int k = 0; k < 4; ++k) {
        const double phi = k * 1.5707963267948966;
        add_guide(g, on_sphere(0.25, phi), float3(float(std::cos(phi)), 0, float(std::sin(phi))), 3.0f + k, points);
    }
    return to_curves(g);
}

std::span<const float3> curve(const CurveSet& cs, size_t c)
{
    const IndexRange r = cs.points_of(c);
    return cs.positions().subspan(r.begin, r.size());
}

}  // namespace

TEST(Generate, RootOnGuideRootReproducesGuideExactly)
{
    const AnalyticSphere head(kC, kR);
    const CurveSet guides = pole_guides();
    const std::vector<float3> roots{curve(guides, 2)[0], curve(guides, 4)[0], on_sphere(0.1, 0.3)};
    GenerateParams params;
    const CurveSet out = generate_at_roots(guides, head, roots, {}, params);
    ASSERT_EQ(out.num_curves(), 3u);
    for (int k = 0; k < 2; ++k) {
        const auto want = curve(guides, k == 0 ? 2 : 4), got = curve(out, k);
        ASSERT_EQ(got.size(), want.size());
        EXPECT_EQ(std::memcmp(got.data(), want.data(), want.size_bytes()), 0) << "curve " << k;
    }
    // With another point count the guide is resampled first: the copy is of the resampled guide.
    params.points = 20;
    const CurveSet out20 = generate_at_roots(guides, head, roots, {}, params);
    const std::vector<float3> want = resample_by_count(curve(guides, 4), 20);
    const auto got = curve(out20, 1);
    ASSERT_EQ(got.size(), 20u);
    EXPECT_EQ(std::memcmp(got.data(), want.data(), got.size_bytes()), 0);
}

TEST(Generate, ShapeFollowsScalpNormal)
{
    // One straight guide along the pole's normal: every root must grow straight along its own normal.
    const AnalyticSphere head(kC, kR);
    std::vector<std::vector<float3>> g(1);
    for (int i = 0; i < 8; ++i) g[0].push_back(on_sphere(0, 0) * (1.0f + 0.3f * float(i) / 7.0f));
    const CurveSet guides = to_curves(g);
    std::vector<float3> roots;
    for (int k = 0; k < 12; ++k) roots.push_back(on_sphere(0.05 + 0.06 * k, 0.5 * k));
    GenerateParams params;
    params.neighbours = 1;
    const CurveSet out = generate_at_roots(guides, head, roots, {}, params);
    for (size_t c = 0; c < roots.size(); ++c) {
        const float3 n = normalize(roots[c] - kC);
        const auto pts = curve(out, c);
        for (int i = 0; i < 8; ++i) {
            const float3 want = roots[c] + n * (3.0f * float(i) / 7.0f);
            EXPECT_LT(distance(pts[i], want), 1e-5f * kR) << "curve " << c << " point " << i;
        }
    }
}

TEST(Generate, InverseDistanceWeightsBlendShapes)
{
    // Straight guides on a plane, heights 1, 3 and 5: the tip height is the documented weighted mean.
    const AnalyticPlane ground(float3(0, 0, 0), float3(0, 1, 0));
    std::vector<std::vector<float3>> g;
    const float xs[3] = {0, 4, 10}, hs[3] = {1, 3, 5};
    for (int k = 0; k < 3; ++k) g.push_back({float3(xs[k], 0, 0), float3(xs[k], hs[k] * 0.5f, 0), float3(xs[k], hs[k], 0)});
    const CurveSet guides = to_curves(g);
    const std::vector<float3> roots{float3(1, 0, 0)};
    GenerateParams params;
    params.neighbours = 2;
    // Franke-Little: w = ((d3 - d) / (d3 d))^2 with d3 = 9 the third guide's distance.
    const double wa = std::pow((9.0 - 1.0) / 9.0, 2), wb = std::pow((9.0 - 3.0) / 27.0, 2);
    EXPECT_NEAR(curve(generate_at_roots(guides, ground, roots, {}, params), 0)[2].y, (wa * 1 + wb * 3) / (wa + wb), 1e-5);
    // All guides in the blend: plain inverse distance, w = 1 / d^2.
    params.neighbours = 3;
    const double v[3] = {1.0, 1.0 / 9.0, 1.0 / 81.0};
    EXPECT_NEAR(curve(generate_at_roots(guides, ground, roots, {}, params), 0)[2].y,
                (v[0] * 1 + v[1] * 3 + v[2] * 5) / (v[0] + v[1] + v[2]), 1e-5);
    EXPECT_EQ(curve(generate_at_roots(guides, ground, roots, {}, params), 0)[2].x, 1.0f);  // straight up
}

TEST(Generate, ShapesVaryContinuouslyAsNeighboursChange)
{
    // Guides on a line; at x = 1.5 the third-nearest guide switches from 0 to 3 (a tie). Plain
    // inverse distance over the 3 nearest would jump by about 0.2 there; the blend must not.
    const AnalyticPlane ground(float3(0, 0, 0), float3(0, 1, 0));
    std::vector<std::vector<float3>> g;
    const float hs[5] = {1, 2, 2, 5, 1};
    for (int k = 0; k < 5; ++k) g.push_back({float3(float(k), 0, 0), float3(float(k), hs[k], 0)});
    std::vector<float3> roots;
    for (int i = 0; i <= 3000; ++i) roots.push_back(float3(0.3f + 0.001f * float(i), 0, 0.01f));
    GenerateParams params;
    params.neighbours = 3;
    const CurveSet out = generate_at_roots(to_curves(g), ground, roots, {}, params);
    float worst = 0;
    for (size_t c = 1; c < roots.size(); ++c) worst = std::max(worst, std::fabs(curve(out, c)[1].y - curve(out, c - 1)[1].y));
    EXPECT_LT(worst, 0.02f);
}

TEST(Generate, RootsAreaUniformInsideRegion)
{
    const AnalyticSphere head(kC, kR);
    GenerateParams params;
    params.count = 20000;
    params.region_center = on_sphere(0, 0);
    params.region_radius = 4.0f;
    params.seed = 11;
    const CurveSet guides = pole_guides();
    const std::vector<SurfaceSample> roots = scatter_roots(guides, head, test::sphere_cap_sampler(kC, kR), params);
    ASSERT_EQ(roots.size(), 20000u);
    // The ball cuts the cap cos(theta) >= 1 - r^2 / (2 R^2).
    const double cos_max = 1.0 - 16.0 / 200.0;

    // Chi-square over 10 bands of equal area (equal steps of cos(theta)) and 8 equal sectors.
    auto chi2 = [](const std::vector<int>& bins, double expected) {
        double x = 0;
        for (int b : bins) x += (b - expected) * (b - expected) / expected;
        return x;
    };
    auto stats = [&](const std::vector<SurfaceSample>& pts, double& bands, double& sectors) {
        std::vector<int> band(10, 0), sector(8, 0);
        for (const SurfaceSample& s : pts) {
            const float3 p = s.position;
            const double z = double(p.y) / kR;
            band[std::min(9, int((1.0 - z) / (1.0 - cos_max) * 10.0))]++;
            const double phi = std::atan2(double(p.z), double(p.x)) + 3.141592653589793;
            sector[std::min(7, int(phi / 6.283185307179586 * 8.0))]++;
        }
        bands = chi2(band, pts.size() / 10.0);
        sectors = chi2(sector, pts.size() / 8.0);
    };
    for (const SurfaceSample& s : roots) {
        const float3 p = s.position;
        ASSERT_LE(distance(p, params.region_center), params.region_radius * (1 + 1e-6f));
        ASSERT_LT(std::fabs(head.distance(p)), 1e-5f * kR);
    }
    double bands, sectors;
    stats(roots, bands, sectors);
    EXPECT_LT(bands, 27.88);   // 9 degrees of freedom, p = 0.001
    EXPECT_LT(sectors, 24.32); // 7 degrees of freedom, p = 0.001

    // The test has power: roots uniform in polar angle (not in area) fail it.
    const RootSampler biased = [](const float3&, float, int64_t count, uint64_t seed) {
        std::vector<SurfaceSample> out;
        for (int64_t i = 0; i < count; ++i) {
            Rng rng(seed, uint64_t(i), 3);
            out.push_back({on_sphere(std::acos(1.0 - 16.0 / 200.0) * rng.uniform_double(), 6.283185307179586 * rng.uniform_double()), float3(0, 1, 0), -1});
        }
        return out;
    };
    stats(scatter_roots(guides, head, biased, params), bands, sectors);
    EXPECT_GT(bands, 27.88);

    // generate() grows its curves from exactly these roots.
    params.count = 500;
    const CurveSet out = generate(guides, head, test::sphere_cap_sampler(kC, kR), params);
    const std::vector<SurfaceSample> first = scatter_roots(guides, head, test::sphere_cap_sampler(kC, kR), params);
    for (size_t c = 0; c < out.num_curves(); ++c) ASSERT_EQ(curve(out, c)[0], first[c].position);
}

TEST(Generate, FootprintKeepsRootsNearGuides)
{
    const AnalyticSphere head(kC, kR);
    const CurveSet guides = pole_guides();
    GenerateParams params;
    params.count = 3000;
    std::vector<float3> groots;
    for (size_t g = 0; g < guides.num_curves(); ++g) groots.push_back(curve(guides, g)[0]);
    // The coarsest spacing: each outer guide's nearest is the pole guide, 2 R sin(0.125) away.
    const float D = 2.0f * kR * std::sin(0.125f);
    const std::vector<SurfaceSample> roots = scatter_roots(guides, head, test::sphere_cap_sampler(kC, kR, 1.0), params);
    float farthest = 0;
    for (const SurfaceSample& s : roots) {
        const float3 p = s.position;
        float nearest = INFINITY;
        for (const float3& r : groots) nearest = std::min(nearest, distance(p, r));
        ASSERT_LE(nearest, D * (1 + 1e-5f));
        farthest = std::max(farthest, nearest);
    }
    EXPECT_GT(farthest, 0.9f * D);  // the footprint is filled out to its edge
    params.footprint_scale = 0.5f;
    for (const SurfaceSample& s : scatter_roots(guides, head, test::sphere_cap_sampler(kC, kR, 1.0), params)) {
        const float3 p = s.position;
        float nearest = INFINITY;
        for (const float3& r : groots) nearest = std::min(nearest, distance(p, r));
        ASSERT_LE(nearest, 0.5f * D * (1 + 1e-5f));
    }
}

TEST(Generate, RootsFacingAwayFromTheGuidesAreNotUsed)
{
    // Guides around the pole; a region reaching 80 degrees down the sphere. Sphere normals are the
    // directions from the centre, so the angle to the nearest guide's normal is known exactly.
    const AnalyticSphere head(kC, kR);
    const CurveSet guides = pole_guides();
    GenerateParams params;
    params.count = 4000;
    params.region_center = on_sphere(0, 0);
    params.region_radius = 2.0f * kR * std::sin(0.5f * 80.0f * 3.14159265f / 180.0f);
    auto worst = [&](float max_angle) {
        params.max_angle = max_angle;
        float widest = 0;
        for (const SurfaceSample& s : scatter_roots(guides, head, test::sphere_cap_sampler(kC, kR, 1.0), params)) {
            size_t nearest = 0;  // by root distance, as the op decides
            for (size_t g = 1; g < guides.num_curves(); ++g)
                if (distance(s.position, curve(guides, g)[0]) < distance(s.position, curve(guides, nearest)[0])) nearest = g;
            const float best = dot(normalize(s.position), normalize(curve(guides, nearest)[0]));
            widest = std::max(widest, std::acos(std::clamp(best, -1.0f, 1.0f)) * 180.0f / 3.14159265f);
        }
        return widest;
    };
    EXPECT_LE(worst(30.0f), 30.0f + 1e-3f);
    EXPECT_GT(worst(30.0f), 25.0f);   // the allowed band is filled
    EXPECT_GT(worst(180.0f), 60.0f);  // without the limit roots reach the region's rim
}

TEST(Generate, NoPointInsideScalp)
{
    // Guides that dive back into the head: generated points must be pushed out.
    const AnalyticSphere head(kC, kR);
    std::vector<std::vector<float3>> g;
    for (int k = 0; k < 4; ++k) {
        const float3 root = on_sphere(0.2, k * 1.5707963);
        const float3 n = normalize(root), t = any_perpendicular(n);
        std::vector<float3> pts;
        for (int i = 0; i < 10; ++i) {
            const float s = 0.5f * float(i);
            pts.push_back(root + t * s + n * (0.3f * s - 0.2f * s * s));
        }
        g.push_back(pts);
    }
    GenerateParams params;
    params.count = 400;
    params.region_center = on_sphere(0, 0);
    params.region_radius = 3.0f;
    const CurveSet out = generate(to_curves(g), head, test::sphere_cap_sampler(kC, kR), params);
    const auto P = out.positions();
    for (const float3& p : P) ASSERT_GE(head.distance(p), -1e-5f * kR);
    params.clearance = 0.25f;
    const CurveSet clear = generate(to_curves(g), head, test::sphere_cap_sampler(kC, kR), params);
    for (size_t c = 0; c < clear.num_curves(); ++c) {
        const auto pts = curve(clear, c);
        EXPECT_LT(std::fabs(head.distance(pts[0])), 1e-5f * kR);  // roots stay on the scalp
        for (size_t i = 1; i < pts.size(); ++i) ASSERT_GE(head.distance(pts[i]), 0.25f - 1e-5f * kR);
    }
}

// The same on a level-set scalp, read by the field itself: one step along its interpolated normal
// lands within about a tenth of a voxel of its surface, either side, so a moved point is checked
// again and moved again with a doubled margin. (On Sintel one step left 5,500 of 640,000 points
// reading up to 0.2 units, a voxel, inside.)
TEST(Generate, NoPointInsideALevelSetScalp)
{
    const ScalpField head = build_scalp(icosphere(kC, kR, 4), {kR / 40.0f, 3.0f});
    std::vector<std::vector<float3>> g;
    for (int k = 0; k < 4; ++k) {
        const float3 root = head.closest_point(on_sphere(0.2, k * 1.5707963));
        const float3 n = normalize(root), t = any_perpendicular(n);
        std::vector<float3> pts;
        for (int i = 0; i < 10; ++i) {
            const float s = 0.5f * float(i);
            pts.push_back(root + t * s + n * (0.3f * s - 0.2f * s * s));
        }
        g.push_back(pts);
    }
    GenerateParams params;
    params.count = 400;
    params.region_center = on_sphere(0, 0);
    params.region_radius = 3.0f;
    const CurveSet out = generate(to_curves(g), head, scalp_root_sampler(head), params);
    int64_t moved = 0;
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const auto pts = curve(out, c);
        for (size_t i = 1; i < pts.size(); ++i) {
            ASSERT_GE(head.distance(pts[i]), 0.0f) << c << " " << i;
            moved += head.distance(pts[i]) < 1e-3f * kR;
        }
    }
    EXPECT_GT(moved, 400);  // the guides dive in: most hairs had points to move
}

TEST(Generate, CarriesAttributesAndAssignsUniqueIds)
{
    const AnalyticSphere head(kC, kR);
    CurveSet guides = pole_guides();
    auto clump = guides.add<float>(Domain::Curve, "clump");
    auto gid = guides.add<int64_t>(Domain::Curve, attr::id);
    auto width = guides.add<float>(Domain::Point, attr::width);
    for (size_t g = 0; g < guides.num_curves(); ++g) {
        clump[g] = 10.0f * float(g);
        gid[g] = 100 + int64_t(g);
    }
    for (size_t p = 0; p < guides.num_points(); ++p) width[p] = float(p % 12);
    guides.set_detail_string("source", "pole");
    GenerateParams params;
    params.count = 300;
    params.first_id = 1000;
    params.region_center = on_sphere(0, 0);
    params.region_radius = 5.0f;
    const CurveSet out = generate(guides, head, test::sphere_cap_sampler(kC, kR), params);
    const auto ids = out.find<int64_t>(Domain::Curve, attr::id);
    const auto near = out.find<int32_t>(Domain::Curve, "guide");
    const auto oclump = out.find<float>(Domain::Curve, "clump");
    const auto owidth = out.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(ids.size(), 300u);
    ASSERT_EQ(near.size(), 300u);
    ASSERT_EQ(oclump.size(), 300u);
    ASSERT_EQ(owidth.size(), out.num_points());
    EXPECT_EQ(out.detail_string("source"), "pole");
    EXPECT_EQ(std::set<int64_t>(ids.begin(), ids.end()).size(), 300u);
    for (size_t c = 0; c < 300; ++c) {
        EXPECT_EQ(ids[c], 1000 + int64_t(c));
        const float3 root = curve(out, c)[0];
        int best = 0;
        for (int g = 1; g < 5; ++g)
            if (distance(root, curve(guides, g)[0]) < distance(root, curve(guides, best)[0])) best = g;
        EXPECT_EQ(near[c], best);
        EXPECT_EQ(oclump[c], 10.0f * float(best));
        for (int64_t i = 0; i < out.points_in(c); ++i) EXPECT_EQ(owidth[out.points_of(c).begin + i], float(i));
    }
    EXPECT_NO_THROW(out.validate());
}

TEST(Generate, DeterministicAcrossThreadCounts)
{
    const AnalyticSphere head(kC, kR);
    GenerateParams params;
    params.count = 5000;
    params.points = 16;
    params.seed = 5;
    auto run = [&](int threads) {
        ThreadLimit limit(threads);
        return generate(pole_guides(), head, test::sphere_cap_sampler(kC, kR), params);
    };
    const CurveSet a = run(1), b = run(2);
    ASSERT_EQ(a.num_points(), b.num_points());
    EXPECT_EQ(std::memcmp(a.positions().data(), b.positions().data(), a.positions().size_bytes()), 0);
    const auto ia = a.find<int64_t>(Domain::Curve, attr::id), ib = b.find<int64_t>(Domain::Curve, attr::id);
    EXPECT_TRUE(std::equal(ia.begin(), ia.end(), ib.begin()));
    // Another seed gives other roots.
    params.seed = 6;
    const CurveSet c = run(2);
    EXPECT_NE(std::memcmp(a.positions().data(), c.positions().data(), a.positions().size_bytes()), 0);
}

// Grown a block at a time (groom generate into .hair never holds its whole output), the blocks laid
// end to end are generate()'s output, every column bit for bit, for any cut, a shard's range too.
TEST(Generate, BlocksEndToEndAreTheWholeGroom)
{
    const AnalyticSphere head(kC, kR);
    CurveSet guides = pole_guides();
    auto clump = guides.add<float>(Domain::Curve, "clump");
    for (size_t g = 0; g < guides.num_curves(); ++g) clump[g] = 10.0f * float(g);
    GenerateParams params;
    params.count = 700;
    params.points = 12;
    params.seed = 3;
    params.clearance = 0.05f;
    for (const int64_t begin : {int64_t(0), int64_t(150)}) {
        params.range_begin = begin;
        params.range_end = begin == 0 ? -1 : 610;
        const CurveSet whole = generate(guides, head, test::sphere_cap_sampler(kC, kR), params);
        for (const int64_t block_points : {int64_t(1), int64_t(1000), int64_t(1) << 40}) {
            SCOPED_TRACE("range from " + std::to_string(begin) + ", block_points " + std::to_string(block_points));
            std::vector<int64_t> announced;
            std::vector<CurveSet> blocks;
            generate_blocks(
                guides, head, test::sphere_cap_sampler(kC, kR), params, nullptr, block_points,
                [&](std::span<const int64_t> counts) { announced.assign(counts.begin(), counts.end()); },
                [&](const CurveSet& b) { blocks.push_back(b); });
            ASSERT_EQ(announced.size(), whole.num_curves());
            if (block_points == 1) EXPECT_EQ(blocks.size(), whole.num_curves());
            if (block_points == 1000) EXPECT_EQ(blocks.size(), (whole.num_curves() * 12 + 1007) / 1008);
            size_t curve = 0, point = 0;
            for (const CurveSet& b : blocks) {
                for (size_t c = 0; c < b.num_curves(); ++c, ++curve) {
                    ASSERT_EQ(b.points_in(c), whole.points_in(curve));
                    EXPECT_EQ(announced[curve], whole.points_in(curve));
                    EXPECT_EQ(b.find<int64_t>(Domain::Curve, attr::id)[c], whole.find<int64_t>(Domain::Curve, attr::id)[curve]);
                    EXPECT_EQ(b.find<int32_t>(Domain::Curve, "guide")[c], whole.find<int32_t>(Domain::Curve, "guide")[curve]);
                    EXPECT_EQ(b.find<float>(Domain::Curve, "clump")[c], whole.find<float>(Domain::Curve, "clump")[curve]);
                }
                const size_t n = b.num_points();
                EXPECT_EQ(std::memcmp(b.positions().data(), whole.positions().data() + point, n * sizeof(float3)), 0);
                EXPECT_EQ(std::memcmp(b.find<float>(Domain::Point, attr::width).data(), whole.find<float>(Domain::Point, attr::width).data() + point,
                                      n * sizeof(float)), 0);
                point += n;
            }
            EXPECT_EQ(curve, whole.num_curves());
            EXPECT_EQ(point, whole.num_points());
        }
    }
}

TEST(Generate, RejectsInvalidParams)
{
    auto message = [](const GenerateParams& p) {
        try {
            p.validate();
        }
        catch (const InvalidParam& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    GenerateParams p;
    p.count = 0;
    EXPECT_NE(message(p).find("`count` must be >= 1 (got 0)"), std::string::npos) << message(p);
    p = {};
    p.neighbours = 0;
    EXPECT_NE(message(p).find("`neighbours` must be >= 1 (got 0)"), std::string::npos) << message(p);
    p = {};
    p.power = -1;
    EXPECT_NE(message(p).find("`power`"), std::string::npos) << message(p);
    p = {};
    p.points = 1;
    EXPECT_NE(message(p).find("`points` must be >= 2"), std::string::npos) << message(p);
    p = {};
    p.region_radius = NAN;
    EXPECT_NE(message(p).find("`region`"), std::string::npos) << message(p);
    p = {};
    p.footprint_scale = 0;
    EXPECT_NE(message(p).find("`footprint_scale`"), std::string::npos) << message(p);
    p = {};
    p.max_angle = 0;
    EXPECT_NE(message(p).find("`max_angle` must be in (0, 180]"), std::string::npos) << message(p);
    p = {};
    p.clearance = -1;
    EXPECT_NE(message(p).find("`clearance`"), std::string::npos) << message(p);
    p.clearance = 1e20f;  // reached the scalp queries as "a non-finite point", the option unnamed (a trial)
    EXPECT_NE(message(p).find("`clearance` must be in [0, 1e15] scene units (got 1e+20)"), std::string::npos) << message(p);
    p = {};
    p.first_id = -2;
    EXPECT_NE(message(p).find("`first_id`"), std::string::npos) << message(p);

    // Input problems: one guide has no footprint; a one-point guide; no guides.
    const AnalyticSphere head(kC, kR);
    std::vector<std::vector<float3>> one;
    add_guide(one, on_sphere(0, 0), float3(1, 0, 0), 2.0f, 4);
    EXPECT_THROW(scatter_roots(to_curves(one), head, test::sphere_cap_sampler(kC, kR), {}), InvalidParam);
    one.push_back({on_sphere(0.1, 0)});
    const std::vector<float3> roots{on_sphere(0, 0)};
    EXPECT_THROW(generate_at_roots(to_curves(one), head, roots, {}, {}), InvalidGeometry);
    EXPECT_THROW(generate_at_roots(CurveSet(), head, roots, {}, {}), InvalidParam);
}

TEST(Generate, RegionOffTheScalpIsRefused)
{
    const AnalyticSphere head(kC, kR);
    GenerateParams params;
    params.count = 10;
    params.region_center = float3(0, 50, 0);
    params.region_radius = 1.0f;
    try {
        scatter_roots(pole_guides(), head, test::sphere_cap_sampler(kC, kR), params);
        FAIL() << "expected LimitExceeded";
    }
    catch (const LimitExceeded& e) {
        EXPECT_NE(std::string(e.what()).find("`region`"), std::string::npos) << e.what();
    }
}

// Guides in other units or place than the scalp (a trial's in cm on a body in metres): no root is
// found around them, and the message says where the guides are rather than point at `max_angle`.
TEST(Generate, GuidesFarFromTheScalpAreNamedAsSuch)
{
    const AnalyticSphere head(kC, kR);
    CurveSet far = pole_guides();
    for (float3& p : far.positions_for_write()) p = p * 100.0f;  // the sphere's guides, 100 times too big
    GenerateParams params;
    params.count = 10;
    try {
        scatter_roots(far, head, test::sphere_cap_sampler(kC, kR), params);
        FAIL() << "expected LimitExceeded";
    }
    catch (const LimitExceeded& e) {
        EXPECT_NE(std::string(e.what()).find("the guides' roots lie a median"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("same units"), std::string::npos) << e.what();
    }
}

TEST(Generate, RootsOnlyInsideTheHairlineAndOffThePartings)
{
    // A level circular hairline 0.95 R up the sphere and a parting along the x = 0 great circle: the
    // region around the pole guides is cut to the cap above the circle, less a bare line.
    const AnalyticSphere head(kC, kR);
    const float y0 = 0.95f * kR, r0 = std::sqrt(kR * kR - y0 * y0);
    CurveSet hairline = CurveSet::from_counts(std::vector<int64_t>{256});
    auto H = hairline.positions_for_write();
    for (int i = 0; i < 256; ++i) H[i] = {r0 * std::cos(6.2831853f * i / 256), y0, r0 * std::sin(6.2831853f * i / 256)};
    CurveSet parting = CurveSet::from_counts(std::vector<int64_t>{101});
    auto Q = parting.positions_for_write();
    for (int i = 0; i <= 100; ++i) Q[i] = float3(0, std::cos(-0.6f + 1.2f * i / 100), std::sin(-0.6f + 1.2f * i / 100)) * kR;
    HairRegionParams rp;
    rp.parting_gap = 0.2f;
    const HairRegion region(head, hairline, parting, rp);
    GenerateParams params;
    params.count = 2000;
    params.region_center = on_sphere(0, 0);
    params.region_radius = 4.0f;
    params.region = &region;
    const std::vector<SurfaceSample> roots = scatter_roots(pole_guides(), head, test::sphere_cap_sampler(kC, kR), params);
    ASSERT_EQ(roots.size(), 2000u);
    int near_line = 0;
    for (const SurfaceSample& s : roots) {
        EXPECT_GT(s.position.y, y0 - 1e-3f * kR);   // inside the hairline (closed form: the cap above its plane)
        EXPECT_GT(std::fabs(s.position.x), 0.1f - 1e-4f);  // off the bare line (half the gap)
        near_line += std::fabs(s.position.x) < 0.3f;
    }
    EXPECT_GT(near_line, 0);  // the gap is only as wide as asked
    // Without the region the same ball reaches below the hairline.
    params.region = nullptr;
    int below = 0;
    for (const SurfaceSample& s : scatter_roots(pole_guides(), head, test::sphere_cap_sampler(kC, kR), params)) below += s.position.y < y0;
    EXPECT_GT(below, 100);
}

TEST(Generate, ARangeIsThatSliceOfTheWholeRun)
{
    // A farm shard: hairs [b, e) of the roots, grown alone, equal the whole run's curves b..e-1 in
    // every point, id, guide and width (the clearance margin comes from all roots and guides, not
    // from the part), for a middle range, an empty one and one past the end.
    const AnalyticSphere head(kC, kR);
    GenerateParams params;
    params.count = 300;
    params.region_center = on_sphere(0, 0);
    params.region_radius = 4.0f;
    params.clearance = 0.05f;
    params.seed = 5;
    const CurveSet guides = pole_guides();
    const CurveSet whole = generate(guides, head, test::sphere_cap_sampler(kC, kR), params);
    ASSERT_EQ(whole.num_curves(), 300u);
    for (const auto& [b, e] : std::vector<std::pair<int64_t, int64_t>>{{75, 150}, {10, 10}, {290, 400}}) {
        GenerateParams part_params = params;
        part_params.range_begin = b;
        part_params.range_end = e;
        const CurveSet part = generate(guides, head, test::sphere_cap_sampler(kC, kR), part_params);
        const int64_t n = std::min<int64_t>(e, 300) - b;
        ASSERT_EQ(int64_t(part.num_curves()), n) << b << ".." << e;
        for (int64_t c = 0; c < n; ++c) {
            const auto a = curve(part, size_t(c)), w = curve(whole, size_t(b + c));
            ASSERT_EQ(a.size(), w.size());
            for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], w[i]) << "hair " << b + c << " point " << i;
            EXPECT_EQ(part.curve_ids()[size_t(c)], whole.curve_ids()[size_t(b + c)]);
            EXPECT_EQ(part.find<int32_t>(Domain::Curve, "guide")[size_t(c)], whole.find<int32_t>(Domain::Curve, "guide")[size_t(b + c)]);
            const IndexRange pr = part.points_of(size_t(c)), wr = whole.points_of(size_t(b + c));
            EXPECT_EQ(part.find<float>(Domain::Point, attr::width)[size_t(pr.begin)], whole.find<float>(Domain::Point, attr::width)[size_t(wr.begin)]);
        }
    }
}
