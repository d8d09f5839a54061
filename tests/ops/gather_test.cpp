// gather on an exact sphere with two puffs, a level hairline and a centre parting along a great
// circle: everything a person looks for, measured from the output (roots cover the haired cap, hair
// lies within its lift of the surface and never inside, no hair crosses the parting, every tip ends
// at its puff's sphere, bands sit on the hair around each base), and the same bytes for 1 or 2 threads.
#include "ops/gather.h"

#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/mesh_io.h"
#include "ops/hairline.h"
#include "test_support.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "ops/puff.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace groom;

namespace {

const float3 kC{0, 0, 0};
constexpr float kR = 8.0f;
constexpr float kPi = 3.14159265358979f;
constexpr float kHairlineY = -0.2f * kR;

/// Area-uniform samples over the whole sphere (the ScalpField sampler's radius <= 0 case).
RootSampler whole_sphere()
{
    return [](const float3&, float, int64_t count, uint64_t seed) {
        std::vector<SurfaceSample> out(static_cast<size_t>(count));
        for (int64_t i = 0; i < count; ++i) {
            Rng rng(seed, uint64_t(i), 5);
            const float z = 2 * rng.uniform() - 1, a = 2 * kPi * rng.uniform(), s = std::sqrt(std::max(0.0f, 1 - z * z));
            const float3 d = normalize(float3(s * std::cos(a), z, s * std::sin(a)));
            out[size_t(i)] = {kC + d * kR, d, -1};
        }
        return out;
    };
}

CurveSet level_hairline()
{
    const int n = 360;
    CurveSet h = CurveSet::from_counts(std::vector<int64_t>{n});
    const float r = std::sqrt(kR * kR - kHairlineY * kHairlineY);
    auto P = h.positions_for_write();
    for (int i = 0; i < n; ++i) P[i] = {r * std::cos(2 * kPi * i / n), kHairlineY, r * std::sin(2 * kPi * i / n)};
    return h;
}

/// The x = 0 great circle from below the hairline at the front, over the top, to below it at the back.
CurveSet centre_parting()
{
    const int n = 200;
    CurveSet p = CurveSet::from_counts(std::vector<int64_t>{n});
    auto P = p.positions_for_write();
    for (int i = 0; i < n; ++i) {
        const float a = -0.4f + (kPi + 0.8f) * i / (n - 1);
        P[i] = {0, kR * std::sin(a), kR * std::cos(a)};
    }
    return p;
}

PuffParams puff_params(float side)
{
    PuffParams p;
    p.center = kC + normalize(float3(0.6f * side, 0.8f, 0)) * kR;
    p.radius = 2.5f;
    p.sphere_center = p.center + normalize(float3(0.6f * side, 0.8f, 0)) * 6.0f;
    p.sphere_radius = 4.0f;
    p.rows = p.cols = 4;
    p.cap_angle = 140.0f;
    return p;
}

GatherPuff make_puff(const AnalyticSphere& head, float side)
{
    const PuffParams p = puff_params(side);
    GatherPuff g;
    g.guides = puff_guides(head, p);
    g.base = g.guides.find<float3>(Domain::Detail, "puff_base")[0];
    g.base_radius = g.guides.find<float>(Domain::Detail, "puff_radius")[0];
    g.sphere_center = g.guides.find<float3>(Domain::Detail, "puff_sphere_center")[0];
    g.sphere_radius = g.guides.find<float>(Domain::Detail, "puff_sphere_radius")[0];
    g.cap_angle = g.guides.find<float>(Domain::Detail, "puff_cap_angle")[0];
    return g;
}

/// Two puffs on the sphere, the level hairline and the centre parting, 0.3 of bare scalp each side.
struct TwoPuffs {
    AnalyticSphere head{kC, kR};
    std::vector<GatherPuff> puffs{make_puff(head, -1), make_puff(head, 1)};
    HairRegion region{head, level_hairline(), centre_parting(), [] {
                          HairRegionParams rp;
                          rp.parting_gap = 0.3f;
                          return rp;
                      }()};

    GatherResult grow(const GatherParams& params) const { return gather(head, whole_sphere(), puffs, region, params); }
};

GatherParams small_params()
{
    GatherParams p;
    p.hairs = 3000;
    p.hair_points = 12;
    p.curl.hair_type = "4a";
    p.curl.seed = 7;
    return p;
}

}  // namespace

TEST(Gather, PuffsCarryTheirBaseAndSphere)
{
    const AnalyticSphere head(kC, kR);
    const GatherPuff g = make_puff(head, 1);
    EXPECT_NEAR(distance(g.base, kC), kR, 1e-4f);  // on the scalp
    EXPECT_EQ(g.base_radius, 2.5f);
    EXPECT_EQ(g.sphere_radius, 4.0f);
    EXPECT_NEAR(distance(g.sphere_center, kC), kR + 6.0f, 1e-4f);
}

TEST(Gather, CoversTheHairedScalpFlatAndIntoThePuffs)
{
    const TwoPuffs scene;
    const std::vector<GatherPuff>& puffs = scene.puffs;
    const HairRegion& region = scene.region;
    const GatherParams params = small_params();
    const GatherResult r = scene.grow(params);
    ASSERT_EQ(r.hairs.num_curves(), size_t(params.hairs));
    EXPECT_EQ(r.roots_without_puff, 0);

    const auto P = r.hairs.positions();
    const auto flat = r.hairs.find<int32_t>(Domain::Point, "flat");
    const auto puff_of = r.hairs.find<int32_t>(Domain::Curve, "puff");
    const float reach = curl_reach(params.curl);
    std::vector<float3> flat_points;
    for (size_t c = 0; c < r.hairs.num_curves(); ++c) {
        const IndexRange pr = r.hairs.points_of(c);
        const float3 root = P[pr.begin];
        const GatherPuff& puff = puffs[puff_of[c]];
        // Roots: on the scalp, inside the hairline, off the parting, outside both bases, on their puff's side.
        ASSERT_NEAR(distance(root, kC), kR, 1e-4f) << c;
        EXPECT_GT(root.y, kHairlineY - 0.01f) << c;
        EXPECT_GT(std::fabs(root.x), 0.15f - 1e-3f) << c;
        for (const GatherPuff& g : puffs) EXPECT_GE(distance(root, g.base), g.base_radius) << c;
        EXPECT_GT(root.x * puff.base.x, 0.0f) << c;
        for (int64_t i = pr.begin; i < pr.end; ++i) {
            const float d = distance(P[i], kC) - kR;
            EXPECT_GE(d, -1e-4f) << c << " " << i;  // never inside
            EXPECT_GT(P[i].x * root.x, 0.0f) << c << " " << i;  // never across the parting
            if (flat[i]) {
                EXPECT_LE(d, params.lift + 1e-4f) << c << " " << i;  // lies on the scalp
                flat_points.push_back(P[i]);
            }
        }
        // The tip ends at the puff's sphere, within the curl's reach.
        EXPECT_LE(std::fabs(distance(P[pr.end - 1], puff.sphere_center) - puff.sphere_radius), reach + 1e-3f) << c;
    }

    // Coverage, as a person sees it: every haired point of the scalp has gathered hair within 0.8.
    Rng rng(11, 12);
    int asked = 0, covered = 0;
    while (asked < 1500) {
        const float z = 2 * rng.uniform() - 1, a = 2 * kPi * rng.uniform(), s = std::sqrt(1 - z * z);
        const float3 p = float3(s * std::cos(a), z, s * std::sin(a)) * kR;
        if (!region.haired(p)) continue;
        bool in_base = false;
        for (const GatherPuff& g : puffs) in_base = in_base || distance(p, g.base) < g.base_radius;
        if (in_base) continue;
        ++asked;
        for (const float3& q : flat_points) {
            if (distance(p, q) < 0.8f) {
                ++covered;
                break;
            }
        }
    }
    EXPECT_GE(covered, asked * 995 / 1000) << covered << " of " << asked;

    // Bands: around each base, outside it, on top of the flat hair.
    ASSERT_EQ(r.bands.num_curves(), size_t(2 * params.band_strands));
    const auto bpuff = r.bands.find<int32_t>(Domain::Curve, "puff");
    const auto BP = r.bands.positions();
    for (size_t c = 0; c < r.bands.num_curves(); ++c) {
        const GatherPuff& g = puffs[bpuff[c]];
        const IndexRange br = r.bands.points_of(c);
        EXPECT_EQ(BP[br.begin], BP[br.end - 1]);  // closed ring
        for (int64_t i = br.begin; i < br.end; ++i) {
            const float h = distance(BP[i], kC) - kR;
            EXPECT_GE(h, params.lift - 1e-4f);
            EXPECT_LE(h, params.lift + params.band_thickness + params.band_width + 1e-3f);
            EXPECT_GT(distance(BP[i], g.base), g.base_radius);
        }
    }
}

// A puff seen from the side: the gathered hair must fill the ball, not run as one sheet from the
// base's rim to the cap's rim. Each gathered hair enters at the rim; when every one followed the
// rim's guides, all their tips met the ball on one circle, the outermost guides' (and their bodies
// made a smooth cone under it with a sharp edge: the demo's Izzy). Read from the tips: where each
// lands on the cap, as the equal-area coordinate u = (1 - cos theta) / (1 - cos cap), against the
// puff's own hairs (rooted area-uniformly over the base, so spread as the guides allow).
TEST(Gather, GatheredHairFillsThePuffNotOneSheet)
{
    const TwoPuffs scene;
    const GatherParams params = small_params();
    const GatherResult r = scene.grow(params);

    PuffParams own_params = puff_params(1);
    own_params.hairs = 3000;
    own_params.hair_points = params.hair_points;
    own_params.curl = params.curl;
    const CurveSet own = puff(scene.head, whole_sphere(), own_params).hairs;

    const GatherPuff& g = scene.puffs[1];
    const float3 axis = normalize(g.sphere_center - g.base);
    const float cap = own_params.cap_angle * kPi / 180.0f;
    auto tips_u = [&](const CurveSet& cs, std::span<const int32_t> puff_of) {
        std::vector<float> u;
        const auto P = cs.positions();
        for (size_t c = 0; c < cs.num_curves(); ++c) {
            if (!puff_of.empty() && puff_of[c] != 1) continue;
            const float3 tip = P[cs.points_of(c).end - 1];
            u.push_back((1.0f - dot(normalize(tip - g.sphere_center), axis)) / (1.0f - std::cos(cap)));
        }
        std::sort(u.begin(), u.end());
        return u;
    };
    const std::vector<float> own_u = tips_u(own, {});
    const std::vector<float> gathered_u = tips_u(r.hairs, r.hairs.find<int32_t>(Domain::Curve, "puff"));
    ASSERT_GT(gathered_u.size(), 1000u);
    const float own_median = own_u[own_u.size() / 2];
    const size_t below = size_t(std::lower_bound(gathered_u.begin(), gathered_u.end(), own_median) - gathered_u.begin());
    // Half of the puff's own tips lie inside its median; all of the gathered ones on one outer circle
    // put none there.
    EXPECT_GE(below, gathered_u.size() * 30 / 100) << below << " of " << gathered_u.size()
                                                    << " gathered tips inside the median of the puff's own (u " << own_median << ")";
    // Nor a ring: no band of the cap a tenth of the own tips' spread wide holds more than a third of them.
    const float spread = own_u[own_u.size() * 95 / 100] - own_u[own_u.size() * 5 / 100];
    size_t most = 0;
    for (size_t a = 0, b = 0; a < gathered_u.size(); ++a) {
        while (b < gathered_u.size() && gathered_u[b] < gathered_u[a] + 0.1f * spread) ++b;
        most = std::max(most, b - a);
    }
    EXPECT_LE(most, gathered_u.size() / 3) << most << " of " << gathered_u.size() << " gathered tips in one band of the cap " << 0.1f * spread << " wide";
}

TEST(Gather, SectionsWithoutAPuffGrowNothingAndThreadsDoNotMatter)
{
    const AnalyticSphere head(kC, kR);
    const std::vector<GatherPuff> puffs{make_puff(head, -1)};
    const HairRegion region(head, level_hairline(), centre_parting(), HairRegionParams{});
    GatherParams params = small_params();
    params.hairs = 400;
    auto run = [&](int threads) {
        ThreadLimit limit(threads);
        return gather(head, whole_sphere(), puffs, region, params);
    };
    const GatherResult one = run(1), two = run(2);
    EXPECT_GT(one.roots_without_puff, 0);
    for (size_t c = 0; c < one.hairs.num_curves(); ++c) EXPECT_LT(one.hairs.positions()[one.hairs.points_of(c).begin].x, 0.0f);
    ASSERT_EQ(one.hairs.num_points(), two.hairs.num_points());
    EXPECT_EQ(std::memcmp(one.hairs.positions().data(), two.hairs.positions().data(), one.hairs.num_points() * sizeof(float3)), 0);
    EXPECT_EQ(std::memcmp(one.bands.positions().data(), two.bands.positions().data(), one.bands.num_points() * sizeof(float3)), 0);
}

TEST(Gather, RejectsBadParamsAndMissingPuffs)
{
    const AnalyticSphere head(kC, kR);
    const HairRegion region(head, CurveSet(), CurveSet(), HairRegionParams{});
    GatherParams p = small_params();
    EXPECT_THROW(gather(head, whole_sphere(), {}, region, p), InvalidGeometry);
    for (auto set : {+[](GatherParams& q) { q.hairs = 0; }, +[](GatherParams& q) { q.lift = 0; }, +[](GatherParams& q) { q.step = NAN; },
                     +[](GatherParams& q) { q.band_strands = -1; }, +[](GatherParams& q) { q.hair_points = 2; }}) {
        GatherParams q = small_params();
        set(q);
        EXPECT_THROW(q.validate(), InvalidParam);
    }
    p.lift = -1;
    try {
        p.validate();
        FAIL();
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`lift`"), std::string::npos) << e.what();
    }
}

// A puff made on another head: its base (groom puff puts it on the scalp) is off this scalp. Moved
// out by a quarter of its radius or less (the level set's error, and more) it still gathers; farther,
// it is refused naming the puff and the distance (a trial gathered Sintel's hair over her face into
// a puff made on ICT's head).
TEST(Gather, APuffWhoseBaseIsOffThisScalpIsRefused)
{
    TwoPuffs t;
    GatherParams p = small_params();
    p.hairs = 200;
    std::vector<GatherPuff> moved = t.puffs;
    const float3 out = normalize(moved[1].base - kC);
    moved[1].base = moved[1].base + out * (0.2f * moved[1].base_radius);
    EXPECT_NO_THROW(gather(t.head, whole_sphere(), moved, t.region, p));
    moved[1].base = t.puffs[1].base + out * (0.3f * moved[1].base_radius);
    try {
        gather(t.head, whole_sphere(), moved, t.region, p);
        FAIL() << "expected InvalidGeometry";
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("puff 1's base"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("another scalp"), std::string::npos) << e.what();
    }
}

// A puff written before `puff_cap_angle` was kept still gathers: each tip goes straight out onto the
// sphere, as it did. A cap angle outside (0, 180) is refused, naming the attribute.
TEST(Gather, PuffWithoutItsCapAngleAndABadOne)
{
    TwoPuffs scene;
    for (GatherPuff& g : scene.puffs) g.cap_angle = 0.0f;
    GatherParams params = small_params();
    params.hairs = 500;
    const GatherResult r = scene.grow(params);
    ASSERT_EQ(r.hairs.num_curves(), 500u);
    const auto P = r.hairs.positions();
    const auto puff_of = r.hairs.find<int32_t>(Domain::Curve, "puff");
    const float reach = curl_reach(params.curl);
    for (size_t c = 0; c < r.hairs.num_curves(); ++c) {
        const GatherPuff& g = scene.puffs[puff_of[c]];
        EXPECT_LE(std::fabs(distance(P[r.hairs.points_of(c).end - 1], g.sphere_center) - g.sphere_radius), reach + 1e-3f) << c;
    }
    scene.puffs[1].cap_angle = 200.0f;
    try {
        scene.grow(params);
        FAIL() << "a cap angle of 200 degrees was accepted";
    }
    catch (const InvalidGeometry& e) {
        EXPECT_NE(std::string(e.what()).find("puff_cap_angle"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("200"), std::string::npos) << e.what();
    }
}

TEST(Gather, RealScanEveryHairReachesItsBaseOnTheScalp)
{
    // Lee Perry-Smith's scan: ears and a real nape, where a walk on the scalp can stall behind an ear.
    // Every hair must still lie on the scalp up to its puff's base circle and enter the puff there.
    GROOM_REQUIRE_SHARED(path, "lee_perry_smith/LeePerrySmith.obj");
    const ScalpField scalp = build_scalp(read_mesh(path));
    const CurveSet hairline = make_hairline(scalp, scalp.bounds(), HairlineParams{});
    std::vector<GatherPuff> puffs;
    for (float side : {-1.0f, 1.0f}) {
        PuffParams p;
        p.center = {side, 3.6f, -0.3f};
        p.radius = 0.5f;
        p.sphere_center = {1.7f * side, 4.45f, -0.3f};
        p.sphere_radius = 1.0f;
        p.cap_angle = 150.0f;
        GatherPuff g;
        g.guides = puff_guides(scalp, p);
        g.base = g.guides.find<float3>(Domain::Detail, "puff_base")[0];
        g.base_radius = p.radius;
        g.sphere_center = p.sphere_center;
        g.sphere_radius = p.sphere_radius;
        puffs.push_back(std::move(g));
    }
    const HairRegion region(scalp, hairline, CurveSet(), HairRegionParams{});
    GatherParams params;
    params.hairs = 2000;
    params.lift = 0.014f;
    params.step = 0.045f;
    params.hair_points = 12;
    params.curl.amplitude = {0.03f, 0.045f};
    params.curl.hair_type = "4a";
    const GatherResult r = gather(scalp, scalp_root_sampler(scalp), puffs, region, params);
    ASSERT_EQ(r.hairs.num_curves(), 2000u);
    const auto P = r.hairs.positions();
    const auto flat = r.hairs.find<int32_t>(Domain::Point, "flat");
    const auto puff_of = r.hairs.find<int32_t>(Domain::Curve, "puff");
    const float tol = 0.05f * scalp.voxel_size();  // the level set's own accuracy near the surface
    int late = 0;
    int64_t high = 0, flat_points = 0;
    for (size_t c = 0; c < r.hairs.num_curves(); ++c) {
        const IndexRange pr = r.hairs.points_of(c);
        const GatherPuff& g = puffs[puff_of[c]];
        int64_t first_up = pr.begin;
        while (first_up < pr.end && flat[first_up]) ++first_up;
        ASSERT_LT(first_up, pr.end);
        // The puff part starts on the base circle (a chord of it: within its radius and a step).
        late += distance(P[first_up], g.base) > g.base_radius + params.step + params.lift;
        // Roots are drawn on the mesh's triangles and never move; the field there reads up to a third
        // of a voxel off in creases. Every other point of the flat part is placed on the field.
        for (int64_t i = pr.begin + 1; i < first_up; ++i) {
            const float d = scalp.distance(P[i]);
            EXPECT_GE(d, -tol) << c << " point " << (i - pr.begin) << " of flat " << (first_up - pr.begin);
            // In a crease (behind an ear) the field's normal turns within a step and a point may settle
            // a little higher: never more than half a voxel, and rarely at all.
            EXPECT_LE(d, params.lift + 0.5f * scalp.voxel_size()) << c;
            high += d > params.lift + tol;
            ++flat_points;
        }
    }
    EXPECT_EQ(late, 0);
    EXPECT_LE(high, flat_points / 1000) << high << " of " << flat_points << " flat points above the lift";
}
