#include "kernel/math/polyline.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace groom {

namespace {

/// Two floats, two doubles in one SSE register (a GCC and Clang vector extension). Arithmetic is
/// per lane and IEEE, so a lane computes what the scalar code would, bit for bit.
typedef float Float2 __attribute__((vector_size(8)));
typedef double Double2 __attribute__((vector_size(16)));

/// A point's x and y, widened to double (cvtps2pd), and its z.
inline Double2 xy_double(const float3& p)
{
    Float2 v;
    std::memcpy(&v, &p.x, sizeof v);
    return __builtin_convertvector(v, Double2);
}

}  // namespace

float polyline_length(std::span<const float3> pts)
{
    // A chunk's squared lengths first, then their square roots in a loop of its own, which the
    // compiler vectorises (sqrtps: the square roots, one after another, were most of this
    // function, and it runs twice per curve in curl); the sum keeps its order.
    constexpr size_t kChunk = 64;
    float seg[kChunk];
    double len = 0.0;
    for (size_t b = 1; b < pts.size(); b += kChunk) {
        const size_t e = std::min(pts.size(), b + kChunk);
        for (size_t i = b; i < e; ++i) seg[i - b] = length_squared(pts[i] - pts[i - 1]);
        for (size_t i = 0; i < e - b; ++i) seg[i] = std::sqrt(seg[i]);
        for (size_t i = 0; i < e - b; ++i) len += seg[i];
    }
    return static_cast<float>(len);
}

std::vector<double> cumulative_lengths(std::span<const float3> pts)
{
    std::vector<double> out;
    cumulative_lengths(pts, out);
    return out;
}

void cumulative_lengths(std::span<const float3> pts, std::vector<double>& out)
{
    out.resize(pts.size());
    if (pts.empty()) return;
    // Squared lengths, their square roots, then the running sum: three loops, so the square roots
    // run vectorised (sqrtpd) instead of one after another on the sum's chain.
    // x and y go as a pair, each point widened once and kept for the next segment: half the
    // instructions of widening and subtracting coordinate by coordinate (perf).
    out[0] = 0.0;
    Double2 xy0 = xy_double(pts[0]);
    double z0 = pts[0].z;
    for (size_t i = 1; i < pts.size(); ++i) {
        const Double2 xy1 = xy_double(pts[i]);
        const double z1 = pts[i].z;
        const Double2 dxy = xy1 - xy0, sq = dxy * dxy;
        const double dz = z1 - z0;
        out[i] = sq[0] + sq[1] + dz * dz;  // dx * dx + dy * dy + dz * dz
        xy0 = xy1, z0 = z1;
    }
    for (size_t i = 1; i < pts.size(); ++i) out[i] = std::sqrt(out[i]);
    for (size_t i = 1; i < pts.size(); ++i) out[i] += out[i - 1];
}

namespace {

/// The spot once `first` (the first point whose cumulative length exceeds s) is known.
ArcSpot spot_at(std::span<const double> cumulative, double s, size_t first)
{
    ArcSpot a;
    a.hi = std::min<size_t>(first, cumulative.size() - 1);
    a.lo = a.hi > 0 ? a.hi - 1 : 0;
    const double seg = cumulative[a.hi] - cumulative[a.lo];
    a.t = seg > 0.0 ? (s - cumulative[a.lo]) / seg : 0.0;
    a.nearest = s - cumulative[a.lo] < cumulative[a.hi] - s ? a.lo : a.hi;
    return a;
}

}  // namespace

ArcSpot locate_at_length(std::span<const double> cumulative, double s)
{
    s = std::clamp(s, 0.0, cumulative.back());
    // First point whose cumulative length exceeds s; the segment before it holds s.
    return spot_at(cumulative, s, size_t(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin()));
}

ArcSpot locate_at_length(std::span<const double> cumulative, double s, size_t& cursor)
{
    s = std::clamp(s, 0.0, cumulative.back());
    size_t first = cursor;
    if (first > cumulative.size() || (first > 0 && cumulative[first - 1] > s)) {
        first = size_t(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin());  // s went back
    }
    else {
        // Every point before the cursor is at or before s: the first beyond s is at or after it.
        while (first < cumulative.size() && cumulative[first] <= s) ++first;
    }
    cursor = first;
    return spot_at(cumulative, s, first);
}

float3 point_at_length(std::span<const float3> pts, std::span<const double> cumulative, double s)
{
    if (pts.empty()) return {};
    if (pts.size() == 1 || s <= 0.0) return pts.front();
    if (s >= cumulative.back()) return pts.back();
    const ArcSpot a = locate_at_length(cumulative, s);
    return lerp(pts[a.lo], pts[a.hi], static_cast<float>(a.t));
}

std::vector<float3> resample_by_count(std::span<const float3> pts, int count)
{
    std::vector<float3> out;
    std::vector<double> cum;
    resample_by_count(pts, count, out, cum);
    return out;
}

void resample_by_count(std::span<const float3> pts, int count, std::vector<float3>& out, std::vector<double>& cum)
{
    if (count <= 0 || pts.empty()) {
        out.assign(static_cast<size_t>(std::max(count, 0)), float3{});
        return;
    }
    out.resize(static_cast<size_t>(count));  // every point is written below (no assign: no fill)
    cumulative_lengths(pts, cum);
    const double total = cum.back();
    if (count >= 3 && pts.size() >= 2 && total > 0.0 && total < INFINITY) {
        // The common case, with what the general loop below would find spelled out: the lengths
        // asked for only grow and stay short of the total, so the segment is found by walking on
        // from the last without locate_at_length's clamp, its check for a length that went back,
        // or its bound (cum.back() = total > s stops the walk). The root and tip (i = 0 and
        // count - 1) are set after the loop, as there. Same divisions, same lerp: same bits.
        size_t hi = 1;  // the first point whose cumulative length exceeds s: cum[0] = 0 < s
        for (int i = 1; i + 1 < count; ++i) {
            const double s = total * i / (count - 1);
            if (s <= 0.0) out[i] = pts.front();  // underflow of a tiny total
            else if (s >= total) out[i] = pts.back();
            else {
                while (cum[hi] <= s) ++hi;
                const size_t lo = hi - 1;
                const double seg = cum[hi] - cum[lo];
                const double t = seg > 0.0 ? (s - cum[lo]) / seg : 0.0;
                out[i] = lerp(pts[lo], pts[hi], static_cast<float>(t));
            }
        }
    }
    else {
        size_t cursor = 0;  // the lengths asked for only grow: each lookup walks on from the last
        for (int i = 0; i < count; ++i) {
            const double s = total * i / (count - 1);
            if (count == 1 || pts.size() == 1 || s <= 0.0) out[i] = pts.front();
            else if (s >= total) out[i] = pts.back();
            else {
                const ArcSpot a = locate_at_length(cum, s, cursor);
                out[i] = lerp(pts[a.lo], pts[a.hi], static_cast<float>(a.t));
            }
        }
    }
    if (count >= 2) {
        out.front() = pts.front();
        out.back() = total > 0.0 ? pts.back() : pts.front();
    }
}

std::vector<float3> polyline_tangents(std::span<const float3> pts)
{
    std::vector<float3> t;
    polyline_tangents(pts, t);
    return t;
}

void polyline_tangents(std::span<const float3> pts, std::vector<float3>& t)
{
    const size_t n = pts.size();
    t.assign(n, float3(0, 1, 0));
    if (n < 2) return;
    // A zero vector marks a point with no tangent of its own yet (a unit tangent is never zero).
    bool any_missing = false;
    for (size_t i = 0; i < n; ++i) {
        const float3 a = pts[i == 0 ? 0 : i - 1];
        const float3 b = pts[i + 1 == n ? n - 1 : i + 1];
        const float3 d = b - a;
        if (length_squared(d) > 0.0f) t[i] = normalize(d);
        else t[i] = float3(0, 0, 0), any_missing = true;
    }
    if (!any_missing) return;
    auto missing = [&](size_t i) { return t[i].x == 0.0f && t[i].y == 0.0f && t[i].z == 0.0f; };
    // Fill degenerate tangents from the nearest valid neighbour (forward, then backward).
    for (size_t i = 1; i < n; ++i)
        if (missing(i) && !missing(i - 1)) t[i] = t[i - 1];
    for (size_t i = n - 1; i-- > 0;)
        if (missing(i) && !missing(i + 1)) t[i] = t[i + 1];
    for (float3& v : t)
        if (v.x == 0.0f && v.y == 0.0f && v.z == 0.0f) v = float3(0, 1, 0);  // no extent at all: +Y
}

double segment_distance_sq(const float3& p1f, const float3& q1f, const float3& p2f, const float3& q2f)
{
    struct D3 {
        double x, y, z;
    };
    auto sub = [](const D3& a, const D3& b) { return D3{a.x - b.x, a.y - b.y, a.z - b.z}; };
    auto dt = [](const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
    const D3 p1{p1f.x, p1f.y, p1f.z}, q1{q1f.x, q1f.y, q1f.z}, p2{p2f.x, p2f.y, p2f.z}, q2{q2f.x, q2f.y, q2f.z};
    const D3 d1 = sub(q1, p1), d2 = sub(q2, p2), r = sub(p1, p2);
    const double a = dt(d1, d1), e = dt(d2, d2), f = dt(d2, r);
    double s, t;
    if (a <= 1e-30 && e <= 1e-30) {
        s = t = 0.0;
    }
    else if (a <= 1e-30) {
        s = 0.0;
        t = std::clamp(f / e, 0.0, 1.0);
    }
    else {
        const double c = dt(d1, r);
        if (e <= 1e-30) {
            t = 0.0;
            s = std::clamp(-c / a, 0.0, 1.0);
        }
        else {
            const double b = dt(d1, d2), denom = a * e - b * b;
            s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = std::clamp(-c / a, 0.0, 1.0);
            }
            else if (t > 1.0) {
                t = 1.0;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    const D3 c1{p1.x + d1.x * s, p1.y + d1.y * s, p1.z + d1.z * s};
    const D3 c2{p2.x + d2.x * t, p2.y + d2.y * t, p2.z + d2.z * t};
    const D3 d = sub(c1, c2);
    return dt(d, d);
}

}  // namespace groom
