// float3: the small value type for positions, directions and colours throughout groom.
// Deliberately dependency-free so kernel/ stays free of OpenVDB, CGAL and Eigen.
#pragma once

#include <cmath>

namespace groom {

struct float3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;

    constexpr float3() = default;
    constexpr float3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}

    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr float3 operator-() const { return {-x, -y, -z}; }
    constexpr float3& operator+=(const float3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    constexpr float3& operator-=(const float3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    constexpr float3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
    constexpr float3& operator/=(float s) { x /= s; y /= s; z /= s; return *this; }
    friend constexpr bool operator==(const float3&, const float3&) = default;
};

constexpr float3 operator+(float3 a, const float3& b) { return a += b; }
constexpr float3 operator-(float3 a, const float3& b) { return a -= b; }
constexpr float3 operator*(float3 a, float s) { return a *= s; }
constexpr float3 operator*(float s, float3 a) { return a *= s; }
constexpr float3 operator/(float3 a, float s) { return a /= s; }

constexpr float dot(const float3& a, const float3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr float3 cross(const float3& a, const float3& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const float3& a) { return std::sqrt(dot(a, a)); }
constexpr float length_squared(const float3& a) { return dot(a, a); }
inline float distance(const float3& a, const float3& b) { return length(a - b); }
constexpr float3 lerp(const float3& a, const float3& b, float t) { return a + (b - a) * t; }
constexpr float3 min(const float3& a, const float3& b)
{
    return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
constexpr float3 max(const float3& a, const float3& b)
{
    return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}

/// Unit vector along `a`; returns `fallback` when `a` is (near) zero length.
inline float3 normalize(const float3& a, const float3& fallback = {0.0f, 0.0f, 0.0f})
{
    const float len = length(a);
    return len > 1e-30f ? a / len : fallback;
}

/// normalize() for a vector already within 1e-3 of unit length (a rotated or interpolated unit
/// vector): one Newton step of 1 / sqrt from 1, exact to 4e-7, with no square root or division on
/// the dependency chain of a frame walked along a curve (rotation_minimising_frames, curl).
inline float3 renormalize(const float3& a, const float3& fallback = {0.0f, 0.0f, 0.0f})
{
    const float l2 = dot(a, a);
    if (l2 > 0.999f && l2 < 1.001f) return a * (1.5f - 0.5f * l2);
    return normalize(a, fallback);
}

inline bool isfinite(const float3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

/// Any unit vector perpendicular to unit vector `n` (stable for every direction).
inline float3 any_perpendicular(const float3& n)
{
    // Cross with the world axis least aligned with n, so the result never degenerates.
    const float ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
    const float3 axis = (ax <= ay && ax <= az) ? float3(1, 0, 0) : (ay <= az ? float3(0, 1, 0) : float3(0, 0, 1));
    return normalize(cross(n, axis));
}

/// Axis-aligned bounding box; empty when min > max.
struct Bounds3 {
    float3 lo{INFINITY, INFINITY, INFINITY};
    float3 hi{-INFINITY, -INFINITY, -INFINITY};
    void extend(const float3& p) { lo = min(lo, p); hi = max(hi, p); }
    bool empty() const { return lo.x > hi.x; }
    float3 size() const { return empty() ? float3() : hi - lo; }
    float3 center() const { return (lo + hi) * 0.5f; }
};

}  // namespace groom
