#include "kernel/math/frames.h"

#include "kernel/math/polyline.h"

#include <cmath>

namespace groom {

std::vector<Frame> rotation_minimising_frames(std::span<const float3> pts, const float3& initial_normal)
{
    const std::vector<float3> tan = polyline_tangents(pts);
    std::vector<Frame> frames(pts.size());
    if (pts.empty()) return frames;

    float3 n0 = initial_normal - tan[0] * dot(initial_normal, tan[0]);
    n0 = length(n0) > 1e-6f * std::max(length(initial_normal), 1e-30f) ? normalize(n0) : any_perpendicular(tan[0]);
    frames[0] = {tan[0], n0, cross(tan[0], n0)};

    for (size_t i = 0; i + 1 < pts.size(); ++i) {
        const Frame& f = frames[i];
        const float3 t1 = tan[i + 1];
        float3 r;
        // Reflection 1 across the bisector plane of the segment x_i -> x_{i+1}.
        const float3 v1 = pts[i + 1] - pts[i];
        const float c1 = dot(v1, v1);
        if (c1 > 0.0f) {
            const float3 rl = f.n - v1 * (2.0f / c1 * dot(v1, f.n));
            const float3 tl = f.t - v1 * (2.0f / c1 * dot(v1, f.t));
            // Reflection 2 maps the reflected tangent onto the new tangent.
            const float3 v2 = t1 - tl;
            const float c2 = dot(v2, v2);
            r = c2 > 0.0f ? rl - v2 * (2.0f / c2 * dot(v2, rl)) : rl;
        }
        else {
            r = f.n;  // coincident points: nothing to rotate through
        }
        // Re-orthonormalise against float drift so long curves stay exact to rounding.
        r = r - t1 * dot(r, t1);
        r = normalize(r, any_perpendicular(t1));
        frames[i + 1] = {t1, r, cross(t1, r)};
    }
    return frames;
}

}  // namespace groom
