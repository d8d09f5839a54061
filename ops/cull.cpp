#include "ops/cull.h"
#include "ops/scene_length.h"

#include "fields/keep_outside.h"
#include "kernel/curve_set_edit.h"
#include "kernel/error.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>

namespace groom {

void CullParams::validate() const
{
    if (!(clearance >= 0.0f && clearance <= kMaxSceneLength)) {
        throw InvalidParam("cull: `clearance` must be a distance in [0, 1e15] scene units (got " + format_number(clearance) + ")");
    }
}

namespace {

/// Curve c keeps its first keep[c] points (0: the curve goes, unless it had none), the last moved
/// to the cut at cut_t[c] on the segment it ends; every column carried. count -> scan -> fill.
CurveSet trim(const CurveSet& src, std::span<const int64_t> keep, std::span<const float> cut_t, std::vector<int64_t>& kept_curves)
{
    const auto P = src.positions();
    const int64_t nc = static_cast<int64_t>(src.num_curves());
    kept_curves.reserve(size_t(nc));
    std::vector<int64_t> counts;
    for (int64_t c = 0; c < nc; ++c) {
        if (keep[c] == 0 && src.points_in(size_t(c)) > 0) continue;
        kept_curves.push_back(c);
        counts.push_back(keep[c]);
    }
    CurveSet dst = CurveSet::from_counts(counts);
    const auto Q = dst.positions_for_write();
    std::vector<int64_t> src_point(dst.num_points());
    parallel_for(int64_t(kept_curves.size()), 64, [&](int64_t b, int64_t e) {
        for (int64_t k = b; k < e; ++k) {
            const int64_t c = kept_curves[k];
            const IndexRange r = src.points_of(size_t(c)), d = dst.points_of(size_t(k));
            for (int64_t i = 0; i < d.size(); ++i) {
                src_point[d.begin + i] = r.begin + i;
                Q[d.begin + i] = P[r.begin + i];
            }
            if (cut_t[c] >= 0.0f && d.size() >= 2) {
                // The last kept point is the source's first offending point: move it to the cut.
                const int64_t inner = r.begin + d.size() - 1;
                Q[d.end - 1] = lerp(P[inner - 1], P[inner], cut_t[c]);
                src_point[d.end - 1] = inner - 1;
            }
        }
    });
    carry_curve_attributes(src, dst, kept_curves);
    carry_point_attributes(src, dst, src_point, {attr::P});
    return dst;
}

}  // namespace

CurveSet cull(const CurveSet& src, const Surface& scalp, const CullParams& params, CullStats* stats)
{
    params.validate();
    const auto P = src.positions();
    const int64_t nc = static_cast<int64_t>(src.num_curves());
    const float D = params.clearance;
    // The output is at most the input: a copy of every column (push; trim and delete keep a subset,
    // with each kept point's source index and an id per curve) and per curve its kept count, cut and
    // flag. Bounded by the input, but a copy all the same: estimated like every op's output.
    check_memory("cull: up to " + std::to_string(src.num_points()) + " points in " + std::to_string(nc) + " curves (the input)",
                 double(src.num_points()) * (bytes_per_point(src) + 8.0) + double(nc) * (bytes_per_curve(src) + 8.0 + 4.0 + 1.0 + 8.0 + 8.0),
                 "cull fewer curves at a time, e.g. parts chosen with groom select --ids");

    if (params.mode == CullMode::Push) {
        CurveSet dst = src;
        // Re-checked and retried like generate's hairs: one trusted move along the band's normal
        // left 14,329 of 160,000 points on Sintel short of a 0.5 clearance (in creases each move
        // gains about half of what is missing), 1,521 of them inside. The margin is generate's.
        // A run the push folds back is laid over the scalp as a whole (fields/drape_runs.h).
        const KeepOutsideCount moved = keep_outside(dst, scalp, KeepOutside{D, scene_margin(src.bounds()), 16});
        if (stats) {
            *stats = CullStats{};
            stats->points_pushed = moved.points;
            stats->curves_affected = moved.curves;
        }
        return dst;
    }

    // Trim / delete: count -> scan -> fill. keep[c] = points kept (0 = curve deleted); for trim,
    // cut_t[c] places the new tip on segment (keep-2, keep-1) of the source.
    std::vector<int64_t> keep(nc, 0);
    std::vector<float> cut_t(nc, -1.0f);
    std::vector<char> affected(nc, 0);
    parallel_for(nc, 64, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = src.points_of(size_t(c));
            keep[c] = r.size();
            if (r.size() < 2) continue;
            for (int64_t i = r.begin + 1; i < r.end; ++i) {
                // Only the first point below the clearance needs distances (its own and its
                // predecessor's): until then a bound does (Surface::distance_within).
                if (!(scalp.distance_within(P[i], D) < D)) continue;
                affected[c] = 1;
                if (params.mode == CullMode::Delete) {
                    keep[c] = 0;
                }
                else {
                    // Linear in distance along the segment; a root below the clearance cuts at the root.
                    const float d = scalp.distance(P[i]), prev = scalp.distance(P[i - 1]);
                    const float t = prev > D ? std::clamp((prev - D) / (prev - d), 0.0f, 1.0f) : 0.0f;
                    const bool empty = (i == r.begin + 1 && t <= 0.0f);
                    keep[c] = empty ? 0 : (i - r.begin) + 1;
                    cut_t[c] = t;
                }
                break;
            }
        }
    });
    // A curve left with no points goes; one the file had empty stays (nothing of it is inside).
    std::vector<int64_t> kept_curves;
    CurveSet dst;
    if (params.mode == CullMode::Delete) {
        std::vector<char> gone(static_cast<size_t>(nc));
        for (int64_t c = 0; c < nc; ++c) gone[c] = keep[c] == 0 && src.points_in(size_t(c)) > 0;
        dst = remove_curves(src, gone, &kept_curves);
    }
    else {
        dst = trim(src, keep, cut_t, kept_curves);
    }
    if (dst.find<int64_t>(Domain::Curve, attr::id).empty() && dst.find<int32_t>(Domain::Curve, attr::id).empty()) {
        // Without an id column a curve's identity is its index, which deleting shifts: record it.
        const auto id = dst.add<int64_t>(Domain::Curve, attr::id);
        std::copy(kept_curves.begin(), kept_curves.end(), id.begin());
    }
    if (stats) {
        *stats = CullStats{};
        for (int64_t c = 0; c < nc; ++c) stats->curves_affected += affected[c];
        stats->curves_deleted = nc - int64_t(kept_curves.size());
        stats->points_removed = int64_t(src.num_points()) - int64_t(dst.num_points());
        for (int64_t c : kept_curves) stats->curves_trimmed += (cut_t[c] >= 0.0f);
    }
    return dst;
}

}  // namespace groom
