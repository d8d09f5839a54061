// Tests for ops/partition (edge hairs between braids, talk Sec. 2.2), against closed forms on an exact
// sphere and plane, with knot, given and every-K centroids, carry-through, determinism and rejection.
#include "ops/partition.h"

#include "fields/surface.h"
#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"
#include "ops/hair_region.h"
#include "tests/ops/circle_on_sphere.h"
#include "tests/ops/guide_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <string>

using namespace groom;
using namespace groom::test;

namespace {

/// Closed form: the point of meridian arc `a` nearest to p. The distance to a point running along a
/// great circle is unimodal, so the nearest point of the arc is the projection onto the meridian's
/// plane, its latitude clamped to the arc.
float3 nearest_on_arc(const float3& p, const Arc& a)
{
    const float3 e(std::cos(a.lon), 0.0f, std::sin(a.lon));
    const float lat = std::clamp(std::atan2(p.y, dot(p, e)), a.lat0, a.lat1);
    return on_sphere(lat, a.lon);
}

float3 first_point(const CurveSet& cs, size_t c) { return cs.positions()[cs.points_of(c).begin]; }
float3 last_point(const CurveSet& cs, size_t c) { return cs.positions()[cs.points_of(c).end - 1]; }

/// The segments of one guide and side, in output order.
std::vector<size_t> curves_of(const CurveSet& out, int guide, int side)
{
    const auto g = out.find<int32_t>(Domain::Curve, "guide");
    const auto s = out.find<int32_t>(Domain::Curve, "side");
    std::vector<size_t> r;
    for (size_t c = 0; c < out.num_curves(); ++c)
        if (g[c] == guide && s[c] == side) r.push_back(c);
    return r;
}

/// Checks every segment of a meridian layout against the closed forms: the end is the station on
/// the source, the root is the mediated point between it and the nearest adjacent point, projected
/// onto the sphere; no point is inside the sphere.
void check_meridian_segments(const CurveSet& out, const std::vector<Arc>& arcs, const std::vector<AdjacentGuides>& adj,
                             int count, float mediate)
{
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    for (size_t g = 0; g < arcs.size(); ++g) {
        const int32_t nb[2] = {adj[g].left, adj[g].right};
        for (int side = 0; side < 2; ++side) {
            const auto curves = curves_of(out, int(g), side);
            if (nb[side] < 0) {
                EXPECT_TRUE(curves.empty()) << "guide " << g << " side " << side;
                continue;
            }
            ASSERT_EQ(curves.size(), size_t(count)) << "guide " << g << " side " << side;
            for (int i = 0; i < count; ++i) {
                const size_t c = curves[i];
                // Uniformly sampled arc: arc length along the polyline is linear in latitude.
                const float lat = arcs[g].lat0 + (arcs[g].lat1 - arcs[g].lat0) * (i + 0.5f) / count;
                const float3 station = on_sphere(lat, arcs[g].lon);
                // Chord sagitta of 201 samples over <= 1.6 rad is < 1e-5.
                EXPECT_NEAR3(last_point(out, c), station, 2e-5f);
                const float3 q = nearest_on_arc(station, arcs[nb[side]]);
                const float3 root = sphere.closest_point(lerp(station, q, mediate));
                // The closest point on the 200-segment polyline slides along the arc from the true
                // foot by up to about half a segment (chords tilt by half a segment's angle and the
                // distance is flat at its minimum): 1e-3 covers it. The closest point itself is
                // checked exactly on straight guides and against brute force.
                EXPECT_NEAR3(first_point(out, c), root, 1e-3f);
                EXPECT_NEAR(length(first_point(out, c)), 1.0f, 1e-5f);  // root on the surface
                for (int64_t p = out.points_of(c).begin; p < out.points_of(c).end; ++p) {
                    EXPECT_GE(sphere.distance(out.positions()[p]), -1e-5f) << "point inside the sphere";
                }
            }
        }
    }
}

}  // namespace

// --- partition: analytic cases ------------------------------------------------------------------------

TEST(Partition, ThreeMeridianArcsRootAtTheMidpointOnTheSphere)
{
    const std::vector<Arc> arcs = {{-0.3f, -0.5f, 0.5f}, {0.0f, -0.5f, 0.5f}, {0.3f, -0.5f, 0.5f}};
    PartitionParams params;
    params.mediate = {0.5f, 0.5f};  // the talk's: every root on the midpoint
    params.count = 10;
    params.samples = 9;
    const CurveSet out = partition(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f), params);
    out.validate();
    EXPECT_EQ(out.num_curves(), 40u);  // 10 per side: guide 1 has two sides, the edges one each
    const std::vector<AdjacentGuides> adj = {{0, 1, -1}, {1, 2, 0}, {2, -1, 1}};
    check_meridian_segments(out, arcs, adj, 10, 0.5f);
    // The midpoint between neighbours at the equator is half way in longitude.
    const size_t c = curves_of(out, 1, 0)[0];
    EXPECT_GT(first_point(out, c).z, 0.0f);  // side 0 = left = towards +longitude
    // Root to end, the default taper (ops/hair_widths.h).
    const auto W = out.find<float>(Domain::Point, "width");
    EXPECT_EQ(W[out.points_of(0).begin], kDefaultRootWidthCm);
    EXPECT_EQ(W[out.points_of(0).end - 1], kDefaultTipWidthCm);
    // A scene in millimetres: the default widths in its units (the Lee Perry-Smith scan's edge hairs
    // were rods of 0.4 mm before partition took --units-per-cm, a trial).
    params.units_per_cm = 10.0f;
    const CurveSet mm = partition(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f), params);
    const auto Wmm = mm.find<float>(Domain::Point, "width");
    EXPECT_FLOAT_EQ(Wmm[mm.points_of(0).begin], 10.0f * kDefaultRootWidthCm);
    EXPECT_FLOAT_EQ(Wmm[mm.points_of(0).end - 1], 10.0f * kDefaultTipWidthCm);
}

namespace {

/// Roots of two neighbouring rows on meridians 0 and theta of the unit sphere, seen as a groom
/// artist sees the strip between the rows: how far each root is from the parting's midline, and
/// which cells of the strip (4 across, from the braid at fraction 0.1 to the parting at 0.47; 10
/// along the middle of the rows) hold a root.
struct StripRoots {
    double nearest_to_midline = 1e9;  ///< least |longitude - theta / 2| of a root, radians
    int cells_across_with_roots = 0;  ///< of 4, cells across (any along) holding a root
    int empty_cells = 0;              ///< of 2 sides x 4 x 10
    int outside_strip = 0;            ///< roots beyond the fractions 0.1..0.47 of their side
    /// Share of the hairs that cover the last quarter of the strip before the parting: a hair covers
    /// the scalp from its root to the braid, so those rooted in that quarter.
    double cover_near_parting = 0.0;
};

StripRoots strip_roots(std::optional<FloatRange> mediate)
{
    const double theta = 0.3;
    const std::vector<Arc> arcs = {{0.0f, -0.5f, 0.5f}, {float(theta), -0.5f, 0.5f}};
    PartitionParams params;
    if (mediate) params.mediate = *mediate;  // else the default
    params.count = 2000;
    params.samples = 4;
    const CurveSet out = partition(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f), params);
    // Closed form: the root at fraction f from a row toward its neighbour (same latitude) projects
    // to longitude atan2(f sin theta, 1 - f + f cos theta) from the row.
    const auto lon_at = [&](double f) { return std::atan2(f * std::sin(theta), 1.0 - f + f * std::cos(theta)); };
    const double lo = lon_at(0.1), hi = lon_at(0.47);
    bool cell[2][4][10] = {};
    StripRoots r;
    int64_t near_parting = 0;
    const auto guide = out.find<int32_t>(Domain::Curve, "guide");
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const float3 root = first_point(out, c);
        const double lon = std::atan2(double(root.z), double(root.x));
        r.nearest_to_midline = std::min(r.nearest_to_midline, std::fabs(lon - 0.5 * theta));
        const double own = guide[c] == 0 ? lon : theta - lon;  // from the root's own row
        if (own < lo - 1e-4 || own > hi + 1e-4) ++r.outside_strip;
        const double lat = std::asin(std::clamp(double(root.y), -1.0, 1.0));
        if (std::fabs(lat) >= 0.4) continue;
        const int across = std::clamp(int((own - lo) / (hi - lo) * 4.0), 0, 3);
        near_parting += across == 3;
        const int along = std::clamp(int((lat + 0.4) / 0.8 * 10.0), 0, 9);
        cell[guide[c]][across][along] = true;
    }
    r.cover_near_parting = out.num_curves() > 0 ? double(near_parting) / double(out.num_curves()) * (1.0 / 0.8) : 0.0;  // of those along the middle 80%
    for (int a = 0; a < 4; ++a) {
        bool any = false;
        for (int side = 0; side < 2; ++side)
            for (int b = 0; b < 10; ++b) any |= cell[side][a][b], r.empty_cells += !cell[side][a][b];
        r.cells_across_with_roots += any;
    }
    return r;
}

}  // namespace

TEST(Partition, DefaultRootsCoverTheStripBetweenBraidAndPartingAndLeaveTheMidlineBare)
{
    // What the artist sees between two cornrows: hair rooted all over the strip from each braid to
    // the parting, and a clean bare line down the middle (the middle 6% of the gap).
    const StripRoots d = strip_roots(std::nullopt);
    const double theta = 0.3, bare = 0.5 * theta - std::atan2(0.47 * std::sin(theta), 0.53 + 0.47 * std::cos(theta));
    EXPECT_GT(bare, 0.0085);  // about 0.009 rad: 6% of the gap, 0.5 degrees either side
    EXPECT_GE(d.nearest_to_midline, bare - 1e-4) << "a root on the parting line";
    EXPECT_EQ(d.outside_strip, 0);
    EXPECT_EQ(d.empty_cells, 0) << "bare patches in the strip (80 cells, 2000 roots a side)";
    // Roots denser toward the parting (density rising linearly: 7/16 of them in the last quarter), so
    // the cover does not thin out to nothing there (uniform roots: a quarter).
    EXPECT_GT(d.cover_near_parting, 0.38);
    EXPECT_LT(d.cover_near_parting, 0.50);
    EXPECT_EQ(d.cells_across_with_roots, 4);
    // The talk's default (every root on the midpoint) is what this test tells apart: every root on
    // the parting line, one cell across holding them all.
    const StripRoots talk = strip_roots(FloatRange{0.5f, 0.5f});
    EXPECT_LT(talk.nearest_to_midline, 1e-4);
    EXPECT_LE(talk.cells_across_with_roots, 1);
}

// The outermost row of a head has no neighbour on its outer side; with a hairline its edge hairs
// reach the hairline (without, the sides of a cornrowed head stayed bald inside the hairline, like an
// undercut: a trial). Two rows along latitudes 0.3 and 0.6 of the unit sphere, the hairline the
// equator: the lower row's outer side is rooted from near it down to the equator and never below; the
// upper row's outer side finds no hairline within two gaps (toward the pole) and gets nothing.
TEST(Partition, OuterSideOfTheLastRowReachesTheHairline)
{
    std::vector<std::vector<float3>> rows;
    for (const float lat : {0.3f, 0.6f}) {
        std::vector<float3> row;
        for (int k = 0; k <= 100; ++k) row.push_back(on_sphere(lat, -0.5f + float(k) / 100.0f));
        rows.push_back(row);
    }
    CurveSet guides = CurveSet::from_counts(std::vector<int64_t>{101, 101});
    auto G = guides.positions_for_write();
    for (size_t c = 0; c < 2; ++c)
        for (size_t k = 0; k < 101; ++k) G[c * 101 + k] = rows[c][k];
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    const HairRegion region(sphere, circle_on_sphere({0, 0, 0}, 1.0f, {0, 1, 0}, 0.0f, 360), CurveSet(), HairRegionParams{});
    PartitionParams params;
    params.count = 200;
    params.samples = 4;
    params.region = &region;
    const CurveSet out = partition(guides, sphere, params);
    const auto guide = out.find<int32_t>(Domain::Curve, "guide");
    int below_row = 0, near_hairline = 0, beyond = 0, above_top = 0;
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const double lat = std::asin(std::clamp(double(first_point(out, c).y), -1.0, 1.0));
        if (guide[c] == 0 && lat < 0.3) {
            ++below_row;
            near_hairline += lat < 0.3 * 0.25;  // the quarter of the strip next to the hairline
            beyond += lat < -1e-3;
        }
        above_top += guide[c] == 1 && lat > 0.6;
    }
    EXPECT_EQ(below_row, 200);  // every station of the outer side (the hairline is 0.3 away, within reach)
    EXPECT_GT(near_hairline, 200 / 8) << "the roots stop short of the hairline";
    EXPECT_EQ(beyond, 0) << "roots past the hairline";
    EXPECT_EQ(above_top, 0) << "the top row's outer side has no hairline within reach";
    // The same bytes at any thread count (the walk is per station).
    {
        ThreadLimit one(1);
        const CurveSet serial = partition(guides, sphere, params);
        ASSERT_EQ(serial.num_points(), out.num_points());
        EXPECT_EQ(std::memcmp(serial.positions().data(), out.positions().data(), out.num_points() * sizeof(float3)), 0);
    }
    // A parting between the row and the hairline (latitude 0.15, bare 0.02 either side) ends the walk
    // there: no root beyond it, no hair drawn across it.
    const HairRegion parted(sphere, circle_on_sphere({0, 0, 0}, 1.0f, {0, 1, 0}, 0.0f, 360),
                            circle_on_sphere({0, 0, 0}, 1.0f, {0, 1, 0}, std::sin(0.15f), 360), HairRegionParams{{0, 1, 0}, 0.04f});
    params.region = &parted;
    const CurveSet stopped = partition(guides, sphere, params);
    const auto stopped_guide = stopped.find<int32_t>(Domain::Curve, "guide");
    int crossed = 0, outer = 0;
    for (size_t c = 0; c < stopped.num_curves(); ++c) {
        const double lat = std::asin(std::clamp(double(first_point(stopped, c).y), -1.0, 1.0));
        if (stopped_guide[c] == 0 && lat < 0.3) ++outer, crossed += lat < 0.15;
    }
    EXPECT_EQ(outer, 200);
    EXPECT_EQ(crossed, 0) << "roots past the parting";
    // A reach that rounds to nothing (--max-gap 1e-45) ends at once with no walk (it looped forever).
    params.region = &region;
    params.max_gap = 1e-45f;
    EXPECT_EQ(partition(guides, sphere, params).num_curves(), 0u);  // no neighbour within 1e-45 either
    params.max_gap = 0.0f;
    // Without a hairline the outer sides get nothing, as before.
    params.region = nullptr;
    const CurveSet inner = partition(guides, sphere, params);
    EXPECT_EQ(inner.num_curves(), 400u);  // the two inner sides only
    // A side walked to the hairline counts in the size check: --spacing 1e-9 on one row is refused
    // before anything is made (uncounted, its station count overflowed an int).
    const CurveSet one_row = CurveSet::from_counts(std::vector<int64_t>{101});
    {
        CurveSet row = one_row;
        auto R = row.positions_for_write();
        for (size_t k = 0; k < 101; ++k) R[k] = rows[0][k];
        PartitionParams tiny;
        tiny.region = &region;
        tiny.count = 0;
        tiny.spacing = 1e-9f;
        tiny.max_gap = 0.5f;
        EXPECT_THROW(partition(row, sphere, tiny), LimitExceeded);
        // One row: no gap to measure, so the automatic count is kAutoCountWithoutGap a side (it was 1).
        PartitionParams automatic;
        automatic.region = &region;
        automatic.max_gap = 0.5f;
        automatic.samples = 4;
        EXPECT_EQ(partition(row, sphere, automatic).num_curves(), size_t(kAutoCountWithoutGap));  // the lower side only
    }
}

// The automatic density: one segment every 1/200 of the typical gap between guides (the median
// distance from a guide's middle to the nearest other guide: here the chord 2 sin(0.15) between
// meridians 0.3 apart).
TEST(Partition, AutomaticCountIsTwoHundredToTheGap)
{
    const std::vector<Arc> arcs = {{0.0f, -0.5f, 0.5f}, {0.3f, -0.5f, 0.5f}};
    const CurveSet guides = meridian_guides(arcs);
    PartitionParams params;
    params.samples = 3;
    const CurveSet out = partition(guides, AnalyticSphere({0, 0, 0}, 1.0f), params);
    const double gap = 2.0 * std::sin(0.15), length = polyline_length(guides.positions().subspan(0, 201));
    const size_t per_side = size_t(std::floor(length / (gap / kAutoSpacingPerGap)));
    EXPECT_NEAR(double(per_side), 668.0, 2.0);
    EXPECT_EQ(out.num_curves(), 2 * per_side);
}

TEST(Partition, ArcsOfDifferentLengthsUseTheNearestEndAndTheMediatedFraction)
{
    // The middle arc runs past its neighbours: past their ends the nearest adjacent point is the end.
    const std::vector<Arc> arcs = {{-0.25f, -0.3f, 0.3f}, {0.0f, -0.8f, 0.8f}, {0.35f, -0.2f, 0.4f}};
    PartitionParams params;
    params.count = 16;
    params.mediate = {0.8f, 0.8f};
    params.adjacent = {{0, 1, -1}, {1, 2, 0}, {2, -1, 1}};
    const CurveSet out = partition(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f), params);
    check_meridian_segments(out, arcs, params.adjacent, 16, 0.8f);
    // And the automatic search finds the same neighbours.
    params.adjacent.clear();
    const CurveSet automatic = partition(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f), params);
    ASSERT_EQ(automatic.num_curves(), out.num_curves());
    EXPECT_EQ(0, std::memcmp(automatic.positions().data(), out.positions().data(), out.num_points() * sizeof(float3)));
}

TEST(Partition, SingleNeighbourGivesOneSide)
{
    const std::vector<Arc> arcs = {{0.0f, -0.4f, 0.6f}, {0.4f, -0.4f, 0.6f}};
    PartitionParams params;
    params.count = 7;
    params.mediate = {0.0f, 0.0f};  // roots at the source's own foot
    const CurveSet out = partition(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f), params);
    EXPECT_EQ(out.num_curves(), 14u);
    EXPECT_EQ(curves_of(out, 0, 0).size(), 7u);
    EXPECT_EQ(curves_of(out, 1, 1).size(), 7u);
    check_meridian_segments(out, arcs, {{0, 1, -1}, {1, -1, 0}}, 7, 0.0f);
}

TEST(Partition, PlaneRootsAtTheMediatedFractionAndSegmentsAreStraight)
{
    const CurveSet guides = straight_guides({-1.0f, 0.0f, 1.5f});
    const AnalyticPlane plane({0, 0, 0}, {0, 1, 0});
    PartitionParams params;
    params.count = 8;
    params.samples = 6;
    params.mediate = {0.25f, 0.25f};
    const CurveSet out = partition(guides, plane, params);
    const float xs[3] = {-1.0f, 0.0f, 1.5f};
    const int nb[3][2] = {{1, -1}, {2, 0}, {-1, 1}};
    const auto P = out.positions();
    for (int g = 0; g < 3; ++g) {
        for (int side = 0; side < 2; ++side) {
            const auto curves = curves_of(out, g, side);
            ASSERT_EQ(curves.size(), nb[g][side] < 0 ? 0u : 8u);
            for (int i = 0; i < int(curves.size()); ++i) {
                const float z = 4.0f * (i + 0.5f) / 8.0f;
                const float3 root(xs[g] + 0.25f * (xs[nb[g][side]] - xs[g]), 0.0f, z), tip(xs[g], 0.2f, z);
                EXPECT_NEAR3(first_point(out, curves[i]), root, 1e-5f);
                EXPECT_NEAR3(last_point(out, curves[i]), tip, 1e-5f);
                // Left roots lie at larger x (normal +Y x tangent +Z = +X).
                EXPECT_EQ(root.x > xs[g], side == 0);
                // The straight line follows the rising height, lifted between root and end by half
                // the hair's width (the default taper, 0.008 to 0.004) so that its surface, not its
                // centreline, rests on the plane.
                const IndexRange r = out.points_of(curves[i]);
                for (int64_t p = r.begin; p < r.end; ++p) {
                    const float u = float(p - r.begin) / float(r.size() - 1);
                    // (The half width one sample rootwards, so the arc-length taper never exceeds it.)
                    const float v = std::max(0.0f, u - 1.0f / float(r.size() - 1));
                    const float half = p == r.begin || p == r.end - 1 ? 0.0f : 0.5f * (0.008f * (1.0f - v) + 0.004f * v);
                    EXPECT_NEAR3(P[p], lerp(root, tip, u) + float3(0.0f, half, 0.0f), 1e-5f);
                }
            }
        }
    }
}

TEST(Partition, SegmentsFollowTheScalpInsteadOfCuttingThroughIt)
{
    // Guides lying on the sphere 0.6 rad apart: chords between them dip 4.5% of the radius inside.
    const std::vector<Arc> arcs = {{0.0f, -0.5f, 0.5f}, {0.6f, -0.5f, 0.5f}};
    PartitionParams params;
    params.count = 5;
    params.samples = 12;
    params.mediate = {1.0f, 1.0f};
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    const CurveSet out = partition(meridian_guides(arcs), sphere, params);
    float lowest = INFINITY;
    for (const float3& p : out.positions()) lowest = std::min(lowest, sphere.distance(p));
    EXPECT_GE(lowest, -1e-5f);
    EXPECT_LE(lowest, 1e-5f);  // and they lie on it, since the source is on it too
}

// What a person sees: edge hairs resting on the skin, not in it. Guides on the unit sphere, so every
// chord between root and end dips inside: each point between them ends with its surface on the
// sphere, its centre half its written width out (it was on the sphere, half the hair under the
// skin: renderers drew broken dashes, a trial). Roots grow from the surface.
TEST(Partition, EdgeHairsRestOnTheScalpNotInIt)
{
    const std::vector<Arc> arcs = {{0.0f, -0.5f, 0.5f}, {0.6f, -0.5f, 0.5f}};
    PartitionParams params;
    params.count = 7;
    params.samples = 10;
    params.widths.root = 0.02f;
    params.widths.tip = 0.01f;
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    const CurveSet out = partition(meridian_guides(arcs), sphere, params);
    ASSERT_EQ(out.num_curves(), 14u);
    const auto P = out.positions();
    const auto W = out.find<float>(Domain::Point, attr::width);
    ASSERT_EQ(W.size(), P.size());
    for (size_t c = 0; c < out.num_curves(); ++c) {
        const IndexRange r = out.points_of(c);
        EXPECT_NEAR(sphere.distance(P[size_t(r.begin)]), 0.0f, 1e-5f) << "root off the surface";
        for (int64_t p = r.begin + 1; p < r.end - 1; ++p) {
            // Its surface clear of the sphere, and resting on it: no more than a tenth of its
            // width above.
            const float d = sphere.distance(P[size_t(p)]), half = 0.5f * W[size_t(p)];
            EXPECT_GE(d, half - 1e-6f) << "curve " << c << " point " << p - r.begin << ": the hair's surface cuts the skin";
            EXPECT_LE(d, half + 0.1f * W[size_t(p)]) << "curve " << c << " point " << p - r.begin << ": the hair floats";
        }
    }
}

TEST(Partition, EndsOnACoarseGuidesChordsAreLiftedOntoTheScalp)
{
    // Guides of 5 points over 1 rad of the unit sphere: each chord dips up to 1 - cos(0.125) =
    // 0.0078 inside it, and a station between two points lies on a chord. Its segment's end is put
    // on the sphere straight out from it (the closed form: the station normalised), every point
    // of every segment outside the sphere.
    const std::vector<Arc> arcs = {{0.0f, -0.5f, 0.5f}, {0.6f, -0.5f, 0.5f}};
    CurveSet coarse = CurveSet::from_counts(std::vector<int64_t>{5, 5});
    auto C = coarse.positions_for_write();
    for (size_t g = 0; g < 2; ++g) {
        for (int k = 0; k < 5; ++k) C[g * 5 + size_t(k)] = on_sphere(arcs[g].lat0 + (arcs[g].lat1 - arcs[g].lat0) * float(k) / 4.0f, arcs[g].lon);
    }
    PartitionParams params;
    params.count = 6;
    params.samples = 8;
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    const CurveSet out = partition(coarse, sphere, params);
    ASSERT_EQ(out.num_curves(), 12u);
    float deepest_station = 0.0f;
    const auto src = coarse.positions();
    for (int g = 0; g < 2; ++g) {
        // Stations 1/6 of the polyline apart, centred: at (i + 1/2) / 6 of its length.
        const std::vector<float3> poly(src.begin() + g * 5, src.begin() + g * 5 + 5);
        const std::vector<double> cum = cumulative_lengths(poly);
        // Each has its one neighbour on one side.
        const auto curves = curves_of(out, g, curves_of(out, g, 0).empty() ? 1 : 0);
        ASSERT_EQ(curves.size(), 6u);
        for (int i = 0; i < 6; ++i) {
            const float3 station = point_at_length(poly, cum, cum.back() * (i + 0.5) / 6.0);
            deepest_station = std::min(deepest_station, sphere.distance(station));
            EXPECT_NEAR3(last_point(out, curves[size_t(i)]), normalize(station), 1e-5f);
            const IndexRange r = out.points_of(curves[size_t(i)]);
            for (int64_t p = r.begin; p < r.end; ++p) EXPECT_GE(sphere.distance(out.positions()[p]), -1e-5f);
        }
    }
    EXPECT_LT(deepest_station, -1e-3f);  // the case is real: some stations lie well inside
}

TEST(Partition, EveryKGroupsConvergeOnTheirCentroid)
{
    const CurveSet guides = straight_guides({0.0f, 1.0f});
    PartitionParams params;
    params.mediate = {0.5f, 0.5f};  // roots on the midpoint, where the closed form below puts them
    params.count = 12;
    params.centroids = CentroidMode::Every;
    params.every = 5;
    for (const float converge : {1.0f, 0.6f, 0.0f}) {
        params.converge = converge;
        const CurveSet out = partition(guides, AnalyticPlane({0, 0, 0}, {0, 1, 0}), params);
        const auto group = out.find<int32_t>(Domain::Curve, "group");
        const auto curves = curves_of(out, 0, 0);
        ASSERT_EQ(curves.size(), 12u);
        for (int i = 0; i < 12; ++i) {
            const int g = i / 5;
            EXPECT_EQ(group[curves[i]], g);
            // Stations 1/3 apart from 1/6; a group's centroid is its middle station (the last has 2).
            // Ends: converge 1 on the centroid (the talk's), 0 at the own station, between: the
            // station's offset from the centroid times 1 - converge.
            const int members = std::min(5, 12 - 5 * g);
            const float centroid = 1.0f / 6.0f + (5 * g + 0.5f * (members - 1)) / 3.0f, station = 1.0f / 6.0f + i / 3.0f;
            const float z = centroid + (station - centroid) * (1.0f - converge);
            SCOPED_TRACE(converge);
            EXPECT_NEAR3(last_point(out, curves[i]), float3(0, 0.2f, z), 1e-5f);
            EXPECT_NEAR3(first_point(out, curves[i]), float3(0.5f, 0, station), 1e-5f);
        }
    }
}

TEST(Partition, KnotCentroidsAreTheBraidsKnotCentres)
{
    // A 4-unit guide: knot k is centred where F t = k + 1/2 (ops/braid.h), each segment joins the
    // nearest knot centre.
    const CurveSet guides = straight_guides({0.0f, 1.0f});
    const AnalyticPlane plane({0, 0, 0}, {0, 1, 0});
    PartitionParams params;
    params.count = 16;  // stations at z = 0.125, 0.375, ...
    params.centroids = CentroidMode::Knots;
    params.converge = 1.0f;  // every segment on its centroid, where the closed form puts it
    for (int run = 0; run < 2; ++run) {
        // F = 4 given directly, or as 1-unit knots on the 4-unit guide: centres at z = 0.5, 1.5, 2.5, 3.5.
        params.knots.frequency.reset();
        params.knots.knot_length.reset();
        if (run == 0) params.knots.frequency = 4.0f;
        else params.knots.knot_length = 1.0f;
        const CurveSet out = partition(guides, plane, params);
        const auto group = out.find<int32_t>(Domain::Curve, "group");
        const auto curves = curves_of(out, 0, 0);
        ASSERT_EQ(curves.size(), 16u);
        for (int i = 0; i < 16; ++i) {
            EXPECT_EQ(group[curves[i]], i / 4);
            EXPECT_NEAR3(last_point(out, curves[i]), float3(0, 0.2f, i / 4 + 0.5f), 1e-5f);
        }
    }
    // 1.5-unit knots: F = 8/3, centres at 0.75, 2.25, 3.75 (a fourth would be centred past the tip).
    params.knots.knot_length = 1.5f;
    const CurveSet out = partition(guides, plane, params);
    const auto group = out.find<int32_t>(Domain::Curve, "group");
    const auto curves = curves_of(out, 1, 1);
    ASSERT_EQ(curves.size(), 16u);
    for (int i = 0; i < 16; ++i) {
        const float z = 0.125f + 0.25f * i;
        const int k = z < 1.5f ? 0 : (z < 3.0f ? 1 : 2);
        EXPECT_EQ(group[curves[i]], k);
        EXPECT_NEAR3(last_point(out, curves[i]), float3(1, 0.2f, 0.75f + 1.5f * k), 1e-5f);
    }
}

TEST(Partition, GivenCentroidsGatherTheNearestSegments)
{
    const std::vector<Arc> arcs = {{0.0f, -0.5f, 0.5f}, {0.3f, -0.5f, 0.5f}};
    PartitionParams params;
    params.count = 10;
    params.centroids = CentroidMode::Points;
    params.converge = 1.0f;  // every segment on its centroid, where the closed form puts it
    params.centroid_points = {{0, 0.75f}, {0, 0.25f}};  // any order; guide 1 has none
    const CurveSet out = partition(meridian_guides(arcs), AnalyticSphere({0, 0, 0}, 1.0f), params);
    const auto group = out.find<int32_t>(Domain::Curve, "group");
    const auto mine = curves_of(out, 0, 0);
    ASSERT_EQ(mine.size(), 10u);
    for (int i = 0; i < 10; ++i) {
        const int g = i < 5 ? 0 : 1;
        EXPECT_EQ(group[mine[i]], g);
        EXPECT_NEAR3(last_point(out, mine[i]), on_sphere(g == 0 ? -0.25f : 0.25f, 0.0f), 2e-5f);
    }
    // Guide 1 has no centroids: each segment ends at its own station, group = station.
    const auto theirs = curves_of(out, 1, 1);
    for (int i = 0; i < 10; ++i) {
        EXPECT_EQ(group[theirs[i]], i);
        EXPECT_NEAR3(last_point(out, theirs[i]), on_sphere(-0.5f + (i + 0.5f) / 10.0f, 0.3f), 2e-5f);
    }
}

TEST(Partition, SpacingPutsStationsThatFarApartCentredOnTheSource)
{
    PartitionParams params;
    params.count = 0;
    params.spacing = 0.7f;  // 4 units: 5 stations, 0.7 apart, centred: 0.6, 1.3, ..., 3.4
    const CurveSet out = partition(straight_guides({0.0f, 1.0f}), AnalyticPlane({0, 0, 0}, {0, 1, 0}), params);
    const auto curves = curves_of(out, 0, 0);
    ASSERT_EQ(curves.size(), 5u);
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(last_point(out, curves[i]).z, 0.6f + 0.7f * i, 1e-5f);
}

TEST(Partition, GivenAdjacencyOnlyPartitionsTheListedSources)
{
    PartitionParams params;
    params.mediate = {0.5f, 0.5f};  // roots on the midpoint, where the closed form below puts them
    params.count = 3;
    params.adjacent = {{1, -1, 2}};  // guide 2 declared on guide 1's right, whatever the geometry says
    const CurveSet out = partition(straight_guides({0.0f, 1.0f, 2.0f}), AnalyticPlane({0, 0, 0}, {0, 1, 0}), params);
    ASSERT_EQ(out.num_curves(), 3u);
    EXPECT_EQ(curves_of(out, 1, 1).size(), 3u);
    EXPECT_NEAR3(first_point(out, 0), float3(1.5f, 0, 4.0f / 6.0f), 1e-5f);
}

TEST(Partition, MaxHeightDropsStationsHighAboveTheScalp)
{
    CurveSet guides = straight_guides({0.0f, 1.0f});
    // Tilt the guides up: height 0.2 at z = 0 rising to 2.2 at z = 4.
    for (float3& p : guides.positions_for_write()) p.y += 0.5f * p.z;
    PartitionParams params;
    params.count = 8;
    params.max_height = 1.0f;  // stations at z <= 1.6
    const CurveSet out = partition(guides, AnalyticPlane({0, 0, 0}, {0, 1, 0}), params);
    const auto curves = curves_of(out, 0, 0);
    ASSERT_EQ(curves.size(), 3u);  // z = 0.25, 0.75, 1.25
    for (size_t c : curves) EXPECT_LE(last_point(out, c).y, 1.0f);
}

TEST(Partition, CarriesGuideAttributesAndGivesStableIds)
{
    CurveSet guides = straight_guides({0.0f, 1.0f, 2.0f});
    auto tag = guides.add<float>(Domain::Curve, "braid_width");
    auto id = guides.add<int64_t>(Domain::Curve, "id");
    for (int c = 0; c < 3; ++c) { tag[c] = 10.0f + c; id[c] = 100 + c; }
    PartitionParams params;
    params.count = 4;
    const AnalyticPlane plane({0, 0, 0}, {0, 1, 0});
    const CurveSet out = partition(guides, plane, params);
    const auto out_tag = out.find<float>(Domain::Curve, "braid_width");
    const auto out_guide = out.find<int32_t>(Domain::Curve, "guide");
    const auto out_id = out.find<int64_t>(Domain::Curve, "id");
    ASSERT_EQ(out_tag.size(), out.num_curves());
    ASSERT_EQ(out_id.size(), out.num_curves());
    for (size_t c = 0; c < out.num_curves(); ++c) EXPECT_EQ(out_tag[c], 10.0f + out_guide[c]);
    std::vector<int64_t> sorted(out_id.begin(), out_id.end());
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "segment ids must be unique";
    // Removing guide 0 leaves guide 2's segment ids unchanged: ids hash the guide id, not its index.
    const CurveSet two = [&] {
        CurveSet g = straight_guides({1.0f, 2.0f});
        auto i2 = g.add<int64_t>(Domain::Curve, "id");
        i2[0] = 101;
        i2[1] = 102;
        return g;
    }();
    const CurveSet out2 = partition(two, plane, params);
    const auto a = curves_of(out, 2, 1), b = curves_of(out2, 1, 1);
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) EXPECT_EQ(out_id[a[k]], out2.find<int64_t>(Domain::Curve, "id")[b[k]]);
}

TEST(Partition, DeterministicAcrossThreadCountsWithJitter)
{
    std::vector<Arc> arcs;
    for (int k = 0; k < 40; ++k) arcs.push_back({0.05f * k + 0.01f * float(k % 3), -0.6f + 0.01f * k, 0.6f});
    const CurveSet guides = meridian_guides(arcs, 60);
    PartitionParams params;
    params.jitter = 0.8f;
    params.seed = 5;
    params.samples = 7;
    const AnalyticSphere sphere({0, 0, 0}, 1.0f);
    auto run = [&](int threads) {
        ThreadLimit limit(threads);
        return partition(guides, sphere, params);
    };
    const CurveSet one = run(1), two = run(2);
    ASSERT_EQ(one.num_points(), two.num_points());
    ASSERT_GT(one.num_curves(), 40u * 24u);
    EXPECT_EQ(0, std::memcmp(one.positions().data(), two.positions().data(), one.num_points() * sizeof(float3)));
    for (const char* name : {"guide", "side", "group"}) {
        const auto a = one.find<int32_t>(Domain::Curve, name), b = two.find<int32_t>(Domain::Curve, name);
        EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << name;
    }
    // The jitter does move stations, within half a spacing either way.
    params.jitter = 0.0f;
    const CurveSet still = partition(guides, sphere, params);
    ASSERT_EQ(still.num_points(), one.num_points());
    EXPECT_NE(0, std::memcmp(still.positions().data(), one.positions().data(), one.num_points() * sizeof(float3)));
}

// --- rejection ----------------------------------------------------------------------------------------

namespace {
void expect_rejected(const std::function<void(PartitionParams&)>& edit, const std::string& needle)
{
    PartitionParams params;
    edit(params);
    try {
        partition(straight_guides({0.0f, 1.0f}), AnalyticPlane({0, 0, 0}, {0, 1, 0}), params);
        ADD_FAILURE() << "accepted; expected an error mentioning '" << needle << "'";
    }
    catch (const InvalidParam& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}
}  // namespace

TEST(Partition, RefusesAbsurdOutputBeforeAllocating)
{
    PartitionParams params;
    params.count = 0;
    params.spacing = 1e-9f;  // 4-unit guides: 4e9 segments a side
    try {
        partition(straight_guides({0.0f, 1.0f}), AnalyticPlane({0, 0, 0}, {0, 1, 0}), params);
        ADD_FAILURE() << "accepted";
    }
    catch (const LimitExceeded& e) {
        EXPECT_NE(std::string(e.what()).find("raise `spacing`"), std::string::npos) << e.what();
    }
}

TEST(Partition, RejectsEachInvalidOption)
{
    expect_rejected([](auto& p) { p.mediate = {-0.1f, 0.5f}; }, "`mediate` must be lo,hi with 0 <= lo <= hi <= 1 (got -0.1,0.5)");
    expect_rejected([](auto& p) { p.mediate = {0.2f, 1.5f}; }, "`mediate` must be lo,hi with 0 <= lo <= hi <= 1 (got 0.2,1.5)");
    expect_rejected([](auto& p) { p.mediate = {0.4f, 0.3f}; }, "`mediate` must be lo,hi with 0 <= lo <= hi <= 1 (got 0.4,0.3)");
    expect_rejected([](auto& p) { p.mediate = {NAN, 0.5f}; }, "`mediate`");
    expect_rejected([](auto& p) { p.units_per_cm = 0.0f; }, "`units_per_cm` must be a finite number > 0 (got 0)");
    expect_rejected([](auto& p) { p.count = -3; }, "`count` must be >= 1, or 0 for automatic (got -3)");
    expect_rejected([](auto& p) { p.count = 5; p.spacing = 0.5f; }, "`count` and `spacing` are exclusive");
    expect_rejected([](auto& p) { p.spacing = -1; }, "`spacing` must be > 0 scene units, or 0 for automatic (got -1)");
    expect_rejected([](auto& p) { p.samples = 1; }, "`samples` must be >= 2 (got 1)");
    expect_rejected([](auto& p) { p.widths.root = 0; }, "--root-width must be a finite number > 0");
    expect_rejected([](auto& p) { p.jitter = 2; }, "`jitter` must be in [0, 1] (got 2)");
    expect_rejected([](auto& p) { p.max_gap = -1; }, "`max_gap` must be >= 0");
    expect_rejected([](auto& p) { p.max_height = INFINITY; }, "`max_height`");
    expect_rejected([](auto& p) { p.centroids = CentroidMode::Every; }, "every:K needs K >= 1 (got 0)");
    expect_rejected([](auto& p) { p.centroids = CentroidMode::Knots; p.knots.frequency = -1.0f; }, "`frequency` must be >= 0 knots per guide (got -1)");
    expect_rejected([](auto& p) { p.centroids = CentroidMode::Knots; p.knots.knot_length = 0.0f; }, "`knot_length` must be > 0 scene units (got 0)");
    expect_rejected([](auto& p) { p.centroids = CentroidMode::Knots; p.knots.frequency = 2.0f; p.knots.knot_length = 1.0f; }, "are exclusive");
    expect_rejected([](auto& p) { p.centroids = CentroidMode::Points; p.centroid_points = {{0, 1.2f}}; }, "in [0, 1] (got 1.2 for guide 0)");
    expect_rejected([](auto& p) { p.centroids = CentroidMode::Points; p.centroid_points = {{5, 0.5f}}; }, "`centroids`: guide 5 out of range (2 guides");
    expect_rejected([](auto& p) { p.adjacent = {{2, 0, -1}}; }, "`adjacent`: source guide 2 out of range");
    expect_rejected([](auto& p) { p.adjacent = {{0, 7, -1}}; }, "left guide 7 of source 0 out of range");
    expect_rejected([](auto& p) { p.adjacent = {{0, -1, -2}}; }, "right guide -2 of source 0 out of range");
    expect_rejected([](auto& p) { p.adjacent = {{0, 0, 1}}; }, "guide 0 cannot be its own neighbour");
    expect_rejected([](auto& p) { p.adjacent = {{0, 1, -1}, {0, -1, 1}}; }, "source guide 0 is listed twice");
}
