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
    std::vector<float3> out;
    evaluate_cubic(cvs, basis, pinned, samples_per_segment, out);
    return out;
}

void evaluate_cubic(std::span<const float3> cvs, CubicBasis basis, bool pinned, int samples_per_segment, std::vector<float3>& out)
{
    // Phantom points chosen so the curve starts/ends exactly on the end control points:
    // reflection for Catmull-Rom, 2*p0 - p1 for B-spline (its end condition). They are read in
    // place of cvs[-1] and cvs[size], never stored (this runs once per curve in curl).
    const bool phantoms = pinned && cvs.size() >= 2;
    const size_t m = cvs.size(), np = m + (phantoms ? 2 : 0);
    out.clear();
    if (np < 4) {
        out.assign(cvs.begin(), cvs.end());
        return;
    }
    const float3 first = phantoms ? 2.0f * cvs[0] - cvs[1] : float3{}, last = phantoms ? 2.0f * cvs[m - 1] - cvs[m - 2] : float3{};
    auto cv = [&](size_t j) {  // control point j of the extended list
        if (!phantoms) return cvs[j];
        return j == 0 ? first : j == np - 1 ? last : cvs[j - 1];
    };
    const int k = std::max(samples_per_segment, 1);
    const size_t segments = np - 3;
    out.resize(segments * size_t(k) + 1);
    size_t o = 0;
    for (size_t s = 0; s < segments; ++s) {
        const float3 p0 = cv(s), p1 = cv(s + 1), p2 = cv(s + 2), p3 = cv(s + 3);
        for (int i = 0; i < k; ++i) {
            const float t = static_cast<float>(i) / k;
            out[o++] = basis == CubicBasis::CatmullRom ? catmull_rom(p0, p1, p2, p3, t) : bspline(p0, p1, p2, p3, t);
        }
    }
    const size_t s = segments - 1;
    out[o] = basis == CubicBasis::CatmullRom ? cv(s + 2) : bspline(cv(s), cv(s + 1), cv(s + 2), cv(s + 3), 1.0f);
    if (pinned && basis == CubicBasis::CatmullRom) {
        out.front() = cvs.front();
        out.back() = cvs.back();
    }
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
