#include "kernel/math/spline.h"

#include <algorithm>
#include <cmath>

namespace groom {

float catmull_rom(float p0, float p1, float p2, float p3, float t)
{
    const float t2 = t * t, t3 = t2 * t;
    return 0.5f * ((2.0f * p1) + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 + (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t3);
}

float3 catmull_rom(const float3& p0, const float3& p1, const float3& p2, const float3& p3, float t)
{
    return {catmull_rom(p0.x, p1.x, p2.x, p3.x, t), catmull_rom(p0.y, p1.y, p2.y, p3.y, t),
            catmull_rom(p0.z, p1.z, p2.z, p3.z, t)};
}

float3 bspline(const float3& p0, const float3& p1, const float3& p2, const float3& p3, float t)
{
    const float s = 1.0f - t, t2 = t * t, t3 = t2 * t;
    const float b0 = s * s * s / 6.0f;
    const float b1 = (3.0f * t3 - 6.0f * t2 + 4.0f) / 6.0f;
    const float b2 = (-3.0f * t3 + 3.0f * t2 + 3.0f * t + 1.0f) / 6.0f;
    const float b3 = t3 / 6.0f;
    return p0 * b0 + p1 * b1 + p2 * b2 + p3 * b3;
}

std::vector<float3> evaluate_cubic(std::span<const float3> cvs, CubicBasis basis, bool pinned, int samples_per_segment)
{
    std::vector<float3> pts(cvs.begin(), cvs.end());
    if (pinned && pts.size() >= 2) {
        // Phantom points chosen so the curve starts/ends exactly on the end control points:
        // reflection for Catmull-Rom, 2*p0 - p1 for B-spline (its end condition).
        pts.insert(pts.begin(), 2.0f * cvs[0] - cvs[1]);
        pts.push_back(2.0f * cvs[cvs.size() - 1] - cvs[cvs.size() - 2]);
    }
    if (pts.size() < 4) return std::vector<float3>(cvs.begin(), cvs.end());
    const int k = std::max(samples_per_segment, 1);
    const size_t segments = pts.size() - 3;
    std::vector<float3> out;
    out.reserve(segments * k + 1);
    for (size_t s = 0; s < segments; ++s) {
        for (int i = 0; i < k; ++i) {
            const float t = static_cast<float>(i) / k;
            out.push_back(basis == CubicBasis::CatmullRom ? catmull_rom(pts[s], pts[s + 1], pts[s + 2], pts[s + 3], t)
                                                          : bspline(pts[s], pts[s + 1], pts[s + 2], pts[s + 3], t));
        }
    }
    const size_t s = segments - 1;
    out.push_back(basis == CubicBasis::CatmullRom ? pts[s + 2] : bspline(pts[s], pts[s + 1], pts[s + 2], pts[s + 3], 1.0f));
    if (pinned && basis == CubicBasis::CatmullRom) {
        out.front() = cvs.front();
        out.back() = cvs.back();
    }
    return out;
}

float sample_uniform_spline(std::span<const float> values, float t)
{
    if (values.empty()) return 1.0f;
    if (values.size() == 1) return values[0];
    const int n = static_cast<int>(values.size());
    const float x = std::clamp(t, 0.0f, 1.0f) * (n - 1);
    const int i = std::min(static_cast<int>(std::floor(x)), n - 2);
    const float u = x - i;
    auto v = [&](int j) { return values[std::clamp(j, 0, n - 1)]; };
    // Clamped ends: reflect the neighbour so the end tangent follows the data.
    const float p0 = i == 0 ? 2.0f * v(0) - v(1) : v(i - 1);
    const float p3 = i + 2 >= n ? 2.0f * v(n - 1) - v(n - 2) : v(i + 2);
    return catmull_rom(p0, v(i), v(i + 1), p3, u);
}

}  // namespace groom
