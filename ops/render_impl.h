// Internals of the renderer shared by ops/render*.cpp: limits, colour packing, the camera basis and
// projection, and colour attribute lookup. Not part of the op's interface (ops/render.h); only the
// render*.cpp files include it, and pack / Projector / ColorSource stay inline for their hot loops.
#pragma once

#include "kernel/error.h"
#include "ops/render.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <string_view>

namespace groom::render_detail {

constexpr float kPi = 3.14159265358979f;
constexpr int kMaxSide = 16384;                 // pixels per side of one view

inline std::string fmt(float v) { return format_number(v); }

inline uint32_t pack(const float3& c)
{
    auto u8 = [](float v) { return static_cast<uint32_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
    return u8(c.x) | (u8(c.y) << 8) | (u8(c.z) << 16);
}
inline float3 unpack(uint32_t c)
{
    return {float(c & 255u) / 255.0f, float((c >> 8) & 255u) / 255.0f, float((c >> 16) & 255u) / 255.0f};
}

/// Orthonormal camera basis: forward (into the picture), right, up.
struct Basis {
    float3 forward, right, up;
};

Basis camera_basis(const Camera& cam);

/// Maps scene points to sample coordinates (x right, y down, pixel centres at i + 0.5) and depth.
struct Projector {
    Basis basis;
    float3 origin;  // eye (perspective) or target (orthographic)
    bool perspective = false;
    float scale = 1.0f;  // orthographic: samples per scene unit; perspective: samples at unit depth
    float cx = 0.0f, cy = 0.0f;
    float near = 0.0f;

    Projector(const Camera& cam, int width_samples, int height_samples)
    {
        basis = camera_basis(cam);
        perspective = cam.fov_degrees > 0.0f;
        cx = 0.5f * float(width_samples);
        cy = 0.5f * float(height_samples);
        if (perspective) {
            origin = cam.eye;
            scale = cy / std::tan(0.5f * cam.fov_degrees * kPi / 180.0f);
            near = 1e-3f * distance(cam.eye, cam.target);
        }
        else {
            origin = cam.target;
            scale = float(height_samples) / cam.ortho_height;
        }
    }

    /// False when the point is behind the near plane (perspective only).
    bool project(const float3& p, float& sx, float& sy, float& depth, float& samples_per_unit) const
    {
        const float3 v = p - origin;
        const float x = dot(v, basis.right), y = dot(v, basis.up);
        depth = dot(v, basis.forward);
        float k = scale;
        if (perspective) {
            if (depth < near) return false;
            k = scale / depth;
        }
        sx = cx + x * k;
        sy = cy - y * k;
        samples_per_unit = k;
        return true;
    }
};

/// One colour attribute column resolved to spans.
struct ColorSource {
    std::span<const int32_t> i32;
    std::span<const int64_t> i64;
    std::span<const float> f32;
    bool per_point = false;
    bool valid() const { return !i32.empty() || !i64.empty() || !f32.empty(); }
    int64_t value(size_t i) const
    {
        if (!i32.empty()) return i32[i];
        if (!i64.empty()) return i64[i];
        return static_cast<int64_t>(std::floor(f32[i]));
    }
};

/// The colour attribute `name` of `curves`: point domain first, then curve; !valid() when absent.
ColorSource find_color_source(const CurveSet& curves, std::string_view name);
/// The attribute a ColorBy reads ("strand", ...); empty for None, Id and File.
std::string_view attribute_of(ColorBy c);

}  // namespace groom::render_detail
