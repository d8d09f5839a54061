#include "fields/surface.h"

#include <algorithm>
#include <cmath>

namespace groom {

float Surface::query(const float3& p, float3& n, float3& closest) const
{
    n = normal(p);
    closest = closest_point(p);
    return distance(p);
}

float Surface::distance_within(const float3& p, float) const { return distance(p); }

bool Surface::first_intersection(const float3& a, const float3& b, float3& hit, float tolerance) const
{
    const float len = groom::distance(a, b);
    if (len <= 0.0f) return false;
    const float tol = tolerance > 0.0f ? tolerance : std::max(len * 1e-6f, 1e-7f);
    const float3 dir = (b - a) / len;
    float d = distance(a);
    if (d < 0.0f) {
        hit = a;  // starts inside: the entry is the start itself
        return true;
    }
    // Sphere tracing: |distance| bounds how far we can step without crossing the surface.
    float t = 0.0f;
    for (int iter = 0; iter < 10000 && t <= len; ++iter) {
        if (d <= tol) {
            hit = a + dir * t;
            return true;
        }
        const float step = std::max(d, tol * 0.5f);
        const float tn = t + step;
        const float dn = distance(a + dir * std::min(tn, len));
        if (dn < 0.0f) {
            // Crossed inside within [t, tn]: bisect to the tolerance.
            float lo = t, hi = std::min(tn, len);
            while (hi - lo > tol) {
                const float mid = 0.5f * (lo + hi);
                (distance(a + dir * mid) < 0.0f ? hi : lo) = mid;
            }
            hit = a + dir * hi;
            return true;
        }
        if (tn > len) break;
        t = tn;
        d = dn;
    }
    return false;
}

}  // namespace groom
