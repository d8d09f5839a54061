#include "ops/cornrow_guides.h"
#include "ops/scene_length.h"
#include "ops/root_uv.h"

#include "fields/keep_outside.h"
#include "fields/point_index.h"
#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <span>
#include <utility>
#include <vector>

namespace groom {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kDeg = kPi / 180.0f;
/// A dense path whose largest chord is this many times its median has jumped across a fold (its
/// even parts differ by a few percent; ICT's forehead jumped 14 times the median).
constexpr float kJumpRatio = 4.0f;
/// Straight-back rows end on the hairline between its points this far round from the face either
/// way, degrees (azimuth about its centroid): behind the ears. At the outer rows' own ends (their
/// planes' cuts) the outermost two pairs of rows on Lee Perry-Smith came within 0.05 of each other
/// behind the ears, a tenth of their spacing.
constexpr float kBackArcStart = 120.0f;

std::string fmt(float v) { return format_number(v); }

void require(bool ok, const std::string& what)
{
    if (!ok) throw InvalidParam("cornrow-guides: " + what);
}

/// A point on the scalp: projected, then lifted along the normal.
float3 on_scalp(const Surface& scalp, const float3& q, float offset)
{
    const float3 p = scalp.closest_point(q);
    return offset > 0.0f ? p + scalp.normal(p) * offset : p;
}

/// The dense path's largest chord, and how many times its median that is: a path projected to the
/// nearest scalp point runs evenly where the scalp follows the arc, and jumps where the arc passes
/// under a fold (a brow, an ear), its points' nearest surface switching from one side of the fold
/// to the other.
struct Jump {
    float chord = 0.0f, ratio = 0.0f;
};
Jump largest_step(std::span<const float3> path)
{
    Jump j;
    if (path.size() < 3) return j;
    std::vector<float> chords(path.size() - 1);
    for (size_t k = 0; k + 1 < path.size(); ++k) chords[k] = distance(path[k], path[k + 1]);
    j.chord = *std::max_element(chords.begin(), chords.end());
    std::nth_element(chords.begin(), chords.begin() + chords.size() / 2, chords.end());
    const float median = chords[chords.size() / 2];
    j.ratio = median > 0.0f ? j.chord / median : (j.chord > 0.0f ? std::numeric_limits<float>::infinity() : 0.0f);
    return j;
}

}  // namespace

void CornrowGuidesParams::validate(bool hairline) const
{
    require(count >= 1 && count <= 256, "`count` must be in [1, 256] (got " + std::to_string(count) + ")");
    require(std::isfinite(center.x) && std::isfinite(center.y) && std::isfinite(center.z), "`center` must be finite");
    require(radius > 0.0f && radius <= kMaxSceneLength, "`radius` must be in (0, 1e15] (got " + fmt(radius) + ")");
    require(isfinite(up) && length(up) > 0.0f, "`up` must be a finite direction of length > 0 (got " + format_xyz(up) + ")");
    require(isfinite(forward) && length(forward) > 0.0f, "`forward` must be a finite direction of length > 0 (got " + format_xyz(forward) + ")");
    require(length(cross(normalize(up), normalize(forward))) > std::sin(10.0f * kDeg),
            "`forward` " + format_xyz(forward) + " must be at least 10 degrees from `up` " + format_xyz(up) + " (the direction the face looks)");
    require(pivot >= 0.0f && pivot <= kMaxSceneLength, "`pivot` must be in [0, 1e15] (got " + fmt(pivot) + ")");
    require(std::isfinite(spread) && spread >= 0.0f && spread < 90.0f, "`spread` must be in [0, 90) degrees (got " + fmt(spread) + ")");
    require(count == 1 || spread > 0.0f, "`spread` 0 lays all " + std::to_string(count) +
                                             " rows in one plane, on top of each other: give a `spread` > 0 or one row");
    require(pivot * std::sin(spread * kDeg) < radius, "`pivot` " + fmt(pivot) + " x sin(`spread` " + fmt(spread) + ") must be below `radius` " +
                                                          fmt(radius) + " (the outermost rows' planes would miss the sphere): lower one of them");
    require(std::isfinite(min_spacing) && min_spacing > 0.0f && min_spacing <= 1.0f,
            "`min_spacing` must be in (0, 1] (got " + fmt(min_spacing) + ")");
    require(std::isfinite(front_angle) && front_angle > -90.0f && front_angle < 90.0f,
            "`front_angle` must be in (-90, 90) degrees (got " + fmt(front_angle) + ")");
    require(std::isfinite(hairline_curve) && hairline_curve >= 0.0f && hairline_curve < 90.0f,
            "`hairline_curve` must be in [0, 90) degrees (got " + fmt(hairline_curve) + ")");
    require(std::isfinite(back_angle) && back_angle > -90.0f && back_angle < 90.0f,
            "`back_angle` must be in (-90, 90) degrees (got " + fmt(back_angle) + ")");
    // Every guide's plane contains the fan axis, so all rows meet where that axis pierces the sphere:
    // at elevation -asin(pivot / radius) in the middle row's plane (the tilted rows reach it at a
    // shallower angle). Rows ending below that point have crossed each other at the nape.
    const float meet = pivot < radius ? -std::asin(pivot / radius) / kDeg : -90.0f;
    require(hairline || back_angle > meet, "`back_angle` " + fmt(back_angle) + " runs past the point where all rows meet (" + fmt(meet) +
                                   " degrees for `pivot` " + fmt(pivot) + " and `radius` " + fmt(radius) +
                                   "), so rows would cross at the nape; use a back angle above " + fmt(meet) +
                                   " or a larger `pivot`");
    require(samples >= 2 && samples <= 100000, "`samples` must be in [2, 100000] (got " + std::to_string(samples) + ")");
    require(std::isfinite(offset) && offset >= 0.0f, "`offset` must be >= 0 (got " + fmt(offset) + ")");
    // Lifted along the normals that far, the rows bunch and tear where the head curves (--offset 5
    // on the default head: steps from 0.29 to 2.2 times the median; 100 on Lee Perry-Smith: jumps of
    // 34, silently: a hostile trial). Guides lie on the scalp; a braid's own height lifts it.
    require(offset <= 0.2f * radius, "`offset` " + fmt(offset) + " must be at most a fifth of `radius` " + fmt(radius) +
                                         " (guides lie on the scalp; lifted that far along its normals they bunch and tear where it curves)");
    require(std::isfinite(tail_length) && tail_length >= 0.0f, "`tail_length` must be >= 0 (got " + fmt(tail_length) + ")");
    require(tail_samples >= 2 && tail_samples <= 100000, "`tail_samples` must be in [2, 100000] (got " + std::to_string(tail_samples) + ")");
}

namespace {

/// The circle a row is laid along, where its plane cuts the sphere round the cranium: the point at
/// angle a is base + upward (s0 + rho sin a) + front (rho cos a), a = 0 towards the face, pi/2 the
/// top. (The fan's planes keep base at the pivot and s0 along their lean, as they were first
/// written, so their rows are the same bits.)
struct RowCircle {
    float3 base, front, upward;  ///< front and upward: unit, perpendicular, in the plane
    float s0 = 0.0f, rho = 0.0f;
    float3 point(float a) const { return base + upward * (s0 + rho * std::sin(a)) + front * (rho * std::cos(a)); }
    float3 centre() const { return base + upward * s0; }
    float3 direction(float a) const { return normalize(upward * std::sin(a) + front * std::cos(a)); }
    /// The plane's unit normal.
    float3 normal() const { return normalize(cross(front, upward)); }
};

/// The circle's point at an angle, on the scalp.
auto on_circle(const Surface& scalp, const RowCircle& circle)
{
    return [&scalp, circle](float a) { return on_scalp(scalp, circle.point(a), 0.0f); };
}

/// One way along a row from its start, walked on the scalp (walk_row).
struct Walk {
    std::vector<float3> points;  ///< after the start, in walking order
    /// It ended on the hairline (or at its target, which is on it); else it stalled at a crease,
    /// came back round to its start (a plane cut that never leaves the hairline) or ran max_length.
    bool left_hairline = false;
};

/// Walks on the scalp from `start` (on it, inside the hairline) in steps of `step` until it leaves
/// the hairline; the last point is on the hairline (bisected to 2^-20 of a step). Without a target
/// it follows the cut of the plane through `start` with normal `normal` (the direction in both the
/// plane and the scalp's tangent plane that goes on the way `heading` points). With a `target`
/// (on the hairline) the direction turns from the plane's towards the target's, by smoothstep of
/// the walk's progress, length / (length + distance to the target): from nothing at the start to
/// all of it at the target, however far the plane's own cut would have gone (a steer scheduled
/// by that cut's length came too late for rows whose cut ran past their target, and their ends
/// hooked back up towards it: up to 142 degrees, the review); the walk ends at the target when it
/// comes within a step of it. A step that lands more than two steps away (across to another sheet
/// of the scalp: an ear's rim) is taken again shorter; the walk stops where that does not help,
/// where a step gains less than a quarter of a step (a crease), back within a step of its start
/// after going four steps, or after max_length.
Walk walk_row(const Surface& scalp, const HairRegion& region, const float3& normal, const float3& start, float3 heading, float step,
              double max_length, const float3* target = nullptr)
{
    // Onto the scalp and, while the walk keeps to its plane, the plane: alternating projections.
    const auto onto = [&](float3 q, bool plane) {
        for (int it = 0; plane && it < 4; ++it) {
            q = scalp.closest_point(q);
            q = q - normal * dot(q - start, normal);
        }
        return scalp.closest_point(q);
    };
    Walk walk;
    double walked = 0.0;
    float3 p = start;
    while (walked < max_length) {
        const float3 n = scalp.normal(p);
        float3 t = cross(normal, n);
        if (dot(t, heading) < 0.0f) t = -t;
        t = normalize(t, heading);
        bool plane = true;
        if (target != nullptr) {
            float3 to = *target - p;
            to = to - n * dot(to, n);
            const float left = distance(p, *target);
            const float x = float(walked / (walked + double(left)));
            const float w = x * x * (3.0f - 2.0f * x);
            if (w > 0.0f && length(to) > 0.0f) {
                t = normalize(t * (1.0f - w) + normalize(to) * w, t);
                plane = false;
            }
        }
        float3 q = onto(p + t * step, plane);
        for (float part = 0.5f; part > 0.05f && distance(q, p) > 2.0f * step; part *= 0.5f) q = onto(p + t * (step * part), plane);
        const float gained = distance(q, p);
        if (!(gained > 0.25f * step) || gained > 2.0f * step) break;
        if (!region.inside_hairline(q)) {
            float3 in = p, out = q;
            for (int it = 0; it < 20; ++it) {
                const float3 mid = onto((in + out) * 0.5f, plane);
                (region.inside_hairline(mid) ? in : out) = mid;
            }
            if (distance(in, p) > 0.0f) walk.points.push_back(in);
            walk.left_hairline = true;
            break;
        }
        walk.points.push_back(q);
        walked += double(gained);
        heading = (q - p) * (1.0f / gained);
        p = q;
        if (target != nullptr && distance(p, *target) < step) {
            walk.points.push_back(scalp.closest_point(*target));
            walk.left_hairline = true;
            break;
        }
        if (walked > 4.0 * double(step) && distance(p, start) < step) break;  // round its plane's cut and back
    }
    return walk;
}

/// The point of the closed `loop` at `degrees` of azimuth about `mid` in the head's frame (0 the
/// face, towards +X positive), interpolated on the segment that crosses it: a hairline goes once
/// round its centroid (HairRegion), so one segment does. The nearest point alone had put a row's
/// end at -107.8 degrees on a 16-point hairline (the review).
float3 hairline_at_azimuth(std::span<const float3> loop, const float3& mid, const float3& X, const float3& Z, float degrees)
{
    const float want = degrees * kDeg;
    const auto off = [&](const float3& q) { return std::remainder(std::atan2(dot(q - mid, X), dot(q - mid, Z)) - want, 2.0f * kPi); };
    size_t best = 0;
    float nearest = std::numeric_limits<float>::infinity();
    for (size_t k = 0; k < loop.size(); ++k) {
        const float3 &a = loop[k], &b = loop[(k + 1) % loop.size()];
        const float da = off(a), db = off(b);
        if (da == 0.0f) return a;
        if ((da < 0.0f) != (db < 0.0f) && std::fabs(da - db) < kPi) return a + (b - a) * (da / (da - db));
        if (std::fabs(da) < nearest) nearest = std::fabs(da), best = k;
    }
    return loop[best];
}

/// `n` points spread evenly in arc length along the closed `loop`, the first its point nearest
/// `first` and the last its point nearest `last`, going the way that does not pass its frontmost
/// point (largest along Z): round the back of the head.
std::vector<float3> spread_along_hairline(std::span<const float3> loop, const float3& first, const float3& last, const float3& Z, int n)
{
    std::vector<float3> closed(loop.begin(), loop.end());
    closed.push_back(loop.front());
    const std::vector<double> cum = cumulative_lengths(closed);
    const double total = cum.back();
    // Arc length of the loop's point nearest p.
    const auto nearest = [&](const float3& p) {
        double best = std::numeric_limits<double>::infinity(), at = 0.0;
        for (size_t k = 0; k + 1 < closed.size(); ++k) {
            const float3 seg = closed[k + 1] - closed[k];
            const float len2 = dot(seg, seg);
            const float t = len2 > 0.0f ? std::clamp(dot(p - closed[k], seg) / len2, 0.0f, 1.0f) : 0.0f;
            const float3 off = closed[k] + seg * t - p;
            const double d = double(dot(off, off));
            if (d < best) best = d, at = cum[k] + double(t) * (cum[k + 1] - cum[k]);
        }
        return at;
    };
    size_t frontmost = 0;
    for (size_t k = 1; k < loop.size(); ++k) {
        if (dot(loop[k], Z) > dot(loop[frontmost], Z)) frontmost = k;
    }
    const auto ahead = [&](double from, double to) { return std::fmod(std::fmod(to - from, total) + total, total); };
    const double s0 = nearest(first), s1 = nearest(last);
    // Forward from s0 to s1 unless that passes the front; then backward.
    const double sign = ahead(s0, cum[frontmost]) < ahead(s0, s1) ? -1.0 : 1.0;
    const double span = sign > 0.0 ? ahead(s0, s1) : ahead(s1, s0);
    std::vector<float3> out(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        const double s = s0 + sign * span * double(i) / double(n - 1);
        out[size_t(i)] = point_at_length(closed, cum, std::fmod(std::fmod(s, total) + total, total));
    }
    return out;
}

/// The part of a row's arc inside the hairline, as arc angles (radians), given the whole arc `at(a)`
/// on the scalp for a in [lo, hi]: the run of inside samples through the highest point, each end
/// refined by bisection on the hairline's margin.
struct ArcRun {
    float from = 0.0f, to = 0.0f;
    float top = 0.0f;  ///< the highest of the 513 samples
};
ArcRun inside_arc(const HairRegion& region, float lo, float hi, int row, const float3& up, const std::function<float3(float)>& at)
{
    constexpr int kSamples = 512;
    std::vector<char> inside(kSamples + 1);
    int top = -1;
    float best = -std::numeric_limits<float>::infinity();
    for (int k = 0; k <= kSamples; ++k) {
        const float3 p = at(lo + (hi - lo) * float(k) / float(kSamples));
        inside[size_t(k)] = region.inside_hairline(p);
        if (inside[size_t(k)] && dot(p, up) > best) best = dot(p, up), top = k;
    }
    if (top < 0) {
        throw InvalidGeometry("cornrow-guides: row " + std::to_string(row) +
                              " never enters the hairline (check --hairline belongs to this head and --center/--radius/--spread)");
    }
    // Bisect between an inside angle and an outside one until they are 1e-4 of the arc apart.
    const auto refine = [&](float in, float out) {
        for (int it = 0; it < 24 && std::fabs(out - in) > 1e-4f * (hi - lo); ++it) {
            const float mid = 0.5f * (in + out);
            (region.inside_hairline(at(mid)) ? in : out) = mid;
        }
        return in;
    };
    int b = top, e = top;
    while (b > 0 && inside[size_t(b - 1)]) --b;
    while (e < kSamples && inside[size_t(e + 1)]) ++e;
    const float step = (hi - lo) / float(kSamples);
    ArcRun run;
    run.from = b == 0 ? lo : refine(lo + step * float(b), lo + step * float(b - 1));
    run.to = e == kSamples ? hi : refine(lo + step * float(e), lo + step * float(e + 1));
    run.top = lo + step * float(top);
    return run;
}

/// Cuts each row to the run through its highest point (along `up`) where every point stays `want`
/// or more from both neighbouring rows' polylines, recording the length cut in `rows`. Neighbours
/// are measured as they were before any cut. A segment within `want` of a point has an end within
/// want + half its length of it: the rows' points in kd-trees, walked outward to that reach, and
/// their segments tested.
void trim_crowded_rows(std::vector<std::vector<float3>>& paths, const float3& up, double want, std::vector<CornrowGuides::Row>& rows)
{
    const int64_t n = int64_t(paths.size());
    std::vector<PointIndex> index;
    std::vector<double> longest(paths.size(), 0.0);
    for (size_t i = 0; i < paths.size(); ++i) {
        index.emplace_back(paths[i]);
        for (size_t k = 0; k + 1 < paths[i].size(); ++k) longest[i] = std::max(longest[i], double(distance(paths[i][k], paths[i][k + 1])));
    }
    std::vector<std::vector<float3>> kept(paths.size());
    parallel_for(n, 1, [&](int64_t b, int64_t e) {
        std::vector<PointIndex::Neighbour> nearest;
        for (int64_t i = b; i < e; ++i) {
            const std::vector<float3>& path = paths[size_t(i)];
            const size_t m = path.size();
            std::vector<char> crowded(m, 0);
            for (const int64_t j : {i - 1, i + 1}) {
                if (j < 0 || j >= n) continue;
                const std::vector<float3>& other = paths[size_t(j)];
                const double reach = want + 0.5 * longest[size_t(j)];
                const auto near_segment = [&](size_t k, uint32_t q) {  // a segment on either side of point q (none before 0)
                    for (const size_t a : {size_t(q) - 1, size_t(q)}) {
                        if (a < other.size() && a + 1 < other.size() && segment_distance_sq(path[k], path[k], other[a], other[a + 1]) < want * want) return true;
                    }
                    return false;
                };
                for (size_t k = 0; k < m; ++k) {
                    if (crowded[k]) continue;
                    // Most points are farther than the reach: one nearest-point query says so, where the
                    // incremental walk costs its set-up on every point.
                    index[size_t(j)].nearest(path[k], 1, nearest);
                    if (nearest.empty() || nearest[0].distance > reach) continue;
                    index[size_t(j)].walk(path[k], [&](uint32_t q, double d2) {
                        if (d2 > reach * reach) return false;
                        crowded[k] = near_segment(k, q);
                        return !crowded[k];
                    });
                }
            }
            size_t top = 0;
            for (size_t k = 1; k < m; ++k) {
                if (dot(path[k], up) > dot(path[top], up)) top = k;
            }
            size_t first = top, last = top;
            while (first > 0 && !crowded[first - 1]) --first;
            while (last + 1 < m && !crowded[last + 1]) ++last;
            if (crowded[top] || last - first + 1 < 2 || (first == 0 && last + 1 == m)) continue;  // nothing to keep, or all of it
            kept[size_t(i)].assign(path.begin() + std::ptrdiff_t(first), path.begin() + std::ptrdiff_t(last) + 1);
            rows[size_t(i)].trimmed = float(polyline_length(path) - polyline_length(kept[size_t(i)]));
        }
    });
    for (size_t i = 0; i < paths.size(); ++i) {
        if (!kept[i].empty()) paths[i] = std::move(kept[i]);
    }
}

}  // namespace

CornrowGuides cornrow_guides(const Surface& scalp, const CornrowGuidesParams& params, const HairRegion* region)
{
    if (region != nullptr && !region->has_hairline()) region = nullptr;
    params.validate(region != nullptr);
    const int n = params.count;
    // Before allocating: the guides (position, root UV; id and guide per curve), the tails (position;
    // id and guide), and every row's dense path of 4 x `samples` points (position), with a trimmed
    // copy for the spacing check and a re-spaced one per worker thread. Bounded by the ranges
    // (256 x 2 x 400,000 points, about 2.5 GB), but estimated like every op's output.
    const double guide_points = double(n) * double(params.samples);
    const double tail_points = params.tail_length > 0.0f ? double(n) * double(params.tail_samples) : 0.0;
    const double dense_points = double(std::max(4 * params.samples, 64)) *
                                (2.0 * double(n) + double(std::min<size_t>(size_t(n), tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))));
    check_memory("cornrow-guides: " + std::to_string(n) + " guides (`count`) x " + std::to_string(params.samples) + " `samples`" +
                     (tail_points > 0.0 ? " + " + std::to_string(n) + " tails x " + std::to_string(params.tail_samples) + " `tail_samples`"
                                        : std::string()),
                 guide_points * (12.0 + 8.0) + tail_points * 12.0 + double(n) * 2.0 * (8.0 + 4.0 + 8.0) + dense_points * 12.0,
                 "lower `count`, `samples` or `tail_samples`");
    CornrowGuides out;
    std::vector<int64_t> counts(size_t(n), params.samples);
    out.guides = CurveSet::from_counts(counts);
    auto P = out.guides.positions_for_write();
    out.rows.resize(size_t(n));
    // Dense paths before re-spacing: projection bunches points where the head curves away from the
    // sphere, so sample generously and resample by arc length afterwards.
    const int dense = std::max(4 * params.samples, 64);
    // The head's frame (X to its side, Y up, Z where the face looks): with the defaults exactly the
    // world's axes, so a +Y-up head's guides are the same bits as before the frame was an option.
    const float3 Y = normalize(params.up), Z = normalize(params.forward - Y * dot(params.forward, Y)), X = cross(Y, Z);
    std::vector<std::vector<float3>> paths(static_cast<size_t>(n));  // each row's dense path on the scalp
    const float3 pivot = params.center - Y * params.pivot;
    std::vector<RowCircle> circles(static_cast<size_t>(n));
    // Each row's arc, as angles on its circle; with a hairline, the angle of its highest point.
    std::vector<float> from(static_cast<size_t>(n)), to(static_cast<size_t>(n)), top(static_cast<size_t>(n));
    // Straight-back rows (their planes never meet) between a hairline's ends are walked on the scalp
    // and spread at the nape (below); other rows are their circles' arcs projected onto it.
    const bool spread_rows = region != nullptr && n >= 3 && params.pivot >= params.radius;
    parallel_for(n, 1, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            const float u = n == 1 ? 0.0f : -1.0f + 2.0f * float(i) / float(n - 1);  // -1 .. 1 across the head
            const float phi = params.spread * u * kDeg;
            // In the guide's plane, with coordinates s along lean = (sin phi, cos phi, 0) from the
            // pivot point c - h Y and w along Z, the sphere |p - c| = R is the circle
            // (s - h cos phi)^2 + w^2 = R^2 - h^2 sin^2 phi.
            const float h = params.pivot;
            RowCircle& circle = circles[size_t(i)];
            circle.base = pivot;
            circle.upward = X * std::sin(phi) + Y * std::cos(phi);
            circle.front = Z;
            circle.s0 = h * std::cos(phi);
            circle.rho = std::sqrt(params.radius * params.radius - h * h * std::sin(phi) * std::sin(phi));
            // The arc runs from the hairline (front, +Z) over the top to the nape: an angle from +Z
            // towards `lean`, from front_angle to 180 - back_angle.
            from[size_t(i)] = (params.front_angle + params.hairline_curve * u * u) * kDeg;
            to[size_t(i)] = (180.0f - params.back_angle) * kDeg;
            if (region != nullptr) {
                // As far as the rows can go before they crowd. Neighbouring rows' planes are dphi
                // apart about the axis, so at distance d from it they are d dphi apart, and over
                // the crown (R + h) dphi: a row goes on while d >= min_spacing (R + h), where
                // d = s0 + rho sin(a) in its plane. "1 degree short of where the rows meet" had
                // them pile into one point at the nape (a trial on Lee Perry-Smith and the demo
                // head: 8 of 10 rows ended at one point, their braids through each other). A
                // deep axis (pivot >= radius) may leave the whole circle: all but its lowest point.
                const float d_min = params.min_spacing * (params.radius + h);
                const float reach = std::asin(std::clamp((circle.s0 - d_min) / circle.rho, -1.0f, 1.0f));
                const ArcRun run = inside_arc(*region, -reach + 1e-3f, kPi + reach - 1e-3f, int(i), Y, on_circle(scalp, circle));
                from[size_t(i)] = run.from;
                to[size_t(i)] = run.to;
                top[size_t(i)] = run.top;
            }
        }
    });
    // The arc projected onto the scalp, as dense points.
    const auto lay_arc = [&](size_t i) {
        const RowCircle& circle = circles[size_t(i)];
        const auto at = on_circle(scalp, circle);
        const float a0 = from[size_t(i)], a1 = to[size_t(i)];
        std::vector<float3> path(static_cast<size_t>(dense));
        for (int k = 0; k < dense; ++k) {
            const float a = a0 + (a1 - a0) * float(k) / float(dense - 1);
            const float3 q = at(a);
            path[size_t(k)] = params.offset > 0.0f ? q + scalp.normal(q) * params.offset : q;
        }
        // Where the nearest-point projection jumps across a fold, the row would cut through
        // the head along the jump's chord (ICT's forehead with the default --center: a chord
        // 2.6 long and 1.1 deep under the skin, its braid and edge hairs inside the head). The
        // row is laid instead on the outermost scalp along rays from its circle's centre, which
        // goes over the fold, if that path jumps less.
        const Jump jump = largest_step(path);
        if (jump.ratio > kJumpRatio) {
            const float3 o = circle.centre();
            std::vector<float3> rays(path);
            int missed = 0;
            for (int k = 0; k < dense; ++k) {
                const float a = a0 + (a1 - a0) * float(k) / float(dense - 1);
                const float3 dir = circle.direction(a);
                float3 hit;
                // The outermost surface along the ray, coming in from far out; a ray that
                // meets none (the centre itself outside the head, at the side) keeps its
                // nearest point.
                if (!scalp.first_intersection(o + dir * (4.0f * (circle.rho + params.radius)), o, hit)) {
                    ++missed;
                    continue;
                }
                const float3 q = on_scalp(scalp, hit, 0.0f);
                rays[size_t(k)] = params.offset > 0.0f ? q + scalp.normal(q) * params.offset : q;
            }
            const bool laid = missed < dense;
            const Jump ray_jump = laid ? largest_step(rays) : Jump{};
            CornrowGuides::Row& row = out.rows[size_t(i)];
            row.along_rays = laid && ray_jump.ratio < jump.ratio;
            if (row.along_rays) path = std::move(rays);
            const Jump left = row.along_rays ? ray_jump : jump;
            row.jump = left.ratio > kJumpRatio ? left.chord : 0.0f;
        }
        paths[size_t(i)] = std::move(path);
    };
    if (!spread_rows) {
        parallel_for(n, 1, [&](int64_t b, int64_t e) {
            for (int64_t i = b; i < e; ++i) lay_arc(size_t(i));
        });
    }
    else {
        // Straight-back rows are walked on the scalp both ways from the highest point of their arc,
        // along the cut of the row's plane (moved parallel through that point) with the scalp, to
        // the hairline. Projected to its nearest scalp points, the arc jumped from the back of the
        // skull to the neck under Lee Perry-Smith's occiput (chords 9-15 times the median) and at
        // the brow, and the fan's reach had stopped the rows above the occiput anyway. The planes
        // all contain the fan's axis, so down the back the rows converge, and a real head's nape
        // is narrower than the sphere: on Lee Perry-Smith six rows ended within 1.0 of each other
        // at the nape, in a V, and the two beside them were cut 1.5 short, high on the back of the
        // head, leaving it bare. So every row is steered down the back to end on the hairline, the
        // rows' ends evenly spaced in arc length round the back of the head from behind one ear to
        // behind the other, as a stylist parts rows that reach the nape side by side; the steer
        // grows with the walk's progress towards the row's end (walk_row), so a row leaves its
        // highest point in its plane. Neighbouring rows head for neighbouring ends; the spacing
        // check below still measures them. A row whose walk does not reach the hairline (its plane
        // cut runs round inside it: a hairline far down a sphere) keeps its arc. Each walk's step
        // is the arc's dense spacing, pi R / dense, but no finer than pi R / 1024: a step costs
        // about six closest-point queries, and `samples` 100,000 would have walked 1.6 M steps a
        // row; the re-spaced points are put back on the scalp anyway.
        const float step = kPi * params.radius / float(std::min(dense, 1024));
        const double max_length = 4.0 * kPi * double(params.radius);
        const std::span<const float3> loop = region->hairline_points();
        const float3 mid = region->centroid();
        const std::vector<float3> ends = spread_along_hairline(loop, hairline_at_azimuth(loop, mid, X, Z, -kBackArcStart),
                                                               hairline_at_azimuth(loop, mid, X, Z, kBackArcStart), Z, n);
        parallel_for(n, 1, [&](int64_t b, int64_t e) {
            for (int64_t k = b; k < e; ++k) {
                const size_t i = size_t(k);
                const RowCircle& circle = circles[i];
                const float3 start = on_circle(scalp, circle)(top[i]);
                // Both ways from the plane's cut at the start, told apart by the face: directions
                // taken from the arc's neighbouring points could point the same way, and a row
                // walked up to an ear and back down its own track (the review).
                const float3 normal = circle.normal();
                float3 forth = normalize(cross(normal, scalp.normal(start)), circle.front);
                if (dot(forth, circle.front) < 0.0f) forth = -forth;
                const Walk ahead = walk_row(scalp, *region, normal, start, forth, step, max_length);
                const Walk behind = walk_row(scalp, *region, normal, start, -forth, step, max_length, &ends[i]);
                if (!ahead.left_hairline || !behind.left_hairline) {
                    lay_arc(i);
                    continue;
                }
                std::vector<float3> walked(ahead.points.rbegin(), ahead.points.rend());
                walked.push_back(start);
                walked.insert(walked.end(), behind.points.begin(), behind.points.end());
                if (params.offset > 0.0f) {
                    for (float3& q : walked) q = q + scalp.normal(q) * params.offset;
                }
                paths[i] = std::move(walked);
                out.rows[i].walked = true;
            }
        });
    }
    if (region != nullptr && n > 1) {
        // The spacing rule above holds in the rows' planes on the sphere; laid on the scalp, rows can
        // come closer (a scalp narrower than the sphere at the nape, rows laid along rays over a
        // fold: on the ponytail head two rows ended 1.44 apart where the rule asked 2.3, their braids
        // through each other, a trial). Measured on the laid rows: each keeps the run through its
        // highest point where it stays min_spacing (R + h) sin(dphi) from both neighbours.
        const float dphi = 2.0f * params.spread * kDeg / float(n - 1);
        const double want = double(params.min_spacing) * double(params.radius + params.pivot) * std::sin(double(dphi));
        trim_crowded_rows(paths, Y, want, out.rows);
    }
    parallel_for(n, 1, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            const std::vector<float3> even = resample_by_count(paths[size_t(i)], params.samples);
            for (int k = 0; k < params.samples; ++k) {
                // Resampled points sit on chords; put them back on the scalp.
                P[i * params.samples + k] = on_scalp(scalp, even[size_t(k)], params.offset);
            }
        }
    });
    auto id = out.guides.add<int64_t>(Domain::Curve, attr::id);
    auto guide = out.guides.add<int32_t>(Domain::Curve, "guide");
    for (int i = 0; i < n; ++i) {
        id[size_t(i)] = i;
        guide[size_t(i)] = i;
    }
    // Before the tails: the rows' root UVs had been written only with --tails-out (a hostile trial).
    add_root_uvs(out.guides, scalp);
    if (params.tail_length <= 0.0f) return out;

    std::vector<int64_t> tail_counts(size_t(n), params.tail_samples);
    out.tails = CurveSet::from_counts(tail_counts);
    auto T = out.tails.positions_for_write();
    parallel_for(n, 1, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            const float3* g = &P[size_t(i) * params.samples];
            const float3 end = g[params.samples - 1];
            const float3 dir0 = normalize(end - g[params.samples - 2], -Y);
            // Gravity: the direction turns from the guide's end tangent to straight down (and a
            // little away from the neck) over the first third of the tail.
            const float3 down = normalize(-Y - Z * 0.25f);
            const int m = params.tail_samples;
            const float step = params.tail_length / float(m - 1);
            float3 p = end;
            T[size_t(i) * m] = p;
            for (int k = 1; k < m; ++k) {
                const float w = std::min(1.0f, float(k) / (0.33f * float(m - 1)));
                const float3 d = normalize(dir0 * (1.0f - w) + down * w, down);
                p = p + d * step;
                // Hanging hair rests against the neck rather than entering it; the march goes on from there.
                keep_outside(p, scalp, KeepOutside{params.offset});
                T[size_t(i) * m + k] = p;
            }
        }
    });
    auto tid = out.tails.add<int64_t>(Domain::Curve, attr::id);
    auto tguide = out.tails.add<int32_t>(Domain::Curve, "guide");
    for (int i = 0; i < n; ++i) {
        tid[size_t(i)] = i;
        tguide[size_t(i)] = i;
    }
    return out;
}

}  // namespace groom
