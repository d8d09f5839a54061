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
    polyline_tangents(pts, tan);
    frames.resize(pts.size());
    if (pts.empty()) return;
    const size_t n = pts.size();

    float3 n0 = initial_normal - tan[0] * dot(initial_normal, tan[0]);
    n0 = length(n0) > 1e-6f * std::max(length(initial_normal), 1e-30f) ? normalize(n0) : any_perpendicular(tan[0]);
    frames[0] = {tan[0], n0, cross(tan[0], n0)};
    if (n < 16) {
        for (size_t i = 0; i + 1 < n; ++i) {
            const float3 r = next_normal(pts, tan, i, frames[i].n);
            frames[i + 1] = {tan[i + 1], r, cross(tan[i + 1], r)};
        }
        return;
    }
    // Each step waits on the last (about 60 cycles of dependent dot products), so the curve is
    // walked as two halves at once, the second from any normal at its start; the step is linear
    // in the normal and keeps the binormal a binormal, so the second half is then the true one
    // turned about its tangents by one angle, found where the halves meet (the frames were 17%
    // of curl_bench, perf; from 16 points on, not 64: 15% of curling Sintel's 32-point hairs
    // walked in one piece). Three or four pieces were slower: the step's own hundred or so
    // operations, not its latency, then set the pace.
    const size_t h = n / 2;  // the first half walks to h, the second from h (n - h >= h)
    const float3 start = any_perpendicular(tan[h]);
    for (size_t i = 0; i < n - 1 - h; ++i) {
        if (i < h) frames[i + 1].n = next_normal(pts, tan, i, frames[i].n);
        frames[h + i + 1].n = next_normal(pts, tan, h + i, i == 0 ? start : frames[h + i].n);
    }
    if (n - 1 - h < h) frames[h].n = next_normal(pts, tan, h - 1, frames[h - 1].n);
    const float3 want = frames[h].n;
    const float ca = dot(want, start), sa = dot(want, cross(tan[h], start));
    for (size_t j = 0; j < n; ++j) {
        float3 nj = frames[j].n;
        if (j > h) nj = nj * ca + cross(tan[j], nj) * sa;
        frames[j] = {tan[j], nj, cross(tan[j], nj)};
    }
}

}  // namespace groom
