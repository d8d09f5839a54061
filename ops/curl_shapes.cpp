#include "ops/curl_shapes.h"

#include "kernel/error.h"
#include "kernel/math/vector_math.h"

#include <algorithm>
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

/// A run of one shape's points, cut into chunks this long so the angles and their sines and cosines
/// live on the stack.
constexpr size_t kChunk = 64;

/// Scratch of one chunk.
struct Chunk {
    float a[kChunk], s[kChunk], c[kChunk];
};

// Sec. 3.1, shape 0: the Lame curve (superellipse) |x|^n + |y|^n = 1, traced by the classic
// x = sgn(cos a) |cos a|^(2/n), y = sgn(sin a) |sin a|^(2/n). It starts at a = pi/4 because for n < 1
// the curve has cusps on the axes, and for any n its diagonal point is smooth.
void lame(const ShapeTable& table, const float* t, size_t n, float* x, float* y, Chunk& w)
{
    const float e = 2.0f / table.params.lame_exponent;
    for (size_t i = 0; i < n; ++i) w.a[i] = kTwoPi * t[i] + 0.25f * std::numbers::pi_v<float>;
    sin_cos(w.a, n, w.s, w.c);
    for (size_t i = 0; i < n; ++i) w.a[i] = std::fabs(w.c[i]);
    pow_of(w.a, e, n, x);
    for (size_t i = 0; i < n; ++i) w.a[i] = std::fabs(w.s[i]);
    pow_of(w.a, e, n, y);
    for (size_t i = 0; i < n; ++i) x[i] = std::copysign(x[i], w.c[i]), y[i] = std::copysign(y[i], w.s[i]);
}

// Shape 1: the regular N-gon with circumradius 1, at constant speed along its perimeter. Vertex j
// sits at angle 2 pi (j + 1/2) / N so that t = 0 is the middle of the edge crossing +x (a smooth
// point: consecutive cycles blend on a straight edge, never across a corner). The corners are the
// table's.
void polygon(const ShapeTable& table, const float* t, size_t n, float* x, float* y, Chunk&)
{
    const int sides = table.params.polygon_sides;
    for (size_t i = 0; i < n; ++i) {
        const float tau = wrap01(t[i]) * float(sides) + 0.5f;
        const int edge = int(std::floor(tau));
        const float f = tau - float(edge);
        const ShapePoint a = table.corners[size_t(edge)], b = table.corners[size_t(edge) + 1];
        x[i] = a.x + (b.x - a.x) * f;
        y[i] = a.y + (b.y - a.y) * f;
    }
}

// Shape 2: the ellipse x = cos, y = aspect * sin (major axis along the frame normal).
void ellipse(const ShapeTable& table, const float* t, size_t n, float* x, float* y, Chunk& w)
{
    for (size_t i = 0; i < n; ++i) w.a[i] = kTwoPi * t[i];
    sin_cos(w.a, n, y, x);
    for (size_t i = 0; i < n; ++i) y[i] = table.params.ellipse_aspect * y[i];
}

// Shape 3: the circle, the cross-section of the classic helix curl.
void circle(const ShapeTable&, const float* t, size_t n, float* x, float* y, Chunk& w)
{
    for (size_t i = 0; i < n; ++i) w.a[i] = kTwoPi * t[i];
    sin_cos(w.a, n, y, x);
}

// Shape 4: the polar rose r = cos(k theta). For odd k the curve closes after theta = pi (k petals),
// for even k after 2 pi (2k petals); one cycle traces it exactly once, starting on a petal tip.
void rose(const ShapeTable& table, const float* t, size_t n, float* x, float* y, Chunk& w)
{
    const int k = table.params.rose_petals;
    const float turn = k % 2 ? std::numbers::pi_v<float> : kTwoPi;
    for (size_t i = 0; i < n; ++i) w.a[i] = turn * wrap01(t[i]);
    sin_cos(w.a, n, w.s, w.c);
    for (size_t i = 0; i < n; ++i) w.a[i] = float(k) * w.a[i];
    cos_of(w.a, n, w.a);  // r
    for (size_t i = 0; i < n; ++i) x[i] = w.a[i] * w.c[i], y[i] = w.a[i] * w.s[i];
}

struct ShapeEntry {
    const char* name;
    void (*points)(const ShapeTable&, const float*, size_t, float*, float*, Chunk&);
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

ShapeTable::ShapeTable(const ShapeParams& p) : params(p)
{
    const int n = std::clamp(p.polygon_sides, 3, 64);
    for (int j = 0; j < n + 2; ++j) {
        const float a = kTwoPi * (float(j) - 0.5f) / float(n);
        corners.push_back({std::cos(a), std::sin(a)});
    }
}

void curl_shape_points(int shape, const ShapeTable& table, const float* t, size_t n, float* x, float* y)
{
    Chunk w;
    for (size_t i = 0; i < n; i += kChunk) {
        const size_t count = std::min(kChunk, n - i);
        kShapes[size_t(shape)].points(table, t + i, count, x + i, y + i, w);
    }
}

ShapePoint curl_shape_point(int shape, const ShapeParams& params, float t)
{
    ShapePoint q;
    curl_shape_points(shape, ShapeTable(params), &t, 1, &q.x, &q.y);
    return q;
}

}  // namespace groom
