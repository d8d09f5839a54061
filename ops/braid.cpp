// braid: the op's parameters and its steps in order (the file comment of ops/braid.h says what a
// braid is). Each step is its own file: the knot distribution (braid_knots.cpp), the per-guide plan
// (braid_plan), one guide's strand centrelines (braid_strands), their fibers (braid_fibers), the tie
// (braid_tie); the scalp rule is fields/keep_outside.h.
#include "ops/braid.h"
#include "ops/scene_length.h"
#include "ops/root_uv.h"

#include "fields/keep_outside.h"
#include "kernel/error.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "ops/braid_fibers.h"
#include "ops/braid_plan.h"
#include "ops/braid_strands.h"
#include "ops/braid_tie.h"
#include "ops/populate.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

namespace groom {

namespace {

std::string fmt(double v) { return format_number(v); }

// Closed ranges: a length past kMaxLength (or an amplitude scale past kMaxScale times one) puts
// points so far out that their squared distances overflow float, and the NaN that follows crashed
// the exact scalp queries (`width` 3e38 with --rest --orient scalp: SIGFPE in GMP).
constexpr float kMaxLength = kMaxSceneLength;  // scene units (ops/scene_length.h)
constexpr float kMaxScale = 1000.0f;

void require_finite_at_least(const char* option, float value, float lo, float hi = kMaxLength)
{
    if (!std::isfinite(value) || value < lo || value > hi) {
        throw InvalidParam(std::string("braid: ") + option + " must be a finite number >= " + fmt(lo) + " and <= " + fmt(hi) + " (got " +
                           fmt(value) + ")");
    }
}

}  // namespace

void BraidParams::validate() const
{
    if (strands != 0 && strands < 2) {
        throw InvalidParam("braid: `strands` must be >= 2 (got " + std::to_string(strands) + ")");
    }
    if (strands > 4096) throw InvalidParam("braid: `strands` must be <= 4096 (got " + std::to_string(strands) + ")");
    validate_pattern_strands(pattern, strand_count());
    if (pattern == BraidPattern::Lissajous && hand != BraidHand::Auto) {
        throw InvalidParam("braid: `hand` does not apply to `pattern` lissajous (the talk's formula fixes who is on top)");
    }
    if (frequency && knot_length) {
        throw InvalidParam("braid: `frequency` and `knot_length` are exclusive (got both: `frequency` " + fmt(*frequency) +
                           ", `knot_length` " + fmt(*knot_length) + ")");
    }
    if (frequency) require_finite_at_least("`frequency`", *frequency, 0.0f);
    if (knot_length && !(std::isfinite(*knot_length) && *knot_length > 0.0f && *knot_length <= kMaxLength)) {
        throw InvalidParam("braid: `knot_length` must be a finite number > 0 (got " + fmt(*knot_length) + ")");
    }
    if (width) require_finite_at_least("`width`", *width, 0.0f);
    if (height) require_finite_at_least("`height`", *height, 0.0f);
    if (samples != 0 && samples < 2) {
        throw InvalidParam("braid: `samples` must be >= 2, or 0 for automatic (got " + std::to_string(samples) + ")");
    }
    require_finite_at_least("`root_amplitude`", root_amplitude, 0.0f, kMaxScale);
    require_finite_at_least("`tip_amplitude`", tip_amplitude, 0.0f, kMaxScale);
    for (size_t i = 0; i < taper.size(); ++i) {
        if (!std::isfinite(taper[i]) || taper[i] < 0.0f || taper[i] > kMaxScale) {
            throw InvalidParam("braid: `taper` values must be finite, >= 0 and <= " + fmt(kMaxScale) + " (value " + std::to_string(i + 1) +
                               " is " + fmt(taper[i]) + ")");
        }
    }
    if (!std::isfinite(knot_bias) || knot_bias <= -1.0f || knot_bias >= 1.0f) {
        throw InvalidParam("braid: `knot_bias` must be in (-1, 1) (got " + fmt(knot_bias) + ")");
    }
    for (size_t i = 0; i < knot_density.size(); ++i) {
        if (!std::isfinite(knot_density[i]) || knot_density[i] <= 0.0f) {
            throw InvalidParam("braid: `knot_density` values must be finite and > 0 (value " + std::to_string(i + 1) +
                               " is " + fmt(knot_density[i]) + ")");
        }
    }
    if (!isfinite(initial_normal)) throw InvalidParam("braid: `initial_normal` must be finite");
    require_finite_at_least("`clearance`", clearance, 0.0f);
    require_finite_at_least("`strand_width`", strand_width, 0.0f);
    if (fibers < 0 || fibers > PopulateParams::kMaxFibersPerCurve) {
        throw InvalidParam("braid: `fibers` must be in [0, " + std::to_string(PopulateParams::kMaxFibersPerCurve) + "] (got " +
                           std::to_string(fibers) + ")");
    }
    require_finite_at_least("`fiber_radius`", fiber_radius, 0.0f);
    require_finite_at_least("`fiber_width`", fiber_width, 0.0f);
    if (!std::isfinite(fiber_twist) || std::fabs(fiber_twist) > 1000.0f) {
        throw InvalidParam("braid: `fiber_twist` must be a finite number of turns per knot in [-1000, 1000] (got " + fmt(fiber_twist) + ")");
    }
    if (!std::isfinite(flatten) || flatten < 0.0f || flatten > 0.9f) {
        throw InvalidParam("braid: `flatten` must be in [0, 0.9] (got " + fmt(flatten) + ")");
    }
    require_finite_at_least("`loose_length`", loose_length, 0.0f);
    require_finite_at_least("`flare`", flare, 0.0f, 100.0f);
    if (tie && !(std::isfinite(*tie) && *tie >= 0.0f && *tie <= 1.0f)) {
        throw InvalidParam("braid: `tie` must be an arc-length fraction in [0, 1] (got " + fmt(*tie) + ")");
    }
    require_finite_at_least("`tie_width`", tie_width, 0.0f);
    if (tie_turns < 1 || tie_turns > 64) {
        throw InvalidParam("braid: `tie_turns` must be in [1, 64] (got " + std::to_string(tie_turns) + ")");
    }
    if (!std::isfinite(flyaways) || flyaways < 0.0f || flyaways > 1.0f) {
        throw InvalidParam("braid: `flyaways` must be a fraction in [0, 1] (got " + fmt(flyaways) + ")");
    }
    require_finite_at_least("`flyaway_height`", flyaway_height, 0.0f);
    if (!std::isfinite(feed_in) || feed_in < 0.0f || feed_in >= 1.0f) {
        throw InvalidParam("braid: `feed_in` must be a fraction in [0, 1) (got " + fmt(feed_in) + ")");
    }
    require_finite_at_least("`feed_length`", feed_length, 0.0f);
    if (fibers == 0 && (flyaways > 0.0f || feed_in > 0.0f)) {
        throw InvalidParam(std::string("braid: ") + (flyaways > 0.0f ? "`flyaways`" : "`feed_in`") +
                           " moves fibers; give `fibers` M > 0");
    }
}

// --- the op ------------------------------------------------------------------------------------------

namespace {

/// The strand centrelines' curves, N per planned guide in guide order, with their curve attributes
/// (guide, strand, id) and an empty point width column. first_strand[g] gets guide g's first strand
/// curve (-1: skipped), src_curve each strand's guide; guides are counted into `report`. Throws
/// LimitExceeded when the output would pass kMaxBraidPoints or an id would overflow.
CurveSet allocate_strands(std::span<const GuidePlan> plans, std::span<const int64_t> guide_ids, const BraidParams& params,
                          BraidReport& report, std::vector<int64_t>& first_strand, std::vector<int64_t>& src_curve)
{
    const int N = params.strand_count();
    const int64_t M = params.fibers;
    const size_t ng = plans.size();
    double total_points = 0.0;
    std::vector<int64_t> strand_counts;
    first_strand.assign(ng, -1);
    for (size_t g = 0; g < ng; ++g) {
        if (plans[g].samples == 0) {
            ++report.skipped_guides;
            continue;
        }
        ++report.guides;
        total_points += double(plans[g].samples) * N * double(std::max<int64_t>(M, 1));
        if (total_points > double(kMaxBraidPoints)) {
            throw LimitExceeded("braid: the output would have more than " + std::to_string(kMaxBraidPoints) +
                                " points; lower `samples`, `fibers`, `strands` or `frequency`");
        }
        // id = (guide id * N + strand) * M + fiber must not overflow, so ids stay unique.
        const int64_t id = guide_ids[g];
        const int64_t per_guide = int64_t(N) * std::max<int64_t>(M, 1);
        if (id > (std::numeric_limits<int64_t>::max() - per_guide) / per_guide ||
            id < std::numeric_limits<int64_t>::min() / per_guide + 1) {
            throw LimitExceeded("braid: guide id " + std::to_string(id) + " times " + std::to_string(N) + " strands" +
                                (M > 0 ? " times " + std::to_string(M) + " fibers" : std::string()) +
                                " overflows a 64-bit id");
        }
        first_strand[g] = int64_t(strand_counts.size());
        for (int i = 0; i < N; ++i) strand_counts.push_back(plans[g].samples);
    }
    // Each output point holds a position, a width and a source index, and the fibers' pass keeps a
    // frame per strand point beside them: about 32 bytes a point.
    check_memory("braid: " + format_number(total_points) + " output points", total_points * 32.0,
                 "lower `samples`, `fibers`, `strands` or `frequency`");

    // Count -> scan -> fill: the strand centrelines' curves first.
    CurveSet strands = CurveSet::from_counts(strand_counts);
    strands.add<float>(Domain::Point, attr::width);
    auto guide_col = strands.add<int32_t>(Domain::Curve, "guide");
    auto strand_col = strands.add<int32_t>(Domain::Curve, "strand");
    auto id_col = strands.add<int64_t>(Domain::Curve, attr::id);
    src_curve.assign(strands.num_curves(), 0);
    for (size_t g = 0; g < ng; ++g) {
        if (first_strand[g] < 0) continue;
        for (int i = 0; i < N; ++i) {
            const int64_t c = first_strand[g] + i;
            guide_col[c] = int32_t(g);
            strand_col[c] = i;
            id_col[c] = guide_ids[g] * N + i;
            src_curve[c] = int64_t(g);
        }
    }
    return strands;
}

/// Per strand, one knot and the feed-in stretch as fractions of its guide's length.
std::vector<StrandFiberPlan> fiber_plans(std::span<const GuidePlan> plans, std::span<const int64_t> first_strand,
                                         const BraidParams& params, size_t num_strands)
{
    std::vector<StrandFiberPlan> fplans(num_strands);
    for (size_t g = 0; g < plans.size(); ++g) {
        if (first_strand[g] < 0) continue;
        const GuidePlan& plan = plans[g];
        const double knot = plan.knot_length();
        for (int i = 0; i < params.strand_count(); ++i) {
            StrandFiberPlan& f = fplans[first_strand[g] + i];
            f.knot_t = float(knot / plan.length);
            f.feed_t = float(plan.feed_t(params.feed_length));
        }
    }
    return fplans;
}

/// Last resort after the section lifts: a hair point still closer to the scalp than clearance + half
/// its width moves out on its own (keep_outside). With fibers (`strands` not null) most points need
/// no query: a signed distance changes no faster than the point moves, so a hair point within
/// `reach` of its strand point keeps clearance where the strand point keeps clearance + reach + its
/// half width. Hair of a strand point marked `left_inside` (its guide runs deep in the head, see
/// braid_guide) stays: pushed one by one, points near the middle of the head would scatter to its
/// either side. Returns the number of points moved.
int64_t keep_hair_outside(CurveSet& out, const CurveSet* strands, std::span<const float> reach,
                          std::span<const int64_t> strand_point, std::span<const uint8_t> left_inside, const BraidParams& params,
                          float margin, const Surface& scalp, Progress* progress)
{
    const KeepOutside rule{params.clearance, margin, 8};
    const auto W = out.find<float>(Domain::Point, attr::width);
    std::vector<uint8_t> known_clear;
    const bool any_inside = std::find(left_inside.begin(), left_inside.end(), uint8_t(1)) != left_inside.end();
    if (!strands && any_inside) {
        // Without fibers the hair is the strands, in order (ties after them).
        known_clear.assign(out.num_points(), 0);
        std::copy(left_inside.begin(), left_inside.end(), known_clear.begin());
    }
    if (strands) {
        const auto SP = strands->positions();
        // Each strand distance is only compared with a threshold. Below `within` the scalp answers
        // exactly; past it, possibly with a bound (Surface::distance_within), which spares a strand
        // point outside the level set's band an exact search of the mesh. `within` comes from a
        // sample of the thresholds; a test that a bound cannot settle asks for the distance itself.
        const int64_t n = int64_t(out.num_points());
        float within = 0.0f;
        for (int64_t q = 0; q < n; q += std::max<int64_t>(1, n / 4096)) {
            if (strand_point[q] >= 0) within = std::max(within, reach[q] + 0.5f * W[q]);
        }
        within = (within + params.clearance + margin) * 1.01f;
        std::vector<float> strand_dist(strands->num_points());
        std::vector<float> strand_exact(strands->num_points(), std::numeric_limits<float>::quiet_NaN());
        parallel_for(int64_t(strands->num_points()), 1024, [&](int64_t begin, int64_t end) {
            for (int64_t q = begin; q < end; ++q) strand_dist[q] = scalp.distance_within(SP[q], within);
        });
        known_clear.assign(out.num_points(), 0);
        parallel_for(n, 4096, [&](int64_t begin, int64_t end) {
            for (int64_t q = begin; q < end; ++q) {
                const int64_t sp = strand_point[q];
                if (sp < 0) continue;
                const float need = params.clearance + 0.5f * W[q] + margin;
                float d = strand_dist[sp];
                if (!(d - reach[q] >= need) && d >= within) {
                    // Perhaps a bound below the distance: the distance itself decides (once per
                    // strand point; threads that race store the same value).
                    std::atomic_ref<float> exact(strand_exact[sp]);
                    d = exact.load(std::memory_order_relaxed);
                    if (d != d) {
                        d = scalp.distance(SP[sp]);
                        exact.store(d, std::memory_order_relaxed);
                    }
                }
                known_clear[q] = d - reach[q] >= need || left_inside[sp];
            }
        });
    }
    return keep_outside(out.positions_for_write(), scalp, rule, W, known_clear, progress);
}

}  // namespace

BraidResult braid(const CurveSet& guides, const BraidParams& params, const Surface* scalp, Progress* progress)
{
    params.validate();
    if (params.orient == BraidOrient::Scalp && !scalp) {
        throw InvalidParam("braid: `orient` scalp needs a scalp (give `scalp` SCALP)");
    }
    if (!scalp && (params.rest || params.clearance > 0.0f)) {
        throw InvalidParam(std::string("braid: ") + (params.rest ? "`rest`" : "`clearance`") + " needs a scalp (give `scalp` SCALP)");
    }
    const KnotRemap remap(params);
    const int N = params.strand_count();
    const BraidWeave weave(params.pattern, N, params.pattern == BraidPattern::Lissajous ? BraidHand::Over : params.resolved_hand());
    const auto GP = guides.positions();
    const size_t ng = guides.num_curves();
    const int64_t M = params.fibers;

    // Plan each guide, then allocate its strands.
    const std::vector<GuidePlan> plans = plan_guides(guides, params, remap, weave);
    BraidReport report;
    std::vector<int64_t> first_strand, src_curve;
    CurveSet strands = allocate_strands(plans, guides.curve_ids(), params, report, first_strand, src_curve);

    // Float slack relative to the scene's size: a few ulps of the largest coordinate.
    const Bounds3 bounds = guides.bounds();
    const float extent = bounds.empty() ? 1.0f
                                        : std::max({std::fabs(bounds.lo.x), std::fabs(bounds.lo.y), std::fabs(bounds.lo.z),
                                                    std::fabs(bounds.hi.x), std::fabs(bounds.hi.y), std::fabs(bounds.hi.z), 1e-3f});
    const BraidContext ctx{params, remap, weave, scalp, 8.0f * extent * std::numeric_limits<float>::epsilon()};

    // The strand centrelines, guide by guide.
    StrandSections sec;
    sec.resize(strands.num_points());
    std::vector<int64_t> src_point(strands.num_points());
    std::vector<uint8_t> left_inside(strands.num_points(), 0);
    std::vector<LiftStats> stats(ng);
    {
        const ProgressStep step(progress, "braid", int64_t(ng));
        parallel_for(int64_t(ng), 4, [&](int64_t begin, int64_t end) {
            for (int64_t g = begin; g < end; ++g) {
                if (first_strand[g] >= 0) {
                    const IndexRange r = guides.points_of(g);
                    stats[g] = braid_guide(ctx, plans[g], GP.subspan(r.begin, r.size()), r.begin, strands, first_strand[g],
                                           sec, src_point, left_inside);
                }
                step.advance(1);
            }
        });
    }
    for (size_t g = 0; g < ng; ++g) {
        const LiftStats& s = stats[g];
        report.lifted_sections += s.lifted;
        report.lowered_sections += s.lowered;
        report.max_lift = std::max(report.max_lift, s.max_lift);
        report.max_lower = std::max(report.max_lower, s.max_lower);
        report.blocked_sections += s.blocked;
        if (s.blocked > 0 || s.deep > 0) {
            report.scalp_issues.push_back({int64_t(g), int64_t(g), s.blocked, s.short_by, s.blocked_at, s.deep, s.depth, s.deepest});
        }
    }
    if (!report.scalp_issues.empty()) {
        const std::vector<int64_t> ids = guides.curve_ids();
        for (BraidScalpIssue& issue : report.scalp_issues) issue.id = ids[size_t(issue.guide)];
    }
    carry_curve_attributes(guides, strands, src_curve);
    carry_point_attributes(guides, strands, src_point, {attr::P});
    report.strands = int64_t(strands.num_curves());

    // Hair: the strands themselves, or M fibers each.
    CurveSet hair;
    std::vector<float> offset_reach;  // per hair point: how far it lies from its strand point
    std::vector<int64_t> hair_strand_point;
    if (M > 0) {
        FiberStats fs;
        hair = braid_fibers(strands, sec, fiber_plans(plans, first_strand, params, strands.num_curves()), params, weave, scalp, fs,
                            offset_reach, hair_strand_point, progress);
        report.flyaways = fs.flyaways;
        report.fed_in = fs.fed_in;
    }
    else {
        hair = std::move(strands);
    }
    auto kind_hair = hair.add<int32_t>(Domain::Curve, "kind");
    std::fill(kind_hair.begin(), kind_hair.end(), 0);

    // Ties: one band per guide, appended after the hair.
    CurveSet out;
    if (params.tie) {
        out = append_ties(hair, M > 0 ? strands : hair, sec, params, plans, first_strand);
        report.ties = int64_t(out.num_curves() - hair.num_curves());
        offset_reach.resize(out.num_points(), std::numeric_limits<float>::infinity());
        hair_strand_point.resize(out.num_points(), -1);
    }
    else {
        out = std::move(hair);
    }

    if (scalp) {
        report.pushed_points = keep_hair_outside(out, M > 0 ? &strands : nullptr, offset_reach, hair_strand_point, left_inside,
                                                 params, ctx.margin, *scalp, progress);
    }
    report.curves = int64_t(out.num_curves());
    report.points = int64_t(out.num_points());
    if (scalp) add_root_uvs(out, *scalp);
    return {std::move(out), report};
}

}  // namespace groom
