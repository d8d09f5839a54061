#include "fields/surface_path.h"

#include <cmath>

namespace groom {

bool surface_path(const Surface& scalp, const float3& from, const float3& to, float step, float lift, std::vector<float3>& out)
{
    out.clear();
    float3 n, c;
    scalp.query(from, n, c);
    float3 p = c;
    float3 target_n, target;
    scalp.query(to, target_n, target);
    out.push_back(p + n * lift);
    const double max_steps = 4.0 * double(distance(from, to)) / double(step) + 16.0;
    float best = distance(p, target);
    int stalled = 0;
    for (int k = 0; k < max_steps; ++k) {
        const float3 d = target - p;
        if (length(d) <= step) {
            if (length(d) > 1e-6f * step || out.size() == 1) out.push_back(target + target_n * lift);
            return true;
        }
        if (stalled >= 8) {
            // Eight steps without getting closer: a concave fold (behind an ear) pulls each step back
            // where it came from. Finish along the chord, each point put back on the surface.
            const int m = int(std::ceil(length(d) / step));
            for (int j = 1; j <= m; ++j) {
                scalp.query(p + d * (float(j) / float(m)), n, c);
                out.push_back(c + n * lift);
            }
            out.back() = target + target_n * lift;
            return true;
        }
        // Toward the target within the tangent plane (a chord through the head would cut inside).
        float3 t = d - n * dot(d, n);
        t = normalize(t, any_perpendicular(n));
        scalp.query(p + t * step, n, c);
        p = c;
        out.push_back(p + n * lift);
        const float now = distance(p, target);
        if (now < best - 0.05f * step) {
            best = now;
            stalled = 0;
        }
        else {
            ++stalled;
        }
    }
    return false;
}

bool surface_path_through(const Surface& scalp, const std::vector<float3>& waypoints, float step, float lift, std::vector<float3>& out)
{
    out.clear();
    if (waypoints.empty()) return true;
    if (waypoints.size() == 1) {
        float3 n, c;
        scalp.query(waypoints[0], n, c);
        out.push_back(c + n * lift);
        return true;
    }
    std::vector<float3> leg;
    for (size_t i = 0; i + 1 < waypoints.size(); ++i) {
        const bool ok = surface_path(scalp, waypoints[i], waypoints[i + 1], step, lift, leg);
        out.insert(out.end(), leg.begin() + (out.empty() ? 0 : 1), leg.end());
        if (!ok) return false;
    }
    return true;
}

}  // namespace groom
