#include "ops/braid_strands.h"

#include "fields/keep_outside.h"
#include "kernel/math/frames.h"
#include "kernel/math/polyline.h"
#include "kernel/math/spline.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace groom {

namespace {

/// Automatic frame-mode normal at the root: the scalp normal, else up (+Y) unless the guide starts
/// near vertical, where +Y would be nearly tangent and the frame ill-defined; then +Z (faces forward).
float3 initial_normal(const BraidContext& ctx, const float3& root, const float3& tangent)
{
    if (length_squared(ctx.params.initial_normal) > 0.0f) return ctx.params.initial_normal;
    if (ctx.scalp) return ctx.scalp->normal(root);
    return std::fabs(tangent.y) > 0.906f ? float3(0, 0, 1) : float3(0, 1, 0);  // cos 25 deg
}

/// Amplitude scale s(t): root/tip blend times the taper spline and the feed-in growth, pinched around
/// a tie.
float amplitude_scale(const BraidParams& p, const GuidePlan& plan, float t)
{
    const float blend = (p.root_amplitude + (p.tip_amplitude - p.root_amplitude) * t) * feed_scale(p.feed_in, plan.feed_t(p.feed_length), t);
    // The taper's Catmull-Rom overshoots between values (1,0,0 dips to -0.07 past its middle): held
    // at 0, as the values themselves are, else strand widths go negative (op_braid, --taper 1,0,0).
    float s = p.taper.empty() ? blend : blend * std::max(0.0f, sample_uniform_spline(p.taper, t));
    if (p.tie) {
        // A tie gathers the braid: the cross-section narrows to 60% within half a knot of it.
        const double knot = plan.frequency > 0.0 ? plan.woven * plan.length / plan.frequency : plan.length;
        const double d = std::fabs(double(t) - double(*p.tie)) * plan.length / (0.5 * knot);
        if (d < 1.0) s *= float(1.0 - 0.4 * 0.5 * (1.0 + std::cos(std::numbers::pi * d)));
    }
    return s;
}

}  // namespace

LiftStats braid_guide(const BraidContext& ctx, const GuidePlan& plan, std::span<const float3> guide, int64_t guide_point0,
                      CurveSet& dst, int64_t first_curve, StrandSections& sec, std::span<int64_t> src_point,
                      std::span<uint8_t> left_inside)
{
    const BraidParams& p = ctx.params;
    const int N = p.strand_count();
    const int64_t S = plan.samples;
    const double len = plan.length;
    const double F = plan.frequency;
    const double tb = plan.woven;

    // Sample the guide evenly in arc length: t_j = j / (S - 1) (the talk's z = omega = Length / N_cv),
    // along a smooth curve through it. On the polyline itself each corner turned the frames within
    // one sample, and the strands' offsets, a braid's width from the guide, swung back on the inside
    // of the turn: a trial counted 7,030 fiber joints turning more than 90 degrees on the demo's
    // 48-point rows (17-degree corners), kinks a close-up shows. The curve is a Catmull-Rom spline
    // through the guide resampled evenly (uniform Catmull-Rom through uneven points can loop), and it
    // keeps the guide's root and tip.
    const std::vector<double> cum = cumulative_lengths(guide);
    std::vector<float3> smooth;
    if (guide.size() >= 3) {
        const std::vector<float3> even = resample_by_count(guide, int(std::max<size_t>(guide.size(), 4)));
        const int per_segment = int(std::clamp<int64_t>(S / int64_t(even.size() - 1) + 1, 4, 64));
        smooth = evaluate_cubic(even, CubicBasis::CatmullRom, true, per_segment);
    }
    const std::span<const float3> centre = smooth.empty() ? guide : std::span<const float3>(smooth);
    const std::vector<double> centre_cum = smooth.empty() ? cum : cumulative_lengths(centre);
    const double centre_len = centre_cum.empty() ? 0.0 : centre_cum.back();
    std::vector<float3> C(S);
    std::vector<float> t(S);
    for (int64_t j = 0; j < S; ++j) {
        t[j] = float(double(j) / double(S - 1));
        C[j] = j == S - 1 ? guide.back() : point_at_length(centre, centre_cum, centre_len * double(j) / double(S - 1));
        // Nearest guide point in arc length, for carrying the guide's point attributes.
        const size_t best = locate_at_length(cum, len * double(j) / double(S - 1)).nearest;
        for (int i = 0; i < N; ++i) src_point[dst.points_of(first_curve + i).begin + j] = guide_point0 + int64_t(best);
    }

    // Frames. Sec. 2.1: offsets are applied in orthonormal frames along the guide; rotation-minimising
    // ones do not flip at inflections. Cornrows replace the normal with the scalp normal.
    const std::vector<float3> tangents = polyline_tangents(C);
    std::vector<Frame> frames = rotation_minimising_frames(C, initial_normal(ctx, C[0], tangents[0]));
    if (p.orient == BraidOrient::Scalp) {
        for (int64_t j = 0; j < S; ++j) {
            const float3 ns = ctx.scalp->normal(C[j]);
            const float3 tj = frames[j].t;
            const float3 b = cross(tj, ns);
            // A guide running straight into the scalp has no tangent plane direction; keep the RMF frame.
            if (length(b) < 1e-3f) continue;
            frames[j].b = normalize(b);
            frames[j].n = cross(frames[j].b, tj);
        }
    }

    // Where the weave stops (t_b): each strand's offset there, and its place in the loose end's row
    // (strands ordered across by their offset at t_b, so none crosses another while they part).
    const double u_end = F;
    std::vector<WeaveOffset> end_offset(N);
    std::vector<double> row(N);
    if (tb < 1.0) {
        std::vector<int> order(N);
        for (int i = 0; i < N; ++i) {
            end_offset[i] = ctx.weave.at(i, u_end);
            order[i] = i;
        }
        std::sort(order.begin(), order.end(), [&](int a, int b) {
            return end_offset[a].x != end_offset[b].x ? end_offset[a].x < end_offset[b].x : a < b;
        });
        // Row spacing in units of A: the strands' own width, at least the weave's touching width.
        const double spacing = std::max(ctx.weave.touching_width(), plan.A > 0.0f ? double(plan.strand_width) / plan.A : 0.0);
        for (int r = 0; r < N; ++r) row[order[r]] = (double(r) - 0.5 * (N - 1)) * spacing;
    }

    auto P = dst.positions_for_write();
    auto W = dst.find_for_write<float>(Domain::Point, attr::width);
    std::vector<float> section_reach(S);  // how far the hair reaches beyond a centreline, per section
    const float inv_sqrt_m = p.fibers > 0 ? 1.0f / std::sqrt(float(p.fibers)) : 0.0f;
    for (int64_t j = 0; j < S; ++j) {
        const double tj = t[j];
        const bool loose = tj > tb;
        // Knot phase: F alpha(t / t_b) over the woven part, then held.
        const double a = loose ? 1.0 : (tb > 0.0 ? tj / tb : 1.0);
        const double u = F * (ctx.remap.identity() ? a : ctx.remap.alpha(a));
        // q: 0 where the loose end starts, 1 at the tip; e: its smooth ease.
        const double q = loose ? (tj - tb) / (1.0 - tb) : 0.0;
        const double e = q * q * (3.0 - 2.0 * q);
        const double spread = 1.0 + double(p.flare) * q;
        const float s = amplitude_scale(p, plan, t[j]);
        const double A = double(plan.A) * s, B = double(plan.B) * s;
        const float w = plan.strand_width * s;
        // With fibers the strand is an ellipse about w/2 across, filled with fibers of their own width.
        // Each fiber keeps its full width while the section grows with the hair fed in (braid_fibers).
        const float fed = feed_scale(p.feed_in, plan.feed_t(p.feed_length), t[j]);
        const float fiber_w = p.fibers > 0 ? (p.fiber_width > 0.0f ? p.fiber_width : w * inv_sqrt_m / fed) : 0.0f;
        // Along the scalp normal (the lift's direction) a strand's fibers reach its radius (their
        // ellipse is kFiberSpreadAcross times wider across the braid, and flattened in height where
        // strands press): the reach across had lifted every cornrow about 1.5 fiber widths off the
        // scalp with --rest --clearance 0 (a trial measured 0.09 above where 0 was asked).
        section_reach[j] = p.fibers > 0 ? float(0.5 * w * spread) + 0.5f * fiber_w : 0.5f * w;
        for (int i = 0; i < N; ++i) {
            WeaveOffset o = loose ? end_offset[i] : ctx.weave.at(i, u);
            if (loose) {
                // Unbraided: part from the weave's last section into a row that opens by the flare.
                o.x = ((1.0 - e) * o.x + e * row[i]) * spread;
                o.y *= 1.0 - e;
                o.press *= 1.0 - e;
            }
            const int64_t q_pt = dst.points_of(first_curve + i).begin + j;
            P[q_pt] = C[j] + frames[j].b * float(A * o.x) + frames[j].n * float(B * o.y);
            W[q_pt] = w;
            sec.centre[q_pt] = C[j];
            sec.lateral[q_pt] = frames[j].b;
            sec.up[q_pt] = frames[j].n;
            sec.phase[q_pt] = float(u);
            sec.press[q_pt] = float(o.press);
            sec.spread[q_pt] = float(spread);
            sec.t[q_pt] = t[j];
            sec.half_width[q_pt] = float(A + 0.5 * w);
            sec.half_height[q_pt] = float(B + 0.5 * w);
        }
    }

    LiftStats stats;
    if (!ctx.scalp) return stats;
    // Scalp intersections: each whole cross-section moves along the scalp normal (so the braid keeps its
    // shape) by the least amount that puts every strand's hair `clearance` off the scalp; with `rest`,
    // sections above that are lowered onto it (lift_outside, fields/keep_outside.h). Never through
    // the scalp: a section with nothing clear that way (too thick for the gap behind an ear) stays
    // where it is clearest, its hair then pushed out point by point. A guide that runs
    // inside the head deeper than its braid is wide gives no sensible place: the near side is a guess
    // that flips from one sample to the next at the middle of the head, and a braid lifted there
    // would jump across it. So its sections are lifted less and less the deeper it runs and left
    // inside with the guide, not pushed; the braid dives in where its guide does. Both are counted
    // for braid's warning, which names the guide.
    const KeepOutside rule{p.clearance, ctx.margin, 32};
    std::vector<float3> section(N), dirs(S);
    std::vector<double> lifts(S, 0.0);
    std::vector<uint8_t> own(S, 0);  // 1: the section's own lift stays (blocked, or a deep guide's)
    for (int64_t j = 0; j < S; ++j) {
        const float3 dir = dirs[j] = ctx.scalp->normal(C[j]);
        for (int i = 0; i < N; ++i) section[i] = P[dst.points_of(first_curve + i).begin + j];
        LiftOutcome outcome;
        double lift = lift_outside(section, dir, *ctx.scalp, rule, section_reach[j], p.rest, &outcome);
        bool deep = false;
        if (lift > 0.0 || outcome.blocked) {
            // The braid here: its width (lateral amplitude and the hair's reach, either side) and half its height.
            const int64_t q0 = dst.points_of(first_curve).begin + j;
            const float width = 2.0f * (sec.half_width[q0] - 0.5f * W[q0] + section_reach[j]);
            const float half_height = sec.half_height[q0] - 0.5f * W[q0] + section_reach[j];
            const float depth = -ctx.scalp->distance(C[j]);
            deep = depth > width;
            if (deep) {
                // At most the lift that clears a guide a braid's width deep, eased to none where the
                // guide is twice that deep: the braid slides off the scalp onto its guide, no jump.
                const float ease = std::clamp(2.0f - depth / width, 0.0f, 1.0f);
                lift = std::min(lift, double((width + half_height) * ease));
                ++stats.deep;
                if (depth > stats.depth) stats.depth = depth, stats.deepest = C[j];
                for (int i = 0; i < N; ++i) left_inside[dst.points_of(first_curve + i).begin + j] = 1;
            }
        }
        if (outcome.blocked && !deep) {
            if (stats.blocked++ == 0) stats.blocked_at = C[j];
            stats.short_by = std::max(stats.short_by, -outcome.worst);
        }
        lifts[j] = lift;
        own[j] = outcome.blocked || deep;
    }
    // Each section's least lift follows whichever strand is lowest there, so along the braid it has
    // a V-shaped corner wherever the lowest strand changes, plus the level set's rounding: the fibers
    // took those corners as kinks (a trial: p90 turn between fiber segments 54 degrees against 20
    // without a scalp, 26,000 joints past 90 degrees on the demo at 672 samples). Each lift becomes
    // the larger of its own and the mean over a crossing either side: a V's bottom is raised to
    // the mean of its sides, rounding it, while elsewhere (a smooth stretch, a crest) the section
    // keeps its own lift, so the braid still rests on the scalp and no strand comes nearer than the
    // rule allows. Blocked and deep sections keep their own and lend none (a neighbour's larger lift
    // could carry a section through an ear).
    const int64_t reach = std::max<int64_t>(1, int64_t(std::lround(double(S - 1) / (F > 0.0 ? F * 2.0 * N : 1.0))));
    std::vector<double> eased(S);
    for (int64_t j = 0; j < S; ++j) {
        eased[j] = lifts[j];
        if (own[j]) continue;
        double sum = 0.0;
        int64_t n = 0;
        for (int64_t k = std::max<int64_t>(0, j - reach); k <= std::min(S - 1, j + reach); ++k) {
            if (own[k]) continue;
            sum += lifts[k];
            ++n;
        }
        eased[j] = std::max(lifts[j], sum / double(n));
    }
    for (int64_t j = 0; j < S; ++j) {
        const double lift = eased[j];
        const float3 dir = dirs[j];
        if (lift == 0.0) continue;
        for (int i = 0; i < N; ++i) {
            const int64_t q = dst.points_of(first_curve + i).begin + j;
            P[q] += dir * float(lift);
            sec.centre[q] += dir * float(lift);
        }
        if (lift > 0.0) {
            ++stats.lifted;
            stats.max_lift = std::max(stats.max_lift, float(lift));
        }
        else {
            ++stats.lowered;
            stats.max_lower = std::max(stats.max_lower, float(-lift));
        }
    }
    return stats;
}

}  // namespace groom
