#include "fields/drape_runs.h"

#include "kernel/error.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace groom {

namespace {

/// The least cosine of the turn between consecutive segments of p[lo..hi] that have a length
/// (a run gathered at one rim point has segments of none: the turn is taken across them); 1 where
/// there is no such pair.
float least_turn_cosine(std::span<const float3> p, int64_t lo, int64_t hi)
{
    float least = 1.0f;
    float3 last;
    bool have = false;
    for (int64_t i = lo; i < hi; ++i) {
        const float3 s = p[size_t(i + 1)] - p[size_t(i)];
        const float len = length(s);
        if (!(len > 0.0f)) continue;
        const float3 u = s / len;
        if (have) least = std::min(least, dot(last, u));
        last = u, have = true;
    }
    return least;
}

/// A lift along `d` (unit) that takes `q` clear by the rule (its distance need = clearance or
/// more), plus rule.margin: stepping out by what is missing (a point short of need by m has no
/// scalp within m of it, so a step that long crosses none), at least most / 64 a step (grazing a
/// wall, steps of what is missing stall; such a step may cross a wall thinner than itself), then
/// halving the last step back to the way out to within the margin (or 1/32 of the step). -1 where
/// none is found within `most`.
float exit_along(const Surface& scalp, const float3& q, const float3& d, const KeepOutside& rule, float most)
{
    const float need = rule.clearance;
    const auto at = [&](float lift) { return scalp.distance_within(q + d * lift, need); };
    const float least = std::max(rule.margin, most / 64.0f);
    float lo = 0.0f, hi = -1.0f;
    float dist = at(lo);
    for (int step = 0; step < 128; ++step) {
        if (!(dist < need)) {
            hi = lo;
            break;
        }
        const float next = lo + std::max(need - dist, least);
        if (!(next <= most)) return -1.0f;
        const float there = at(next);
        if (!(there < need)) {
            hi = next;
            break;
        }
        lo = next, dist = there;
    }
    if (hi < 0.0f) return -1.0f;
    const float tol = std::max(rule.margin, (hi - lo) * 0x1p-5f);
    for (int it = 0; it < 40 && hi - lo > tol; ++it) {
        const float mid = 0.5f * (lo + hi);
        (!(at(mid) < need) ? hi : lo) = mid;
    }
    const float out = hi + rule.margin;
    return out <= most && !(at(out) < need) ? out : -1.0f;
}

}  // namespace

DrapeCount drape_runs(CurveSet& curves, std::span<const MovedPoint> moved, const Surface& scalp, const KeepOutside& rule)
{
    auto all = curves.positions_for_write();
    const int64_t nc = int64_t(curves.num_curves());
    std::vector<int64_t> runs(size_t(nc), 0);
    const auto by_index = [](const MovedPoint& m, int64_t i) { return m.index < i; };
    parallel_for(nc, 256, [&](int64_t b, int64_t e) {
        std::vector<float3> before, lifted, trial;
        std::vector<uint8_t> was_moved;
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = curves.points_of(c);
            const auto first = std::lower_bound(moved.begin(), moved.end(), r.begin, by_index);
            const auto last = std::lower_bound(first, moved.end(), r.end, by_index);
            if (first == last) continue;
            // A record out of order would name points of other curves here: refused, not written.
            if (!std::all_of(first, last, [&](const MovedPoint& m) { return m.index >= r.begin && m.index < r.end; })) {
                throw InvalidParam("drape_runs: the record of moved points is not sorted by index (point " + std::to_string(first->index) + ")");
            }
            // The curve's points (P) and where they were before keep_outside (before), from 0.
            const std::span<float3> P = all.subspan(size_t(r.begin), size_t(r.size()));
            const int64_t n = int64_t(P.size());
            before.assign(P.begin(), P.end());
            was_moved.assign(size_t(n), 0);
            for (auto m = first; m != last; ++m) before[size_t(m->index - r.begin)] = m->before, was_moved[size_t(m->index - r.begin)] = 1;
            for (int64_t s = 1; s < n;) {
                if (!was_moved[size_t(s)]) {
                    ++s;
                    continue;
                }
                int64_t t = s;
                while (t < n && was_moved[size_t(t)]) ++t;
                // The run [s, t) moved; the turns around it: from the segment into its clear point
                // before to the one out of its clear point after.
                const int64_t lo = std::max<int64_t>(0, s - 2), hi = std::min(n - 1, t + 1);
                trial.assign(P.begin() + lo, P.begin() + hi + 1);
                const float after_turn = least_turn_cosine(P, lo, hi);
                if (!(after_turn < 0.0f) || least_turn_cosine(before, lo, hi) < 0.0f) {
                    s = t;
                    continue;
                }
                // Directions to lay the run out along, each less its part along the chord between
                // the clear points either end: the mean of the moves keep_outside made, the mean of
                // the scalp's normals at those points (either can point into the head: beside an
                // open rim the normal does, and in an ear flap the moves go to whichever side is
                // nearer), and both reversed (the far side of a flap). The first whose drape turns
                // by no more than 90 degrees is kept, else the one that turns least.
                const float3 a = P[size_t(s - 1)];
                float3 push, normal = scalp.normal(a);
                float reach = 0.0f;  // the farthest move: a drape may lift by a few times that
                for (int64_t i = s; i < t; ++i) {
                    push = push + (P[size_t(i)] - before[size_t(i)]);
                    reach = std::max(reach, distance(P[size_t(i)], before[size_t(i)]));
                }
                float3 chord;
                float span = 0.0f;
                if (t < n) {
                    chord = P[size_t(t)] - a;
                    span = length(chord);
                    normal = normal + scalp.normal(P[size_t(t)]);
                }
                const float most = std::max(span, 4.0f * reach);
                float best = after_turn;
                for (const float3& way : {push, normal, -push, -normal}) {
                    float3 d = span > 0.0f ? way - chord * (dot(way, chord) / (span * span)) : way;
                    const float dl = length(d);
                    if (!(dl > 1e-30f)) continue;
                    d = d / dl;
                    bool ok = true;
                    for (int64_t i = s; i < t && ok; ++i) {
                        const float lift = exit_along(scalp, before[size_t(i)], d, rule, most);
                        ok = lift >= 0.0f;
                        trial[size_t(i - lo)] = before[size_t(i)] + d * lift;
                    }
                    if (!ok) continue;
                    const float turn = least_turn_cosine(trial, 0, hi - lo);
                    if (turn > best) best = turn, lifted.assign(trial.begin() + (s - lo), trial.begin() + (t - lo));
                    if (best >= 0.0f) break;  // no fold left: the later directions are for runs this one cannot mend
                }
                if (best > after_turn) {
                    std::copy(lifted.begin(), lifted.end(), P.begin() + s);
                    ++runs[size_t(c)];
                }
                s = t;
            }
        }
    });
    DrapeCount count;
    for (const int64_t n : runs) {
        count.runs += n;
        count.curves += n > 0;
    }
    return count;
}

}  // namespace groom
