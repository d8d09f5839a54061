#include "fields/keep_outside.h"

#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace groom {

namespace {

/// The distance where it decides `d < need` (the rule's only question of a point that is clear):
/// exact below `need`, possibly a bound beyond (Surface::distance_within), which a level set answers
/// outside its band without searching the mesh.
float distance_for(const Surface& scalp, const float3& p, float need)
{
    return need >= 0.0f ? scalp.distance_within(p, need) : scalp.distance(p);
}

/// The move, for a point whose distance `d` the caller has just asked: nothing when d >= need, else
/// up to rule.max_steps projections to need + margin, the margin doubling on each retry.
bool settle(float3& p, float d, float need, const Surface& scalp, const KeepOutside& rule)
{
    if (!(d < need)) return false;  // clear (a NaN distance moves nothing)
    float margin = rule.margin;
    for (int step = 1;; ++step) {
        float3 n, c;
        scalp.query(p, n, c);
        p = c + n * (need + margin);
        if (step >= rule.max_steps || !(distance_for(scalp, p, need) < need)) break;
        margin *= 2.0f;
    }
    return true;
}

}  // namespace

bool keep_outside(float3& p, const Surface& scalp, const KeepOutside& rule, float extra, const float3* anchor)
{
    const float need = rule.clearance + extra;
    const float d = distance_for(scalp, p, need);
    if (!(d < need)) return false;
    if (anchor && !(distance_for(scalp, *anchor, need) < need)) {
        // Back toward the anchor: lo stays clear, hi not, so the point ends clear along its own offset.
        float lo = 0.0f, hi = 1.0f;
        const float3 a = *anchor, off = p - a;
        for (int it = 0; it < 24; ++it) {
            const float mid = 0.5f * (lo + hi);
            (distance_for(scalp, a + off * mid, need) < need ? hi : lo) = mid;
        }
        p = a + off * lo;
        return true;
    }
    return settle(p, d, need, scalp, rule);
}

int64_t keep_outside(std::span<float3> points, const Surface& scalp, const KeepOutside& rule, std::span<const float> widths,
                     std::span<const uint8_t> known_clear, Progress* progress)
{
    const int64_t n = int64_t(points.size());
    std::vector<uint8_t> moved(size_t(n), 0);
    const ProgressStep step(progress, "scalp clearance", n);
    parallel_for(n, 4096, [&](int64_t begin, int64_t end) {
        for (int64_t q = begin; q < end; ++q) {
            if (!known_clear.empty() && known_clear[q]) continue;
            const float need = widths.empty() ? rule.clearance : rule.clearance + 0.5f * widths[q];
            moved[q] = settle(points[q], distance_for(scalp, points[q], need), need, scalp, rule);
        }
        step.advance(end - begin);
    });
    int64_t count = 0;
    for (const uint8_t m : moved) count += m;
    return count;
}

KeepOutsideCount keep_outside(CurveSet& curves, const Surface& scalp, const KeepOutside& rule)
{
    auto P = curves.positions_for_write();
    const int64_t nc = int64_t(curves.num_curves());
    const float need = rule.clearance;
    // The walk's bound holds only for a 1-Lipschitz distance: across an opening's 1/2 surface the
    // sign jumps, and hair that went in through Sintel's eye sockets was left inside, skipped.
    const bool bounded = scalp.lipschitz();
    std::vector<int64_t> moved(size_t(nc), 0);
    parallel_for(nc, 256, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = curves.points_of(c);
            float lower = -std::numeric_limits<float>::infinity();  // nothing known of the root
            for (int64_t q = r.begin + 1; q < r.end; ++q) {
                lower -= distance(P[q], P[q - 1]);
                if (bounded && lower > need) continue;
                // A bound where the point is clear by more than `need`: still a lower bound for the walk.
                const float d = distance_for(scalp, P[q], need);
                lower = d;
                if (!settle(P[q], d, need, scalp, rule)) continue;
                lower = need;
                ++moved[c];
            }
        }
    });
    KeepOutsideCount count;
    for (const int64_t m : moved) {
        count.points += m;
        count.curves += m > 0;
    }
    return count;
}

double lift_outside(std::span<const float3> group, const float3& direction, const Surface& scalp, const KeepOutside& rule,
                    float extra, bool rest)
{
    const float need = rule.clearance + extra + rule.margin;
    double lift = 0.0;
    if (!rest && need >= 0.0f) {
        // A group with every point clear is not moved: that needs no distances, only comparisons.
        bool clear = true;
        for (const float3& p : group) clear = clear && !(scalp.distance_within(p + direction * float(lift), need) < need);
        if (clear) return lift;
    }
    for (int iter = 0; iter < rule.max_steps; ++iter) {
        float worst = std::numeric_limits<float>::infinity();
        for (const float3& p : group) {
            const float3 q = p + direction * float(lift);
            // Only a point that lowers the worst needs its distance: one certainly beyond the
            // worst so far (by more than float rounding) can be answered with a bound.
            const double beyond = double(worst) + double(need) + 1e-5 * (std::fabs(double(worst)) + std::fabs(double(need))) + 1e-30;
            float reach = float(beyond);
            if (double(reach) < beyond) reach = std::nextafter(reach, std::numeric_limits<float>::infinity());
            float d = reach > 0.0f && std::isfinite(reach) ? scalp.distance_within(q, reach) : scalp.distance(q);
            if (d >= reach) continue;
            if (!(std::fabs(d) < reach)) d = scalp.distance(q);  // a bound inside: the value is needed
            worst = std::min(worst, d - need);
        }
        const double next = rest ? lift - worst : std::max(lift - worst, 0.0);
        const bool done = std::fabs(next - lift) <= rule.margin;
        lift = next;
        if (done) break;
    }
    return lift;
}

}  // namespace groom
