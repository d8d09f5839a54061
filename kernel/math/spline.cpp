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

namespace {

/// x, y, z and a spare lane in one SSE register (a GCC and Clang vector extension): a float3
/// operation is one instruction instead of three. Arithmetic is per lane and IEEE, so a lane
/// computes what the scalar code would, bit for bit.
typedef float Float4 __attribute__((vector_size(16)));

inline Float4 lanes(const float3& p) { return Float4{p.x, p.y, p.z, 0.0f}; }
inline float3 xyz(const Float4& v) { return {v[0], v[1], v[2]}; }

/// A Catmull-Rom segment as twice its polynomial's coefficients in 1, t, t^2, t^3: the terms of
/// the scalar catmull_rom, with the same operations in the same order, so a segment sampled k
/// times computes them once and gives catmull_rom's bits.
struct CatmullRomSegment {
    Float4 c0, c1, c2, c3;

    CatmullRomSegment(const Float4& p0, const Float4& p1, const Float4& p2, const Float4& p3)
        : c0(2.0f * p1), c1(-p0 + p2), c2(2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3), c3(-p0 + 3.0f * p1 - 3.0f * p2 + p3)
    {
    }
    /// The point at t, given t2 = t * t and t3 = t2 * t.
    Float4 at(float t, float t2, float t3) const { return 0.5f * (c0 + c1 * t + c2 * t2 + c3 * t3); }
};

}  // namespace

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
    out.resize(segments * size_t(k) + 1);  // every point is written below (no clear(): no zero fill)
    size_t o = 0;
    if (basis == CubicBasis::CatmullRom) {
        // Each segment's coefficients once, not per sample, x, y and z in one register, and the
        // control points slid along instead of cv()'s branches per point (evaluate_cubic was a
        // fifth of curl's centreline, perf). The powers of t = i / k are the same for every
        // segment: a table for the first few, so the division is not paid per point. t, t^2 and
        // t^3 are the ones catmull_rom computes, so the points are its bits.
        struct Powers {
            float t, t2, t3;
        };
        auto powers = [k](int i) {
            const float t = static_cast<float>(i) / k, t2 = t * t;
            return Powers{t, t2, t2 * t};
        };
        constexpr int kTabled = 16;
        Powers table[kTabled];
        for (int i = 0; i < std::min(k, kTabled); ++i) table[i] = powers(i);
        const size_t skip = phantoms ? 1 : 0;  // cv(j) is cvs[j - skip] away from the ends
        Float4 p0 = lanes(cv(0)), p1 = lanes(cv(1)), p2 = lanes(cv(2));
        for (size_t s = 0; s < segments; ++s) {
            const Float4 p3 = lanes(s + 1 < segments ? cvs[s + 3 - skip] : cv(s + 3));
            const CatmullRomSegment seg(p0, p1, p2, p3);
            for (int i = 0; i < k; ++i) {
                const Powers w = i < kTabled ? table[i] : powers(i);
                out[o++] = xyz(seg.at(w.t, w.t2, w.t3));
            }
            p0 = p1, p1 = p2, p2 = p3;
        }
        out[o] = xyz(p1);  // cv(segments + 1): the last segment's p2
        if (pinned) {
            out.front() = cvs.front();
            out.back() = cvs.back();
        }
        return;
    }
    for (size_t s = 0; s < segments; ++s) {
        const float3 p0 = cv(s), p1 = cv(s + 1), p2 = cv(s + 2), p3 = cv(s + 3);
        for (int i = 0; i < k; ++i) out[o++] = bspline(p0, p1, p2, p3, static_cast<float>(i) / k);
    }
    const size_t s = segments - 1;
    out[o] = bspline(cv(s), cv(s + 1), cv(s + 2), cv(s + 3), 1.0f);
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
