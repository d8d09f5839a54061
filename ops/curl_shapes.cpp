#include "ops/curl_shapes.h"

#include "kernel/error.h"

#include <array>
#include <cmath>
#include <numbers>

namespace groom {

namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

/// Wraps t into [0, 1): the shapes are periodic with period one cycle.
float wrap01(float t)
{
    const float w = t - std::floor(t);
    return w < 1.0f ? w : 0.0f;
}

// Sec. 3.1, shape 0: the Lame curve (superellipse) |x|^n + |y|^n = 1, traced by the classic
// x = sgn(cos a) |cos a|^(2/n), y = sgn(sin a) |sin a|^(2/n). It starts at a = pi/4 because for n < 1
// the curve has cusps on the axes, and for any n its diagonal point is smooth.
ShapePoint lame(const ShapeParams& p, float t)
{
    const float a = kTwoPi * t + 0.25f * std::numbers::pi_v<float>;
    const float c = std::cos(a), s = std::sin(a), e = 2.0f / p.lame_exponent;
    return {std::copysign(std::pow(std::fabs(c), e), c), std::copysign(std::pow(std::fabs(s), e), s)};
}

// Shape 1: the regular N-gon with circumradius 1, at constant speed along its perimeter. Vertex j
// sits at angle 2 pi (j + 1/2) / N so that t = 0 is the middle of the edge crossing +x (a smooth
// point: consecutive cycles blend on a straight edge, never across a corner).
ShapePoint polygon(const ShapeParams& p, float t)
{
    const int n = p.polygon_sides;
    const float tau = wrap01(t) * float(n) + 0.5f;
    const int edge = int(std::floor(tau));
    const float f = tau - float(edge);
    const float a0 = kTwoPi * (float(edge) - 0.5f) / float(n), a1 = kTwoPi * (float(edge) + 0.5f) / float(n);
    return {std::cos(a0) + (std::cos(a1) - std::cos(a0)) * f, std::sin(a0) + (std::sin(a1) - std::sin(a0)) * f};
}

// Shape 2: the ellipse x = cos, y = aspect * sin (major axis along the frame normal).
ShapePoint ellipse(const ShapeParams& p, float t)
{
    const float a = kTwoPi * t;
    return {std::cos(a), p.ellipse_aspect * std::sin(a)};
}

// Shape 3: the circle, the cross-section of the classic helix curl.
ShapePoint circle(const ShapeParams&, float t)
{
    const float a = kTwoPi * t;
    return {std::cos(a), std::sin(a)};
}

// Shape 4: the polar rose r = cos(k theta). For odd k the curve closes after theta = pi (k petals),
// for even k after 2 pi (2k petals); one cycle traces it exactly once, starting on a petal tip.
ShapePoint rose(const ShapeParams& p, float t)
{
    const int k = p.rose_petals;
    const float theta = (k % 2 ? std::numbers::pi_v<float> : kTwoPi) * wrap01(t);
    const float r = std::cos(float(k) * theta);
    return {r * std::cos(theta), r * std::sin(theta)};
}

struct ShapeEntry {
    const char* name;
    ShapePoint (*point)(const ShapeParams&, float);
};

// The dictionary, in the talk's order. A new shape: one function above and one line here.
constexpr std::array<ShapeEntry, 5> kShapes{{
    {"lame", lame},
    {"polygon", polygon},
    {"ellipse", ellipse},
    {"circle", circle},
    {"rose", rose},
}};

}  // namespace

void ShapeParams::validate() const
{
    if (!(lame_exponent > 0.0f) || !std::isfinite(lame_exponent) || lame_exponent > 100.0f) {
        throw InvalidParam("curl: `lame_exponent` must be in (0, 100] (got " + format_number(lame_exponent) + ")");
    }
    if (polygon_sides < 3 || polygon_sides > 64) {
        throw InvalidParam("curl: `polygon_sides` must be in 3..64 (got " + std::to_string(polygon_sides) + ")");
    }
    if (!(ellipse_aspect > 0.0f) || !(ellipse_aspect <= 1.0f)) {
        throw InvalidParam("curl: `ellipse_aspect` must be in (0, 1] (got " + format_number(ellipse_aspect) + ")");
    }
    if (rose_petals < 1 || rose_petals > 32) {
        throw InvalidParam("curl: `rose_petals` must be in 1..32 (got " + std::to_string(rose_petals) + ")");
    }
}

int curl_shape_count() { return int(kShapes.size()); }

std::string_view curl_shape_name(int shape)
{
    return shape >= 0 && shape < curl_shape_count() ? kShapes[size_t(shape)].name : "unknown";
}

std::string curl_shape_list()
{
    std::string out;
    for (int i = 0; i < curl_shape_count(); ++i) {
        if (i) out += ", ";
        out += std::to_string(i) + " " + kShapes[size_t(i)].name;
    }
    return out;
}

ShapePoint curl_shape_point(int shape, const ShapeParams& params, float t)
{
    return kShapes[size_t(shape)].point(params, t);
}

}  // namespace groom
