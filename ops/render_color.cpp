// Colour maps: categorical colours for integer values (golden-ratio hues), the --color-by names, and
// finding the attribute a ColorBy reads. Apart from the rasteriser, which only packs what these give it.
#include "ops/render_impl.h"

#include <cmath>

namespace groom {

using namespace render_detail;

namespace {

float3 hsv(float h, float s, float v)
{
    h = (h - std::floor(h)) * 6.0f;
    const int i = static_cast<int>(h) % 6;
    const float f = h - std::floor(h);
    const float a = v * (1 - s), b = v * (1 - s * f), c = v * (1 - s * (1 - f));
    switch (i) {
    case 0: return {v, c, a};
    case 1: return {b, v, a};
    case 2: return {a, v, c};
    case 3: return {a, b, v};
    case 4: return {c, a, v};
    default: return {v, a, b};
    }
}

}  // namespace

namespace render_detail {

ColorSource find_color_source(const CurveSet& curves, std::string_view name)
{
    ColorSource s;
    for (Domain d : {Domain::Point, Domain::Curve}) {
        s.i32 = curves.find<int32_t>(d, name);
        s.i64 = curves.find<int64_t>(d, name);
        s.f32 = curves.find<float>(d, name);
        s.per_point = d == Domain::Point;
        if (s.valid()) return s;
    }
    return {};
}

std::string_view attribute_of(ColorBy c)
{
    switch (c) {
    case ColorBy::Strand: return "strand";
    case ColorBy::Guide: return "guide";
    case ColorBy::Shape: return "shape";
    case ColorBy::Kind: return "kind";
    default: return {};
    }
}

}  // namespace render_detail

std::string_view color_by_name(ColorBy c)
{
    switch (c) {
    case ColorBy::None: return "none";
    case ColorBy::Strand: return "strand";
    case ColorBy::Guide: return "guide";
    case ColorBy::Shape: return "shape";
    case ColorBy::Kind: return "kind";
    case ColorBy::Id: return "id";
    case ColorBy::File: return "file";
    }
    return "none";
}

float3 categorical_color(int64_t value)
{
    // Golden-ratio hue steps (computed in double so large ids stay exact enough), alternating two
    // brightness levels so even hues that come close again differ in value.
    const double h = 0.08 + 0.6180339887498949 * static_cast<double>(value);
    const float hue = static_cast<float>(h - std::floor(h));
    const bool odd = (value & 1) != 0;
    return hsv(hue, odd ? 0.55f : 0.70f, odd ? 0.95f : 0.82f);
}

bool has_color_attribute(const CurveSet& curves, ColorBy color_by)
{
    const std::string_view name = attribute_of(color_by);
    return name.empty() || find_color_source(curves, name).valid();
}

}  // namespace groom
