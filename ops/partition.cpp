#include "ops/partition.h"
#include "ops/root_uv.h"

#include "fields/keep_outside.h"
#include "fields/surface.h"
#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace groom {

namespace {

std::string num(float v) { return format_number(v); }

void require(bool ok, const std::string& message)
{
    if (!ok) throw InvalidParam("partition: " + message);
}

/// One segment planned in the first pass: everything but its sampled interior.
struct Plan {
    int32_t side = 0, group = 0, station = 0;
    float3 root, end;
};

// Output points refused beyond this even within a large `memory` budget: station counts are int.
constexpr double kMaxOutputPoints = 2e9;
constexpr uint64_t kJitterStream = 0x9a27;  // Rng stream for station jitter (per side: + side)
constexpr uint64_t kMediateStream = 0x9a37;  // Rng stream for the root's place across the gap (per side: + side)

/// Where the hair region ends (the hairline, or a parting's bare line) walking on the scalp from p's
/// foot in direction `dir` (kept in the tangent plane), in kHairlineSteps steps of reach /
/// kHairlineSteps: the last haired place, to a sixty-fourth of a step (bisection). False when the
/// walk stays haired (or leaves the scalp) that far. A fixed count of steps: a step of reach / 20
/// added to a running length rounded to nothing for a tiny reach (--max-gap 1e-45) and never ended.
constexpr int kHairlineSteps = 20;
bool hairline_beside(const Surface& scalp, const HairRegion& region, const float3& p, float3 dir, float reach, float3& edge)
{
    const float step = reach / float(kHairlineSteps);
    if (!(step > 0.0f) || !std::isfinite(step)) return false;
    float3 x = scalp.closest_point(p);
    if (!region.haired(x)) return false;
    for (int k = 0; k < kHairlineSteps; ++k) {
        const float3 n = scalp.normal(x);
        dir = normalize(dir - n * dot(dir, n), float3(0, 0, 0));
        if (length_squared(dir) == 0.0f) return false;
        const float3 next = scalp.closest_point(x + dir * step);
        if (!isfinite(next)) return false;
        if (!region.haired(next)) {
            float3 in = x, out = next;
            for (int b = 0; b < 6; ++b) {
                const float3 mid = scalp.closest_point(lerp(in, out, 0.5f));
                (region.haired(mid) ? in : out) = mid;
            }
            edge = in;
            return true;
        }
        x = next;
    }
    return false;
}

}  // namespace

void PartitionParams::validate() const
{
    require(std::isfinite(mediate.lo) && std::isfinite(mediate.hi) && mediate.lo >= 0.0f && mediate.lo <= mediate.hi && mediate.hi <= 1.0f,
            "`mediate` must be lo,hi with 0 <= lo <= hi <= 1 (got " + num(mediate.lo) + "," + num(mediate.hi) + ")");
    require(!(count != 0 && spacing != 0.0f), "`count` and `spacing` are exclusive (got both)");
    require(count >= 0, "`count` must be >= 1, or 0 for automatic (got " + std::to_string(count) + ")");
    require(std::isfinite(spacing) && spacing >= 0.0f, "`spacing` must be > 0 scene units, or 0 for automatic (got " + num(spacing) + ")");
    require(samples >= 2, "`samples` must be >= 2 (got " + std::to_string(samples) + ")");
    widths.validate("partition");
    require(std::isfinite(units_per_cm) && units_per_cm > 0.0f, "`units_per_cm` must be a finite number > 0 (got " + num(units_per_cm) + ")");
    require(std::isfinite(jitter) && jitter >= 0.0f && jitter <= 1.0f, "`jitter` must be in [0, 1] (got " + num(jitter) + ")");
    require(std::isfinite(converge) && converge >= 0.0f && converge <= 1.0f, "`converge` must be in [0, 1] (got " + num(converge) + ")");
    require(std::isfinite(max_gap) && max_gap >= 0.0f, "`max_gap` must be >= 0 scene units, 0 = automatic (got " + num(max_gap) + ")");
    require(std::isfinite(max_height) && max_height >= 0.0f,
            "`max_height` must be >= 0 scene units, 0 = no limit (got " + num(max_height) + ")");
    if (centroids == CentroidMode::Every) {
        require(every >= 1, "`centroids` every:K needs K >= 1 (got " + std::to_string(every) + ")");
    }
    if (centroids == CentroidMode::Knots) {
        require(!(knots.frequency && knots.knot_length), "`frequency` and `knot_length` are exclusive (got both)");
        if (knots.frequency) {
            require(std::isfinite(*knots.frequency) && *knots.frequency >= 0.0f,
                    "`frequency` must be >= 0 knots per guide (got " + num(*knots.frequency) + ")");
        }
        if (knots.knot_length) {
            require(std::isfinite(*knots.knot_length) && *knots.knot_length > 0.0f,
                    "`knot_length` must be > 0 scene units (got " + num(*knots.knot_length) + ")");
        }
        knots.validate();  // the remap options, worded as groom braid words them
    }
    if (centroids == CentroidMode::Points) {
        for (const CentroidPoint& c : centroid_points) {
            require(std::isfinite(c.u) && c.u >= 0.0f && c.u <= 1.0f,
                    "`centroids`: arc-length fraction must be in [0, 1] (got " + num(c.u) + " for guide " + std::to_string(c.guide) + ")");
        }
    }
}

CurveSet partition(const CurveSet& guides, const Surface& scalp, const PartitionParams& params, Progress* progress)
{
    params.validate();
    const size_t nc = guides.num_curves();
    const auto P = guides.positions();
    const std::string guide_range = "(" + std::to_string(nc) + " guides: 0 to " + std::to_string(int64_t(nc) - 1) + ")";

    // Neighbours: the user's, checked against the guide count, or found.
    std::vector<AdjacentGuides> adjacent(nc);
    std::vector<bool> listed(nc, params.adjacent.empty());
    if (params.adjacent.empty()) {
        adjacent = find_adjacent_guides(guides, scalp, params.max_gap, progress);
    }
    else {
        for (size_t c = 0; c < nc; ++c) adjacent[c].source = int32_t(c);
        for (const AdjacentGuides& a : params.adjacent) {
            auto in_range = [&](int32_t g) { return g >= 0 && size_t(g) < nc; };
            require(in_range(a.source), "`adjacent`: source guide " + std::to_string(a.source) + " out of range " + guide_range);
            require(a.left == -1 || in_range(a.left), "`adjacent`: left guide " + std::to_string(a.left) + " of source " +
                                                          std::to_string(a.source) + " out of range " + guide_range + " or -1");
            require(a.right == -1 || in_range(a.right), "`adjacent`: right guide " + std::to_string(a.right) + " of source " +
                                                            std::to_string(a.source) + " out of range " + guide_range + " or -1");
            require(a.left != a.source && a.right != a.source,
                    "`adjacent`: guide " + std::to_string(a.source) + " cannot be its own neighbour");
            require(!listed[a.source], "`adjacent`: source guide " + std::to_string(a.source) + " is listed twice");
            listed[a.source] = true;
            adjacent[a.source] = a;
        }
    }

    // Centroids per guide, as sorted arc-length fractions.
    std::vector<std::vector<float>> centroid_u(nc);
    if (params.centroids == CentroidMode::Points) {
        for (const CentroidPoint& c : params.centroid_points) {
            require(c.guide >= 0 && size_t(c.guide) < nc, "`centroids`: guide " + std::to_string(c.guide) + " out of range " + guide_range);
            centroid_u[c.guide].push_back(c.u);
        }
        for (auto& u : centroid_u) std::sort(u.begin(), u.end());
    }

    // Closest-point indexes for the guides that are someone's neighbour.
    std::vector<bool> needed(nc, false);
    for (size_t c = 0; c < nc; ++c) {
        if (!listed[c]) continue;
        if (adjacent[c].left >= 0) needed[adjacent[c].left] = true;
        if (adjacent[c].right >= 0) needed[adjacent[c].right] = true;
    }
    std::vector<std::optional<PolylineNearest>> nearest(nc);
    parallel_for(int64_t(nc), 16, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = guides.points_of(c);
            if (needed[c]) nearest[c].emplace(P.subspan(r.begin, r.size()));
        }
    });

    // Neither count nor spacing: a spacing from the guides' own layout, so the density of edge hairs
    // does not depend on the scene's units.
    // With no gap to measure (a single guide), the automatic count is kAutoCountWithoutGap a side.
    const bool automatic = params.count == 0 && params.spacing == 0.0f;
    const bool to_hairline = params.region && params.region->has_hairline();
    const double gap = automatic || to_hairline ? typical_guide_gap(guides, GuidePointIndex(guides)) : 0.0;
    double spacing = params.spacing;
    if (automatic) spacing = gap > 0.0 ? gap / double(kAutoSpacingPerGap) : 0.0;
    // A side with no neighbour reaches the hairline, when there is one within this: the outermost
    // rows' edge hairs cover the scalp out to it (without, the sides of a head of cornrows stayed bald
    // inside the hairline, like an undercut: a trial).
    const float hairline_reach = params.max_gap > 0.0f ? params.max_gap : float(2.0 * gap);
    // Refuse before allocating anything when the options would make an absurd number of segments
    // (a --spacing in the wrong units, say).
    auto station_count = [&](double length) {
        if (params.count > 0) return double(params.count);
        if (!(spacing > 0.0)) return double(kAutoCountWithoutGap);
        return std::max(1.0, std::floor(length / spacing));
    };
    // Every side that can get segments counts: a side with a neighbour, and with a hairline a side
    // without one (it walks to the hairline; uncounted, --spacing 1e-9 there overflowed the station
    // count past the memory check, a review).
    const bool walks = to_hairline && hairline_reach > 0.0f;
    double planned = 0.0;
    for (size_t c = 0; c < nc; ++c) {
        if (!listed[c]) continue;
        const IndexRange r = guides.points_of(c);
        const double length = polyline_length(P.subspan(r.begin, r.size()));
        planned += station_count(length) * ((adjacent[c].left >= 0 || walks) + (adjacent[c].right >= 0 || walks));
    }
    // Per segment: its plan, its points (position, width) and its curve columns (guide, side, group,
    // id, source curve, root UV, and every curve column of the guides, carried).
    const std::string segments = planned < 9e18 ? std::to_string(int64_t(planned)) : format_number(planned);
    check_memory("partition: " + segments + " segments (`count` or `spacing` per side of each guide) x " +
                     std::to_string(params.samples) + " `samples`",
                 planned * (double(params.samples) * (12.0 + 4.0) + double(sizeof(Plan)) + 4.0 * 3.0 + 8.0 + 8.0 + 8.0 + bytes_per_curve(guides)),
                 "raise `spacing` or lower `count` / `samples`");
    if (planned * params.samples > kMaxOutputPoints) {
        throw LimitExceeded("partition: the options ask for " + segments + " segments of " + std::to_string(params.samples) +
                            " points, more than " + std::to_string(int64_t(kMaxOutputPoints)) +
                            " points in all; raise `spacing` or lower `count` / `samples`");
    }

    const std::vector<int64_t> ids = guides.curve_ids();
    std::vector<std::vector<Plan>> plans(nc);
    {
        ProgressStep step(progress, "partition: segments", int64_t(nc));
        parallel_for(int64_t(nc), 1, [&](int64_t b, int64_t e) {
            for (int64_t c = b; c < e; ++c) {
                step.advance(1);
                const IndexRange r = guides.points_of(c);
                if (!listed[c] || r.size() < 2) continue;
                const auto src = P.subspan(r.begin, r.size());
                const std::vector<double> cum = cumulative_lengths(src);
                const double length = cum.back();
                if (!(length > 0.0)) continue;
                // Stations: n of them `step` apart, centred on the source.
                const int n = int(station_count(length));  // bounded by the check above
                const double step = params.count > 0 || !(spacing > 0.0) ? length / n : spacing;
                const double start = 0.5 * (length - (n - 1) * step);
                // Centroids along this source as arc-length fractions, sorted.
                const std::vector<float> us = params.centroids == CentroidMode::Points ? centroid_u[c]
                                              : params.centroids == CentroidMode::Knots  ? braid_knot_parameters(params.knots, length)
                                                                                         : std::vector<float>{};
                const int32_t sides[2] = {adjacent[c].left, adjacent[c].right};
                const std::vector<float3> tangents = walks ? polyline_tangents(src) : std::vector<float3>{};  // for the walk only
                for (int side = 0; side < 2; ++side) {
                    const bool beside_hairline = sides[side] < 0;
                    if (beside_hairline && !walks) continue;
                    const PolylineNearest* other = beside_hairline ? nullptr : &*nearest[sides[side]];
                    const Rng rng(params.seed, uint64_t(ids[c]), kJitterStream + side);
                    const Rng across(params.seed, uint64_t(ids[c]), kMediateStream + side);
                    for (int i = 0; i < n; ++i) {
                        const double jitter = params.jitter > 0.0f
                                                  ? (double(rng.at(uint64_t(i)) >> 11) * 0x1.0p-53 - 0.5) * params.jitter * step
                                                  : 0.0;
                        const double s = std::clamp(start + i * step + jitter, 0.0, length);
                        const float3 p = point_at_length(src, cum, s);
                        if (params.max_height > 0.0f && scalp.distance(p) > params.max_height) continue;
                        PolylineNearest::Hit hit;
                        if (other) {
                            hit = other->closest(p);
                            if (hit.segment < 0) continue;
                            if (params.max_gap > 0.0f && hit.distance > params.max_gap) continue;
                        }
                        else {
                            // No neighbour on this side: the hairline, straight out sideways on the scalp.
                            const float3 n = scalp.normal(p);
                            const float3 left = left_direction(n, tangent_at_length(src, cum, tangents, s));
                            if (!hairline_beside(scalp, *params.region, p, side == 0 ? left : -left, hairline_reach, hit.point)) {
                                continue;
                            }
                        }
                        Plan plan;
                        plan.side = side;
                        plan.station = i;
                        // Sec. 2.2: rooted between the source point and the nearest adjacent point, on
                        // the scalp, at a fraction drawn from `mediate` (exactly lo when lo = hi).
                        const FloatRange& m = params.mediate;
                        // Density rising linearly toward hi (the square root of a uniform draw): every
                        // hair covers the scalp from its root to the braid, so with uniform roots the
                        // cover thinned to nothing at the parting and the bare line read three times
                        // wider than the gap left (a trial); this way a third of the hairs still cross
                        // 80% of the way out.
                        const double u = std::sqrt(double(across.at(uint64_t(i)) >> 11) * 0x1.0p-53);
                        // Toward the hairline there is no parting to leave bare: roots reach the edge.
                        const float hi = other ? m.hi : 1.0f;
                        const float f = hi > m.lo ? m.lo + (hi - m.lo) * float(u) : m.lo;
                        plan.root = scalp.closest_point(lerp(p, hit.point, std::min(f, hi)));
                        if (params.region && !params.region->haired(plan.root)) continue;  // outside the hairline, on a parting
                        double end_s = s;
                        plan.group = i;
                        if (params.centroids == CentroidMode::Every) {
                            const int g = i / params.every;
                            const int members = std::min(params.every, n - g * params.every);
                            plan.group = g;
                            end_s = start + step * (g * params.every + 0.5 * (members - 1));
                        }
                        else if (!us.empty()) {
                            // The nearest centroid by arc length; ties to the earlier one.
                            int best = 0;
                            for (int k = 1; k < int(us.size()); ++k) {
                                if (std::fabs(us[k] * length - s) < std::fabs(us[best] * length - s)) best = k;
                            }
                            plan.group = best;
                            end_s = us[best] * length;
                        }
                        // A group's hairs end spread over (1 - converge) of their stations' span around
                        // its centroid: all on one point, they fanned out of each knot like a starburst,
                        // with bare notches between the fans (a trial's close-ups).
                        if (end_s != s) end_s = std::clamp(end_s + (s - end_s) * double(1.0f - params.converge), 0.0, length);
                        plan.end = end_s == s ? p : point_at_length(src, cum, end_s);
                        plans[c].push_back(plan);
                    }
                }
            }
        });
    }

    // Count -> scan -> fill.
    std::vector<int64_t> first_curve(nc + 1, 0);
    for (size_t c = 0; c < nc; ++c) first_curve[c + 1] = first_curve[c] + int64_t(plans[c].size());
    const int64_t total = first_curve[nc];
    std::vector<int64_t> counts(size_t(total), params.samples);
    CurveSet dst = CurveSet::from_counts(counts);
    auto out_P = dst.positions_for_write();
    auto out_guide = dst.add<int32_t>(Domain::Curve, "guide");
    auto out_side = dst.add<int32_t>(Domain::Curve, "side");
    auto out_group = dst.add<int32_t>(Domain::Curve, "group");
    auto out_id = dst.add<int64_t>(Domain::Curve, attr::id);
    std::vector<int64_t> src_curve(static_cast<size_t>(total), 0);
    const int samples = params.samples;
    // The hair's surface, not its centreline, rests on the scalp: each point between the root and
    // the end (in the braid) is kept half its width out (the widths written below, linear from root to tip). At 0 the centreline
    // lay on the skin, so half of every hair was under it and renderers drew broken dashes (a
    // trial measured 74-91% of edge-hair points inside a finer field of the same head).
    const HairWidths taper = params.widths.resolved(params.units_per_cm);
    const float root_half = 0.5f * *taper.root, tip_half = 0.5f * *taper.tip;
    // And on the mesh, not the field: a level set's surface strays from a scan's finer detail by
    // more than a hair's width (Surface::surface_tolerance).
    const float lift = scalp.surface_tolerance();
    // Its own step: most of the op's time is here, and -v showed only the planning ("segments done
    // in 2.52s" of a 17 s run: a trial).
    const ProgressStep lay(progress, "partition: points on the scalp", int64_t(nc));
    parallel_for(int64_t(nc), 1, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            lay.advance(1);
            for (size_t k = 0; k < plans[c].size(); ++k) {
                const Plan& plan = plans[c][k];
                const int64_t curve = first_curve[c] + int64_t(k);
                src_curve[curve] = c;
                out_guide[curve] = int32_t(c);
                out_side[curve] = plan.side;
                out_group[curve] = plan.group;
                const uint64_t key = (uint64_t(plan.side) << 32) | uint64_t(uint32_t(plan.station));
                out_id[curve] = int64_t(mix64(mix64(uint64_t(ids[c])) ^ key) >> 1);
                const int64_t first = dst.points_of(curve).begin;
                // Follow the scalp: the height above it rises linearly from the root (0) to the end.
                const float end_height = std::max(0.0f, scalp.distance(plan.end));
                for (int j = 0; j < samples; ++j) {
                    const float u = float(j) / float(samples - 1);
                    float3 x = lerp(plan.root, plan.end, u);
                    if (j == 0) x = plan.root;
                    else if (j == samples - 1) {
                        // On the guide, which is a polyline: between its points its chords dip under
                        // a curved scalp (up to 0.015 on ICT's 48-point rows, 3% of a voxel), and an
                        // end there would be under the skin, where a simulation's collider pushes it.
                        // (The end is in the braid, which covers it: only its centreline is kept out.)
                        x = plan.end;
                        keep_outside(x, scalp, KeepOutside{0.0f, 0.0f, 2});
                    }
                    else {
                        // Two moves: exact for analytic surfaces, and a level set's distance is
                        // accurate enough near the surface that a second move settles it.
                        // The half width one sample rootwards: the written taper runs by arc length,
                        // which the lifts themselves shift from the sample fraction u by up to a
                        // sample (2% of a width at 10 samples); the wider one keeps the surface out.
                        const float v = std::max(0.0f, u - 1.0f / float(samples - 1));
                        keep_outside(x, scalp, KeepOutside{0.0f, 0.0f, 2}, u * end_height + (1.0f - v) * root_half + v * tip_half + lift);
                    }
                    out_P[first + j] = x;
                }
            }
        }
    });
    carry_curve_attributes(guides, dst, src_curve);
    // New hairs: always the taper asked for, never a guide's (braid-sized) curve width.
    apply_hair_widths(dst, taper);
    add_root_uvs(dst, scalp);
    return dst;
}

}  // namespace groom
