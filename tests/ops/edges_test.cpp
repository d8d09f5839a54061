// edges: baby hairs along a hairline. On an exact sphere the hairline is a circle of latitude, so the
// band of roots, the heights and the swirls' turning have closed forms; on the demo head the heights
// are read back from the scalp field.
#include "ops/edges.h"

#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/parallel.h"
#include "ops/hairline.h"
#include "ops/head.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

using namespace groom;

namespace {

constexpr float kR = 10.0f;
constexpr double kPi = 3.14159265358979323846;
const float3 kC(0.0f, 0.0f, 0.0f);
/// The hairline's elevation on the test sphere: 20 degrees above the equator.
constexpr double kLineElevation = 20.0 * kPi / 180.0;
constexpr int kLinePoints = 360;

/// Point at azimuth `az` (radians from +Z toward +X, around +Y) and elevation `el` on the sphere.
float3 sphere_point(double az, double el)
{
    return kC + float3(float(std::cos(el) * std::sin(az)), float(std::sin(el)), float(std::cos(el) * std::cos(az))) * kR;
}

/// A circle of latitude, one point per degree of azimuth from -180, in order of increasing azimuth.
CurveSet circle_hairline(int points = kLinePoints)
{
    CurveSet line = CurveSet::from_counts(std::vector<int64_t>{points});
    auto P = line.positions_for_write();
    for (int i = 0; i < points; ++i) P[i] = sphere_point(-kPi + 2.0 * kPi * i / points, kLineElevation);
    line.add<int64_t>(Domain::Curve, attr::id)[0] = 0;
    return line;
}

double elevation(const float3& p) { return std::asin(std::clamp(double((p - kC).y) / double(length(p - kC)), -1.0, 1.0)); }
double azimuth_deg(const float3& p) { return std::atan2(double(p.x - kC.x), double(p.z - kC.z)) * 180.0 / kPi; }

std::span<const float3> curve(const CurveSet& cs, size_t c)
{
    const IndexRange r = cs.points_of(c);
    return cs.positions().subspan(r.begin, r.size());
}

/// Signed turning angles of the polyline about the outward normal at each interior vertex (the
/// discrete geodesic curvature times the step), from segment j to j+1.
std::vector<double> turning(std::span<const float3> pts)
{
    std::vector<double> a;
    for (size_t j = 1; j + 1 < pts.size(); ++j) {
        const float3 n = normalize(pts[j] - kC);
        float3 u = pts[j] - pts[j - 1], v = pts[j + 1] - pts[j];
        u = normalize(u - n * dot(u, n));
        v = normalize(v - n * dot(v, n));
        a.push_back(std::atan2(double(dot(cross(u, v), n)), double(dot(u, v))));
    }
    return a;
}

EdgesParams sphere_params()
{
    EdgesParams p;
    p.seed = 7;
    return p;
}

}  // namespace

TEST(Edges, HeightsOnASphereAreWithinTheHairsHeight)
{
    const AnalyticSphere head(kC, kR);
    EdgesParams p = sphere_params();
    p.height = 0.05f;
    const CurveSet cs = edges(head, circle_hairline(), p);
    ASSERT_GT(cs.num_curves(), 100u);
    EXPECT_NO_THROW(cs.validate());
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        ASSERT_EQ(pts.size(), size_t(p.points));
        // The root on the sphere (float rounding of a closest point at radius 10: a few ulps).
        EXPECT_LT(std::fabs(head.distance(pts[0])), 1e-5f) << c;
        for (size_t j = 1; j < pts.size(); ++j) {
            const float d = head.distance(pts[j]);
            // Each hair lies at its own height in [h/2, h] from one step past its root: 0.25 cm is
            // the bound, h + rounding the op's own.
            ASSERT_GE(d, 0.5f * p.height - 1e-5f) << c << ":" << j;
            ASSERT_LE(d, p.height + 1e-5f) << c << ":" << j;
            ASSERT_LE(d, 0.25f);
        }
    }
}

TEST(Edges, HeightZeroLiesOnTheSkinAndNeverInside)
{
    const AnalyticSphere head(kC, kR);
    EdgesParams p = sphere_params();
    p.height = 0.0f;
    const CurveSet cs = edges(head, circle_hairline(), p);
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        for (size_t j = 1; j < pts.size(); ++j) {
            // keep_outside's margin is 1e-4 x length above the surface, the rest float rounding.
            ASSERT_GE(head.distance(pts[j]), 0.0f) << c << ":" << j;
            ASSERT_LE(head.distance(pts[j]), 1e-4f * p.length + 1e-5f) << c << ":" << j;
        }
    }
}

TEST(Edges, RootsInTheBandInsideTheHairlineOverTheChosenAzimuths)
{
    const AnalyticSphere head(kC, kR);
    EdgesParams p = sphere_params();
    p.depth = 0.4f;
    p.from = -60.0f;
    p.to = 30.0f;
    const CurveSet cs = edges(head, circle_hairline(), p);
    // Count: density x the length of the chosen part of the polygon (90 one-degree chords).
    const double chord = 2.0 * kR * std::cos(kLineElevation) * std::sin(0.5 * kPi / 180.0);
    EXPECT_EQ(int64_t(cs.num_curves()), std::llround(p.density * 90.0 * chord));
    double lo = 1e9, hi = -1e9;
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const float3 root = curve(cs, c)[0];
        // The walk inward is perpendicular to the latitude circle: along the meridian, by depth x u on
        // the sphere, so the elevation rises by [0, depth / R] and the azimuth does not change (the
        // polygon's chords sag inside the circle by R cos(el) (1 - cos 0.5 deg), 4e-4 rad here).
        const double rise = elevation(root) - kLineElevation;
        EXPECT_GE(rise, -4e-4) << c;
        EXPECT_LE(rise, p.depth / kR + 1e-4) << c;
        const double az = azimuth_deg(root);
        EXPECT_GE(az, p.from - 1e-3) << c;
        EXPECT_LE(az, p.to + 1e-3) << c;
        lo = std::min(lo, az);
        hi = std::max(hi, az);
    }
    // Spread over the whole range: one root per equal interval.
    const double spacing = 90.0 / double(cs.num_curves());
    EXPECT_LT(lo - p.from, spacing);
    EXPECT_LT(p.to - hi, spacing);
}

TEST(Edges, CountWinsOverDensityAndIdsFollowTheHairline)
{
    const AnalyticSphere head(kC, kR);
    EdgesParams p = sphere_params();
    p.count = 37;
    p.first_id = 100;
    p.kind = 5;
    const CurveSet cs = edges(head, circle_hairline(), p);
    ASSERT_EQ(cs.num_curves(), 37u);
    const auto id = cs.find<int64_t>(Domain::Curve, attr::id);
    const auto kind = cs.find<int32_t>(Domain::Curve, "kind");
    const auto width = cs.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(id.size(), 37u);
    ASSERT_EQ(width.size(), cs.num_points());
    double last = -1e9;
    for (size_t c = 0; c < 37; ++c) {
        EXPECT_EQ(id[c], 100 + int64_t(c));
        EXPECT_EQ(kind[c], 5);
        const double az = azimuth_deg(curve(cs, c)[0]);
        EXPECT_GT(az, last);  // stations in order of azimuth from `from`
        last = az;
    }
    // Tapered from the default root width to the default tip width (ops/hair_widths.h).
    for (size_t c = 0; c < 37; ++c) {
        const IndexRange r = cs.points_of(c);
        EXPECT_EQ(width[r.begin], kDefaultRootWidthCm);
        EXPECT_EQ(width[r.end - 1], kDefaultTipWidthCm);
        for (int64_t i = r.begin + 1; i < r.end; ++i) EXPECT_LE(width[i], width[i - 1]);
    }
}

TEST(Edges, EachHairTurnsAsAsked)
{
    // Height 0, no variation, roots on the hairline: every hair's turning, measured from its points,
    // is the prescribed one: `bends` arcs of alternating sign (bends - 1 sign changes), radii between
    // r and r + w, each turning by tau = L / (bends (r + w/2)).
    const AnalyticSphere head(kC, kR);
    for (int bends : {1, 2, 3}) {
        EdgesParams p = sphere_params();
        p.height = 0.0f;
        p.variation = 0.0f;
        p.depth = 0.0f;
        p.points = 193;
        p.bends = bends;
        p.count = 40;
        const CurveSet cs = edges(head, circle_hairline(), p);
        ASSERT_EQ(cs.num_curves(), 40u);
        const double w = p.swoop, r = p.radius;
        const double tau = p.length / (bends * (r + 0.5 * w));
        double tightest = 1e9;
        for (size_t c = 0; c < cs.num_curves(); ++c) {
            const auto pts = curve(cs, c);
            double length = 0.0;
            for (size_t j = 1; j < pts.size(); ++j) length += distance(pts[j], pts[j - 1]);
            const double ds = length / double(pts.size() - 1);
            const std::vector<double> a = turning(pts);
            // A vertex's turning is the curvature integrated over the step around it: within an arc,
            // ds / radius; one vertex at each junction mixes two arcs.
            int changes = 0, last = 0;
            double plus = 0.0, minus = 0.0, total = 0.0;
            for (size_t j = 0; j < a.size(); ++j) {
                const int sign = a[j] > 0 ? 1 : -1;
                if (last != 0 && sign != last) ++changes;
                last = sign;
                (a[j] > 0 ? plus : minus) += a[j];
                total += a[j];
                const double radius = ds / std::fabs(a[j]);
                tightest = std::min(tightest, radius);
                // Junction vertices turn less (both signs cancel): only a lower bound there. 2%: the
            // chords of a walk on a sphere of radius 10 against the plane circle.
                EXPECT_GE(radius, r * 0.98) << "bends " << bends << " hair " << c << " vertex " << j;
                if (j > 0 && j + 1 < a.size() && (a[j - 1] > 0) == (a[j] > 0) && (a[j + 1] > 0) == (a[j] > 0)) {
                    EXPECT_LE(radius, (r + w) * 1.02) << "bends " << bends << " hair " << c << " vertex " << j;
                }
            }
            EXPECT_EQ(changes, bends - 1) << "bends " << bends << " hair " << c;
            // The measured turning misses half a step at each end and mixes at each junction: at
            // most one step's turning at the tightest radius per arc.
            const double slack = bends * ds / r;
            const int major = (bends + 1) / 2, minor = bends / 2;  // arcs bending the first way, the other way
            EXPECT_NEAR(std::max(plus, -minus), major * tau, slack) << "bends " << bends << " hair " << c;
            EXPECT_NEAR(std::min(plus, -minus), minor * tau, slack) << "bends " << bends << " hair " << c;
            EXPECT_NEAR(std::fabs(total), (major - minor) * tau, slack) << "bends " << bends << " hair " << c;
        }
        // Some hair starts next to its swoop's end: the tightest radius is r.
        EXPECT_NEAR(tightest, r, 0.1 * r) << "bends " << bends;
    }
}

TEST(Edges, ASwoopsHairsCircleOneCentre)
{
    // On a sphere large enough to be flat over a swoop (R = 1000, hairline through the origin), a
    // swoop's hairs leave the hairline at right angles and circle the point `radius` past the swoop's
    // end: every point of a hair's first arc is at its root's distance from that point.
    const float R = 1000.0f;
    const double el = kLineElevation;
    const float3 centre(0.0f, -R * float(std::sin(el)), -R * float(std::cos(el)));
    const AnalyticSphere head(centre, R);
    const int n = 36000;  // chords of 0.16 along the hairline
    CurveSet line = CurveSet::from_counts(std::vector<int64_t>{n});
    auto L = line.positions_for_write();
    for (int i = 0; i < n; ++i) {
        const double az = -kPi + 2.0 * kPi * i / n;
        L[i] = centre + float3(float(std::cos(el) * std::sin(az)), float(std::sin(el)), float(std::cos(el) * std::cos(az))) * R;
    }
    EdgesParams p;
    p.variation = 0.0f;
    p.depth = 0.0f;
    p.height = 0.0f;
    p.points = 97;
    p.from = -0.3f;  // about 5 units of hairline either side of the middle: 10 swoops
    p.to = 0.3f;
    const CurveSet cs = edges(head, line, p);
    ASSERT_GT(cs.num_curves(), 60u);
    // Arc length along the hairline from the middle (azimuth 0, the origin), signed toward +x.
    const double rho = R * std::cos(el);
    auto arc_of = [&](const float3& q) { return rho * std::atan2(double(q.x), double(q.z - centre.z)); };
    auto at_arc = [&](double s) {
        const double az = s / rho;
        return centre + float3(float(std::cos(el) * std::sin(az)), float(std::sin(el)), float(std::cos(el) * std::cos(az))) * R;
    };
    const double tau = p.length / (p.bends * (p.radius + 0.5 * p.swoop));
    int checked = 0;
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        const double s0 = arc_of(pts[0]);
        if (std::fabs(s0) > 4.5) continue;  // the part's ends: clipped swoops
        const int g = int(std::floor(s0 / p.swoop));  // swoops are counted from the middle
        // Face: away from the middle, so the swirl's centre is past the swoop's far end.
        const double end = s0 >= 0 ? (g + 1) * p.swoop + p.radius : g * p.swoop - p.radius;
        const float3 C = at_arc(end);
        const double radius = distance(pts[0], C);
        EXPECT_NEAR(radius, std::fabs(end - s0), 2e-3) << c;
        const size_t first_arc = size_t(radius * tau / (p.length / (p.points - 1)));
        for (size_t j = 1; j < std::min(first_arc, pts.size()); ++j) ASSERT_NEAR(distance(pts[j], C), radius, 5e-3) << c << ":" << j;
        ++checked;
    }
    EXPECT_GT(checked, 40);
}

TEST(Edges, DirectionsLayTheHairsWhereAsked)
{
    const AnalyticSphere head(kC, kR);
    EdgesParams p = sphere_params();
    p.variation = 0.0f;
    p.depth = 0.0f;
    // Face: out of the hairline (the tip below the root by most of the hair) and swept away from the
    // face's middle: the S's arcs each move it sideways by radius (1 - cos tau).
    p.direction = EdgeDirection::Face;
    CurveSet cs = edges(head, circle_hairline(), p);
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        const double down = (elevation(pts[0]) - elevation(pts.back())) * kR;
        const double az0 = azimuth_deg(pts[0]), az1 = azimuth_deg(pts.back());
        EXPECT_GT(down, 0.4 * p.length) << c;
        if (std::fabs(az0) > 0.5) EXPECT_GT(std::fabs(az1), std::fabs(az0)) << c;
    }
    // Along: tips farther from the face's middle than their roots by most of the hair, at about their
    // height: the S is symmetric about the hairline's direction (on the sphere the latitude circle
    // bends away from the hair's great-circle chord by about L^2 tan(el) / 2R).
    p.direction = EdgeDirection::Along;
    cs = edges(head, circle_hairline(), p);
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        const double az0 = azimuth_deg(pts[0]), az1 = azimuth_deg(pts.back());
        if (std::fabs(az0) < 0.5) continue;  // at the very middle either way is away
        const double aside = std::fabs(az1 - az0) * kPi / 180.0 * kR * std::cos(kLineElevation);
        const double down = (elevation(pts[0]) - elevation(pts.back())) * kR;
        EXPECT_GT(std::fabs(az1), std::fabs(az0)) << c;
        EXPECT_GT(aside, 0.5 * p.length) << c;
        EXPECT_LT(std::fabs(down), 0.15 * aside) << c;
    }
    // Alternate: swoops lean to one side, then the other, group by group.
    p.direction = EdgeDirection::Alternate;
    cs = edges(head, circle_hairline(), p);
    const auto group = cs.find<int32_t>(Domain::Curve, "group");
    ASSERT_EQ(group.size(), cs.num_curves());
    std::set<int32_t> groups;
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        const double d_az = azimuth_deg(pts.back()) - azimuth_deg(pts[0]);
        EXPECT_EQ(d_az > 0.0, group[c] % 2 == 0) << c << " group " << group[c];
        EXPECT_GT(elevation(pts[0]), elevation(pts.back())) << c;  // out of the hairline, onto the face
        groups.insert(group[c]);
    }
    EXPECT_GT(groups.size(), 10u);
}

TEST(Edges, SwoopsShareTheirSideAndRandomIsSeeded)
{
    const AnalyticSphere head(kC, kR);
    EdgesParams p = sphere_params();
    p.direction = EdgeDirection::Random;
    p.variation = 0.0f;
    const CurveSet a = edges(head, circle_hairline(), p);
    const auto group = a.find<int32_t>(Domain::Curve, "group");
    std::vector<int> side_of_group(1000, 0);
    int left = 0, right = 0;
    for (size_t c = 0; c < a.num_curves(); ++c) {
        const auto pts = curve(a, c);
        const int side = azimuth_deg(pts.back()) > azimuth_deg(pts[0]) ? 1 : -1;
        int& g = side_of_group.at(size_t(group[c]));
        if (g == 0) (side > 0 ? left : right) += 1;
        EXPECT_TRUE(g == 0 || g == side) << c;
        g = side;
    }
    EXPECT_GT(left, 2);
    EXPECT_GT(right, 2);
    p.seed = 8;
    const CurveSet b = edges(head, circle_hairline(), p);
    ASSERT_EQ(a.num_points(), b.num_points());
    EXPECT_NE(std::memcmp(a.positions().data(), b.positions().data(), a.positions().size_bytes()), 0);
}

TEST(Edges, DeterministicAcrossThreadCounts)
{
    const AnalyticSphere head(kC, kR);
    const EdgesParams p = sphere_params();
    auto run = [&](int threads) {
        ThreadLimit limit(threads);
        return edges(head, circle_hairline(), p);
    };
    const CurveSet a = run(1), b = run(2);
    ASSERT_EQ(a.num_points(), b.num_points());
    EXPECT_EQ(std::memcmp(a.positions().data(), b.positions().data(), a.positions().size_bytes()), 0);
}

TEST(Edges, NoRootOnAPartingAndNoHairAcrossIt)
{
    const AnalyticSphere head(kC, kR);
    // A centre parting from the crown down to the forehead's hairline, along the meridian x = 0.
    CurveSet parting = CurveSet::from_counts(std::vector<int64_t>{40});
    auto P = parting.positions_for_write();
    for (int i = 0; i < 40; ++i) P[i] = sphere_point(0.0, kPi / 2 - (kPi / 2 - kLineElevation + 0.05) * i / 39.0);
    HairRegionParams rp;
    rp.parting_gap = 0.3f;
    const CurveSet line = circle_hairline();
    const HairRegion region(head, line, parting, rp);
    EdgesParams p = sphere_params();
    p.direction = EdgeDirection::Random;
    const CurveSet cs = edges(head, line, p, &region);
    const CurveSet all = edges(head, line, p);
    EXPECT_LT(cs.num_curves(), all.num_curves());  // the gap holds a few stations
    EXPECT_GT(cs.num_curves(), all.num_curves() * 9 / 10);
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        EXPECT_TRUE(!region.inside_hairline(pts[0]) || region.haired(pts[0])) << c;
        for (size_t j = 0; j + 1 < pts.size(); ++j) ASSERT_FALSE(region.crosses_parting(pts[j], pts[j + 1])) << c << ":" << j;
    }
    // Without the parting some hair does cross where it would be.
    int crossing = 0;
    for (size_t c = 0; c < all.num_curves(); ++c) {
        const auto pts = curve(all, c);
        for (size_t j = 0; j + 1 < pts.size(); ++j) crossing += region.crosses_parting(pts[j], pts[j + 1]);
    }
    EXPECT_GT(crossing, 0);
}

TEST(Edges, OnTheDemoHeadEveryPointIsWithinAQuarterCentimetreOfTheScalp)
{
    const ScalpField scalp = build_scalp(make_head(HeadParams{}));
    const CurveSet line = make_hairline(scalp, scalp.bounds(), HairlineParams{});
    const EdgesParams p;  // the defaults, as `groom edges --scalp head.vdb` runs them
    const CurveSet cs = edges(scalp, line, p);
    ASSERT_GT(cs.num_curves(), 200u);
    float lowest = 1e9f, highest = -1e9f;
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const auto pts = curve(cs, c);
        // The root is a closest point of the level set: on its zero to a small fraction of a voxel.
        EXPECT_LT(std::fabs(scalp.distance(pts[0])), 2e-3f) << c;
        for (size_t j = 1; j < pts.size(); ++j) {
            const float d = scalp.distance(pts[j]);
            lowest = std::min(lowest, d);
            highest = std::max(highest, d);
            ASSERT_GE(d, 0.0f) << c << ":" << j;
            ASSERT_LE(d, 0.25f) << c << ":" << j;
        }
    }
    // Pressed flat: the heights stay near [h/2, h] (the level set's closest points are not exact).
    EXPECT_LT(highest, p.height + 0.02f);
    EXPECT_GT(lowest, -1.0f);
    // Roots within the band: no farther from the hairline polyline than the band's depth plus the
    // hairline's chord sag.
    const auto lp = line.positions();
    for (size_t c = 0; c < cs.num_curves(); ++c) {
        const float3 root = curve(cs, c)[0];
        float best = 1e9f;
        for (size_t i = 0; i < lp.size(); ++i) {
            const float3 a = lp[i], b = lp[(i + 1) % lp.size()];
            const float t = std::clamp(dot(root - a, b - a) / dot(b - a, b - a), 0.0f, 1.0f);
            best = std::min(best, distance(root, a + (b - a) * t));
        }
        EXPECT_LE(best, p.depth + 0.02f) << c;
    }
}

TEST(Edges, RejectsBadParamsNamingThem)
{
    struct Case {
        void (*change)(EdgesParams&);
        const char* name;
    };
    const Case cases[] = {
        {[](EdgesParams& p) { p.from = 400.0f; }, "`from`"},
        {[](EdgesParams& p) { p.to = p.from; }, "`to`"},
        {[](EdgesParams& p) { p.to = p.from + 361.0f; }, "`to`"},
        {[](EdgesParams& p) { p.depth = -0.1f; }, "`depth`"},
        {[](EdgesParams& p) { p.density = 0.0f; }, "`density`"},
        {[](EdgesParams& p) { p.count = -1; }, "`count`"},
        {[](EdgesParams& p) { p.length = 0.0f; }, "`length`"},
        {[](EdgesParams& p) { p.radius = -1.0f; }, "`radius`"},
        {[](EdgesParams& p) { p.bends = 0; }, "`bends`"},
        {[](EdgesParams& p) { p.bends = 17; }, "`bends`"},
        {[](EdgesParams& p) { p.swoop = 0.0f; }, "`swoop`"},
        {[](EdgesParams& p) { p.variation = 1.0f; }, "`variation`"},
        {[](EdgesParams& p) { p.height = NAN; }, "`height`"},
        {[](EdgesParams& p) { p.widths.root = 0.0f; }, "--root-width"},
        {[](EdgesParams& p) { p.widths.tip = -1.0f; }, "--tip-width"},
        {[](EdgesParams& p) { p.points = 3; }, "`points`"},
        {[](EdgesParams& p) { p.first_id = -1; }, "`first_id`"},
        {[](EdgesParams& p) { p.kind = -1; }, "`kind`"},
        {[](EdgesParams& p) { p.up = float3(0, 0, 0); }, "`up`"},
        {[](EdgesParams& p) { p.forward = float3(0, 2, 0); }, "`forward`"},
    };
    for (const Case& c : cases) {
        EdgesParams p;
        c.change(p);
        try {
            p.validate();
            ADD_FAILURE() << c.name << " accepted";
        }
        catch (const InvalidParam& e) {
            EXPECT_NE(std::string(e.what()).find(c.name), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(parse_edge_direction("sideways"), InvalidParam);
    EXPECT_EQ(parse_edge_direction(edge_direction_name(EdgeDirection::Along)), EdgeDirection::Along);
}

TEST(Edges, RejectsAHairlineNotOnceAroundAndTooManyHairs)
{
    const AnalyticSphere head(kC, kR);
    EdgesParams p;
    CurveSet two = CurveSet::from_counts(std::vector<int64_t>{10, 10});
    EXPECT_THROW(edges(head, two, p), InvalidGeometry);
    // Half a circle, closing back through the middle: turns 0 degrees in all.
    CurveSet half = CurveSet::from_counts(std::vector<int64_t>{20});
    auto P = half.positions_for_write();
    for (int i = 0; i < 20; ++i) P[i] = sphere_point(-0.5 + 1.0 * (i < 10 ? i : 19 - i) / 9.0, kLineElevation + (i < 10 ? 0.0 : 0.1));
    EXPECT_THROW(edges(head, half, p), InvalidGeometry);
    // Too many hairs for the chosen part of the hairline: refused naming the option.
    p.density = 1e9f;
    try {
        edges(head, circle_hairline(), p);
        ADD_FAILURE() << "1e9 hairs per unit accepted";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find("`density`"), std::string::npos) << e.what();
    }
}
