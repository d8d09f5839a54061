#include "fields/keep_outside.h"

#include "fields/drape_runs.h"
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
/// up to rule.max_steps projections to need + margin, the margin doubling on each retry. A move is
/// never for the worse: where every try falls short the point takes the farthest place tried, or
/// stays where it was. And a move that lands deeper inside than it started tries the other side:
/// beside an open rim (Sintel's eye holes) the closest face's normal can point into the head, and
/// cull's push put 117 of 160,000 hair points that were outside half a unit inside (a trial).
bool settle(float3& p, float d, float need, const Surface& scalp, const KeepOutside& rule)
{
    if (!(d < need)) return false;  // clear (a NaN distance moves nothing)
    float margin = rule.margin;
    float3 at = p, best = p;
    float at_d = d, best_d = d;
    for (int step = 1;; ++step) {
        float3 n, c;
        scalp.query(at, n, c);
        const float reach = need + margin;
        float3 next = c + n * reach;
        float next_d = distance_for(scalp, next, need);
        if (next_d < 0.0f && next_d < at_d) {
            const float3 other = c - n * reach;
            const float other_d = distance_for(scalp, other, need);
            if (other_d > next_d) next = other, next_d = other_d;
        }
        if (!(next_d < need)) {
            p = next;
            return true;
        }
        if (next_d > best_d) best = next, best_d = next_d;
        if (step >= rule.max_steps) break;
        at = next, at_d = next_d;
        margin *= 2.0f;
    }
    const bool moved = best_d > d;
    p = best;
    return moved;
}

/// A clear place on the segment from `a` (clear: fa = distance - need >= 0) to `p` (not: fp < 0)
/// with a place that is not clear within 1/16 of the rule's margin beyond it along the segment
/// (2^-24 of the segment where the margin is 0, what the 24 halvings used before gave). Every place
/// kept as `lo` passed the rule's own test, so the point ends clear whatever the distances are.
/// The steps are regula falsi's on distance - need with the Illinois rule (the side kept twice has
/// its value halved), which converge superlinearly where the distance
/// is smooth along the segment (the band's trilinear values, the mesh's), each held at least half
/// the tolerance inside the bracket so that the last step closes it; where a step leaves more than
/// half of a bracket two steps old (a bound's values far out, a sign's jump at an opening) the next
/// one halves it, so it is never much slower than bisection. On Sintel's curl (100,000 hairs, 69,000
/// points pulled back) 3.9 queries a point instead of 24: the bisection had been 37% of all the
/// curl's scalp queries (perf and counts: 1.66M of 5.08M).
float3 pull_back(const float3& a, const float3& p, float fa, float fp, float need, const Surface& scalp, const KeepOutside& rule)
{
    const float3 off = p - a;
    const double len = double(length(off));
    const double tol = std::max(len > 0.0 ? double(rule.margin) * 0x1p-4 / len : 0.0, 0x1p-24);
    double lo = 0.0, hi = 1.0, flo = fa, fhi = fp, width = 1.0;
    int kept = 0;  // the side the last step replaced: 1 lo, -1 hi
    for (int it = 0; it < 64 && hi - lo > tol; ++it) {
        double t = 0.5 * (lo + hi);
        const bool secant = std::isfinite(flo) && std::isfinite(fhi) && flo - fhi > 0.0;
        if (it % 2 == 0 && it > 0) {
            if (hi - lo > 0.5 * width) kept = 2;  // stalled: halve this time
            width = hi - lo;
        }
        if (secant && kept != 2) t = lo + (hi - lo) * (flo / (flo - fhi));
        t = std::clamp(t, lo + 0.5 * tol, hi - 0.5 * tol);
        const double f = double(distance_for(scalp, a + off * float(t), need)) - double(need);
        if (!(f < 0.0)) {
            if (kept == 1) fhi *= 0.5;
            lo = t, flo = f, kept = 1;
        }
        else {
            if (kept == -1) flo *= 0.5;
            hi = t, fhi = f, kept = -1;
        }
    }
    return a + off * float(lo);
}

/// Whether `p`, carried along `dir` from lift `a` to lift `b`, goes into the scalp on the way (from
/// a distance of -tol or more to one below -tol): lift_outside's guard against passing through.
/// `da` and `db` are the distances at the ends, or values of the same sign smaller in size
/// (Surface::distance_within's bounds). A signed distance changes no faster than the point moves, so
/// where the ends' distances together span the step no crossing lies between them; elsewhere the
/// step is halved, each half asked only for the distance it needs, while `budget` queries last (a
/// point grazing the surface all the way would otherwise be asked at every 2^-k of the step). A
/// point that starts inside may come out; going back in counts.
bool enters(const Surface& scalp, const float3& p, const float3& dir, double a, double b, float da, float db, float tol, int& budget)
{
    if (!(da < -tol) && db < -tol) return true;
    const double step = std::fabs(b - a);
    if (double(std::fabs(da)) + double(std::fabs(db)) >= step || step <= double(tol) || budget <= 0) return false;
    --budget;
    const double m = 0.5 * (a + b);
    const float dm = scalp.distance_within(p + dir * float(m), float(0.5 * step));
    return enters(scalp, p, dir, a, m, da, dm, tol, budget) || enters(scalp, p, dir, m, b, dm, db, tol, budget);
}

}  // namespace

bool keep_outside(float3& p, const Surface& scalp, const KeepOutside& rule, float extra, const float3* anchor)
{
    const float need = rule.clearance + extra;
    if (scalp.known_clear(p, need)) return false;
    const float d = distance_for(scalp, p, need);
    if (!(d < need)) return false;
    if (anchor) {
        const float da = distance_for(scalp, *anchor, need);
        if (!(da < need)) {
            p = pull_back(*anchor, p, da - need, d - need, need, scalp, rule);
            return true;
        }
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
            if (scalp.known_clear(points[q], need)) continue;
            moved[q] = settle(points[q], distance_for(scalp, points[q], need), need, scalp, rule);
        }
        step.advance(end - begin);
    });
    int64_t count = 0;
    for (const uint8_t m : moved) count += m;
    return count;
}

KeepOutsideCount keep_outside(CurveSet& curves, const Surface& scalp, const KeepOutside& rule, std::vector<MovedPoint>* moved_points)
{
    auto P = curves.positions_for_write();
    const int64_t nc = int64_t(curves.num_curves());
    const float need = rule.clearance;
    // The walk's bound holds only for a 1-Lipschitz distance: across an opening's 1/2 surface the
    // sign jumps, and hair that went in through Sintel's eye sockets was left inside, skipped.
    const bool bounded = scalp.lipschitz();
    std::vector<int64_t> moved(size_t(nc), 0);
    // Blocks of 256 curves, each with its own record of the points it moved: joined in block order
    // they are in index order, with no lock and no sort.
    constexpr int64_t kBlock = 256;
    const int64_t blocks = (nc + kBlock - 1) / kBlock;
    std::vector<std::vector<MovedPoint>> records(static_cast<size_t>(blocks));
    parallel_for(blocks, 1, [&](int64_t b0, int64_t b1) {
        for (int64_t blk = b0; blk < b1; ++blk) {
            for (int64_t c = blk * kBlock; c < std::min(nc, (blk + 1) * kBlock); ++c) {
                const IndexRange r = curves.points_of(c);
                float lower = -std::numeric_limits<float>::infinity();  // nothing known of the root
                for (int64_t q = r.begin + 1; q < r.end; ++q) {
                    lower -= distance(P[q], P[q - 1]);
                    if (bounded && lower > need) continue;
                    if (scalp.known_clear(P[q], need)) {
                        lower = need;  // at least
                        continue;
                    }
                    // A bound where the point is clear by more than `need`: still a lower bound for the walk.
                    const float d = distance_for(scalp, P[q], need);
                    lower = d;
                    const float3 was = P[q];
                    if (!settle(P[q], d, need, scalp, rule)) continue;
                    lower = need;
                    ++moved[c];
                    records[size_t(blk)].push_back({q, was});
                }
            }
        }
    });
    std::vector<MovedPoint> own;
    std::vector<MovedPoint>& record = moved_points ? *moved_points : own;
    record.clear();
    for (const auto& r : records) record.insert(record.end(), r.begin(), r.end());
    KeepOutsideCount count;
    for (const int64_t m : moved) {
        count.points += m;
        count.curves += m > 0;
    }
    count.draped = drape_runs(curves, record, scalp, rule).runs;
    return count;
}

double lift_outside(std::span<const float3> group, const float3& direction, const Surface& scalp, const KeepOutside& rule,
                    float extra, bool rest, LiftOutcome* outcome)
{
    const float need = rule.clearance + extra + rule.margin;
    double lift = 0.0;
    if (outcome) *outcome = LiftOutcome{};
    if (!rest && need >= 0.0f) {
        // A group with every point clear is not moved: that needs no distances, only comparisons.
        bool clear = true;
        for (const float3& p : group) {
            const float3 q = p + direction * float(lift);
            clear = clear && (scalp.known_clear(q, need) || !(scalp.distance_within(q, need) < need));
        }
        if (clear) return lift;
    }
    // Each step goes as far as the worst point lacks, which never passes the first lift along
    // `direction` where the whole group is clear (a signed distance changes no faster than a point
    // moves). But that first lift can lie on the far side of the head: a box-braid guide hanging
    // behind an ear (the TressFX ponytail head, a trial) was nearer the ear than the skull, and the
    // ear's inner side faces the skull; its sections, too thick for the gap, were carried on through
    // the head and out 52 units away on its other side. A demanding artist expects a section
    // to come out on the near side by about what it lacks, or, where nothing clear lies that way, to
    // stay where it is clearest and be named (braid warns). So each step out (one taken because the
    // group was short) is watched: one that takes a point that was outside into the scalp, or the
    // second in a row that leaves the worst point shorter than before it, ends the search at the
    // least short place found. The distances (or their bounds) at the lift before are kept for the
    // first test. A level set is not quite a distance (in a gap a few voxels wide, or where its band
    // meets the mesh's exact distance): one step may come out a little worse and the next one
    // settle (the ICT head's box braids: 0.0014 short, then 0.003, then clear), which is why one
    // is let pass, and why steps back down, toward the least lift or onto the scalp (rest), are
    // not watched.
    std::vector<float> at(group.size()), before(group.size());
    const float tol = rule.margin;
    const auto short_of = [](float worst) { return std::max(-worst, 0.0f); };
    double prev = 0.0, best = 0.0;
    float best_worst = 0.0f, last_worst = 0.0f;
    bool blocked = false, done = false, grew = false;
    const auto way_in = [&](double from, double to, std::span<const float> d_from, std::span<const float> d_to) {
        int budget = 64;
        for (size_t i = 0; i < group.size(); ++i) {
            if (enters(scalp, group[i], direction, from, to, d_from[i], d_to[i], tol, budget)) return true;
        }
        return false;
    };
    for (int iter = 0; iter < rule.max_steps; ++iter) {
        float worst = std::numeric_limits<float>::infinity();
        for (size_t i = 0; i < group.size(); ++i) {
            const float3 q = group[i] + direction * float(lift);
            // Only a point that lowers the worst needs its distance: one certainly beyond the
            // worst so far (by more than float rounding) can be answered with a bound.
            const double beyond = double(worst) + double(need) + 1e-5 * (std::fabs(double(worst)) + std::fabs(double(need))) + 1e-30;
            float reach = float(beyond);
            if (double(reach) < beyond) reach = std::nextafter(reach, std::numeric_limits<float>::infinity());
            float d = reach > 0.0f && std::isfinite(reach) ? scalp.distance_within(q, reach) : scalp.distance(q);
            at[i] = d;
            if (d >= reach) continue;
            if (!(std::fabs(d) < reach)) d = scalp.distance(q);  // a bound inside: the value is needed
            at[i] = d;
            worst = std::min(worst, d - need);
        }
        if (iter > 0 && last_worst < 0.0f) {
            const bool worse = short_of(worst) > short_of(last_worst) + rule.margin;
            if ((worse && grew) || way_in(prev, lift, before, at)) {
                blocked = true;
                break;
            }
            grew = worse;
        }
        else {
            grew = false;
        }
        if (iter == 0 || short_of(worst) < short_of(best_worst)) best = lift, best_worst = worst;
        last_worst = worst;
        std::swap(at, before);
        prev = lift;
        const double next = rest ? lift - worst : std::max(lift - worst, 0.0);
        done = std::fabs(next - lift) <= rule.margin;
        lift = next;
        if (done) break;
    }
    if (!blocked && !done && last_worst < 0.0f) {
        // The steps ran out: the last one was not looked at yet.
        for (size_t i = 0; i < group.size(); ++i) {
            at[i] = scalp.distance_within(group[i] + direction * float(lift), float(std::fabs(lift - prev)));
        }
        blocked = way_in(prev, lift, before, at);
    }
    if (blocked) lift = best, last_worst = best_worst;
    if (outcome) *outcome = LiftOutcome{blocked && best_worst < 0.0f, last_worst};
    return lift;
}

}  // namespace groom
