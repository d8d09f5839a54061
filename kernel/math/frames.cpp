#include "kernel/math/frames.h"

#include "kernel/math/polyline.h"

#include <cmath>

namespace groom {

namespace {

/// The double-reflection step (Wang et al. 2008): the normal at point i + 1 from the normal `n` at i.
inline float3 next_normal(std::span<const float3> pts, const std::vector<float3>& tan, size_t i, const float3& n)
{
    const float3 t1 = tan[i + 1];
    float3 r;
    // Reflection 1 across the bisector plane of the segment x_i -> x_{i+1}.
    const float3 v1 = pts[i + 1] - pts[i];
    const float c1 = dot(v1, v1);
    if (c1 > 0.0f) {
        const float3 rl = n - v1 * (2.0f / c1 * dot(v1, n));
        const float3 tl = tan[i] - v1 * (2.0f / c1 * dot(v1, tan[i]));
        // Reflection 2 maps the reflected tangent onto the new tangent.
        const float3 v2 = t1 - tl;
        const float c2 = dot(v2, v2);
        r = c2 > 0.0f ? rl - v2 * (2.0f / c2 * dot(v2, rl)) : rl;
    }
    else {
        r = n;  // coincident points: nothing to rotate through
    }
    // Re-orthonormalise against float drift so long curves stay exact to rounding. r is a unit
    // vector twice reflected, so one Newton step keeps it unit without a square root and divisions
    // on the chain from frame to frame; the fallback only when r vanished (any_perpendicular as an
    // argument cost a cross product and a square root every step: a third of this loop, perf).
    r = r - t1 * dot(r, t1);
    return dot(r, r) > 0.0f ? renormalize(r) : any_perpendicular(t1);
}

/// Four floats in one SSE register and four lanes' truth (-1 or 0): a GCC and Clang vector
/// extension. Arithmetic is per lane and IEEE, so a lane computes what the scalar code would.
typedef float Float4 __attribute__((vector_size(16)));
typedef int Int4 __attribute__((vector_size(16)));

/// Two float3 side by side, coordinate by coordinate: lane 0 the first half's, lane 1 the second
/// half's (lanes 2 and 3 unused).
struct Pair {
    Float4 x, y, z;
};
inline Pair pair(const float3& a, const float3& b)
{
    return {Float4{a.x, b.x, 0.0f, 0.0f}, Float4{a.y, b.y, 0.0f, 0.0f}, Float4{a.z, b.z, 0.0f, 0.0f}};
}
inline float3 lane(const Pair& p, int k) { return {p.x[k], p.y[k], p.z[k]}; }
inline void set_lane(Pair& p, int k, const float3& v) { p.x[k] = v.x, p.y[k] = v.y, p.z[k] = v.z; }
inline Pair operator-(const Pair& a, const Pair& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Pair operator*(const Pair& a, const Float4& s) { return {a.x * s, a.y * s, a.z * s}; }
inline Float4 dot(const Pair& a, const Pair& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Float4 splat(float v) { return Float4{v, v, v, v}; }
inline Float4 keep(const Float4& v, const Int4& mask) { return (Float4)((Int4)v & mask); }

/// next_normal for both halves at once, each lane its operations in their order (so its bits),
/// where `ok` is set; where it is not (coincident points, or a normal that next_normal does not
/// renormalise the short way) the caller takes next_normal itself. c2 = 0 (the reflected
/// tangent already the new one) is no exception: there the second reflection subtracts +0,
/// which leaves every float as it was, -0 included.
inline Pair next_normals(const Pair& p0, const Pair& p1, const Pair& t0, const Pair& t1, const Pair& n, Int4& ok)
{
    const Pair v1 = p1 - p0;
    const Float4 c1 = dot(v1, v1);
    const Float4 k1 = splat(2.0f) / c1;
    const Pair rl = n - v1 * (k1 * dot(v1, n));
    const Pair tl = t0 - v1 * (k1 * dot(v1, t0));
    const Pair v2 = t1 - tl;
    const Float4 c2 = dot(v2, v2);
    const Float4 k2 = splat(2.0f) / c2;
    const Int4 two = c2 > splat(0.0f);
    const Float4 s2 = k2 * dot(v2, rl);
    Pair r = rl - Pair{keep(v2.x * s2, two), keep(v2.y * s2, two), keep(v2.z * s2, two)};
    r = r - t1 * dot(r, t1);
    const Float4 l2 = dot(r, r);
    ok = (c1 > splat(0.0f)) & (l2 > splat(0.999f)) & (l2 < splat(1.001f));
    return r * (splat(1.5f) - splat(0.5f) * l2);
}

/// The first frame's normal: `initial_normal` made perpendicular to tangent t0.
inline float3 first_normal(const float3& initial_normal, const float3& t0)
{
    const float3 n0 = initial_normal - t0 * dot(initial_normal, t0);
    return length(n0) > 1e-6f * std::max(length(initial_normal), 1e-30f) ? normalize(n0) : any_perpendicular(t0);
}

/// Point i's tangent as polyline_tangents computes it, or false where it has none of its own
/// (polyline_tangents then takes a neighbour's).
inline bool own_tangent(std::span<const float3> pts, size_t i, float3& t)
{
    const size_t n = pts.size();
    const float3 d = pts[i + 1 == n ? n - 1 : i + 1] - pts[i == 0 ? 0 : i - 1];
    if (!(length_squared(d) > 0.0f)) return false;
    t = normalize(d);
    return true;
}

/// The frames of a curve of 16 or more points. Each step waits on the last (about 60 cycles of
/// dependent dot products), so the curve is walked as two halves at once, the second from any
/// normal at its start; the step is linear in the normal and keeps the binormal a binormal, so
/// the second half is then the true one turned about its tangents by one angle, found where the
/// halves meet (the frames were 17% of curl_bench, perf; from 16 points on, not 64: 15% of
/// curling Sintel's 32-point hairs walked in one piece). Three or four pieces were slower: the
/// step's own hundred or so operations, not its latency, then set the pace.
///
/// The halves step side by side in the lanes of SSE registers (next_normals): half the
/// instructions of stepping them one after the other, which, not the chain, had set the pace
/// (with its chain cut that walk was no faster, perf). That leaves the walk mostly waiting on
/// its chain, so with `own_tangents` the tangents are computed inside it, two steps ahead of
/// their use, instead of in a pass of their own before it (their square roots and divisions
/// then mostly hide in that wait): false then, and nothing to keep, where a point has no
/// tangent of its own, which needs polyline_tangents' neighbours first.
bool walk_in_halves(std::span<const float3> pts, const float3& initial_normal, std::vector<Frame>& frames, std::vector<float3>& tan,
                    bool own_tangents)
{
    const size_t n = pts.size(), h = n / 2;  // the first half walks to h, the second from h (n - h >= h)
    bool own = true;
    if (own_tangents) {
        tan.resize(n);
        own = own_tangent(pts, 0, tan[0]) && own_tangent(pts, 1, tan[1]) && own_tangent(pts, h, tan[h]) &&
              own_tangent(pts, h + 1, tan[h + 1]);
        if (!own) return false;
    }
    const float3 n0 = first_normal(initial_normal, tan[0]);
    frames[0] = {tan[0], n0, cross(tan[0], n0)};
    const float3 start = any_perpendicular(tan[h]);
    Pair nn = pair(n0, start), p0 = pair(pts[0], pts[h]), t0 = pair(tan[0], tan[h]);
    for (size_t i = 0; i < n - 1 - h; ++i) {  // i < h throughout: both halves step every time
        if (own_tangents) {
            if (i + 2 < h) own &= own_tangent(pts, i + 2, tan[i + 2]);
            if (h + i + 2 < n) own &= own_tangent(pts, h + i + 2, tan[h + i + 2]);
        }
        const Pair p1 = pair(pts[i + 1], pts[h + i + 1]), t1 = pair(tan[i + 1], tan[h + i + 1]);
        Int4 ok;
        Pair next = next_normals(p0, p1, t0, t1, nn, ok);
        if (!ok[0]) set_lane(next, 0, next_normal(pts, tan, i, lane(nn, 0)));
        if (!ok[1]) set_lane(next, 1, next_normal(pts, tan, h + i, lane(nn, 1)));
        frames[i + 1].n = lane(next, 0);
        frames[h + i + 1].n = lane(next, 1);
        nn = next, p0 = p1, t0 = t1;
    }
    if (!own) return false;
    if (n - 1 - h < h) frames[h].n = next_normal(pts, tan, h - 1, frames[h - 1].n);
    const float3 want = frames[h].n;
    const float ca = dot(want, start), sa = dot(want, cross(tan[h], start));
    for (size_t j = 0; j < n; ++j) {
        float3 nj = frames[j].n;
        if (j > h) nj = nj * ca + cross(tan[j], nj) * sa;
        frames[j] = {tan[j], nj, cross(tan[j], nj)};
    }
    return true;
}

}  // namespace

std::vector<Frame> rotation_minimising_frames(std::span<const float3> pts, const float3& initial_normal)
{
    std::vector<Frame> frames;
    std::vector<float3> tan;
    rotation_minimising_frames(pts, initial_normal, frames, tan);
    return frames;
}

void rotation_minimising_frames(std::span<const float3> pts, const float3& initial_normal, std::vector<Frame>& frames,
                                std::vector<float3>& tan)
{
    frames.resize(pts.size());
    if (pts.size() >= 16 && walk_in_halves(pts, initial_normal, frames, tan, true)) return;
    polyline_tangents(pts, tan);
    if (pts.empty()) return;
    const size_t n = pts.size();
    if (n >= 16) {
        walk_in_halves(pts, initial_normal, frames, tan, false);
        return;
    }
    const float3 n0 = first_normal(initial_normal, tan[0]);
    frames[0] = {tan[0], n0, cross(tan[0], n0)};
    for (size_t i = 0; i + 1 < n; ++i) {
        const float3 r = next_normal(pts, tan, i, frames[i].n);
        frames[i + 1] = {tan[i + 1], r, cross(tan[i + 1], r)};
    }
}

}  // namespace groom
