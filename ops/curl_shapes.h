// The curl cross-section dictionary (talk, Sec. 3.1, equation 1): each entry is a closed curve in
// the plane normal to the hair's centreline, traced once as t goes over one curl cycle [0, 1), at
// unit scale (the curl op multiplies by the amplitude): circle radius 1, ellipse semi-axes 1 and
// aspect, polygon circumradius 1, Lame semi-axes 1, rose petals of length 1. Numbered as in the talk: 0 Lame curve, 1 N-sided polygon, 2 ellipse, 3 circle,
// 4 polar rose. Adding a shape is one function and one entry in the table in curl_shapes.cpp.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace groom {

/// A point in the cross-section plane: x along the frame normal, y along the binormal.
struct ShapePoint {
    float x = 0.0f, y = 0.0f;
};

/// The parameters of the parametric shapes. Each is validated by validate().
struct ShapeParams {
    float lame_exponent = 2.5f;   ///< n of |x|^n + |y|^n = 1; > 0 (2 = circle, < 1 star, > 2 squircle)
    int polygon_sides = 5;        ///< N of the regular polygon; 3..64
    float ellipse_aspect = 0.5f;  ///< minor / major semi-axis; (0, 1]
    int rose_petals = 3;          ///< k of r = cos(k theta); 1..32 (odd k: k petals, even k: 2k)
    /// Throws InvalidParam naming the option (`--lame-exponent`, ...), the value and the range.
    void validate() const;
};

/// Dictionary indices (stable: they are written to the `shape` point attribute).
enum CurlShape : int { kLame = 0, kPolygon = 1, kEllipse = 2, kCircle = 3, kRose = 4 };

/// Number of shapes in the dictionary.
int curl_shape_count();

/// The shape's name as the command line spells it: "lame", "polygon", "ellipse", "circle", "rose"
/// (cli/curl_options.h parses names and numbers).
std::string_view curl_shape_name(int shape);

/// "0 lame, 1 polygon, ..." for messages and help text.
std::string curl_shape_list();

/// What the shapes need computed once for a run's parameters: the polygon's corners.
struct ShapeTable {
    ShapeParams params;
    /// polygon_sides + 2 corners, corner j at angle 2 pi (j - 1/2) / N (the last two repeat the first
    /// two, so an edge is always corners j and j + 1).
    std::vector<ShapePoint> corners;

    ShapeTable() : ShapeTable(ShapeParams{}) {}
    explicit ShapeTable(const ShapeParams& params);
};

/// Points of `shape` at cycle parameters t[0..n) into x[i], y[i]: curl_shape_point's points, many at
/// once (the curl op asks for millions: sines and cosines four at a time, kernel/math/vector_math.h).
/// `shape` must be in [0, curl_shape_count()).
void curl_shape_points(int shape, const ShapeTable& table, const float* t, size_t n, float* x, float* y);

/// Point of `shape` at cycle parameter t (any real; the shape repeats with period 1), unit scale.
/// Every shape starts (t = 0) at a point where it is smooth, so consecutive cycles can be blended
/// around t = 0 without creating a corner (the polygon starts mid-edge, the Lame curve on its
/// diagonal, the rose on a petal tip). Points move counter-clockwise (x towards y).
/// `shape` must be in [0, curl_shape_count()). One point of curl_shape_points (the same bits).
ShapePoint curl_shape_point(int shape, const ShapeParams& params, float t);

}  // namespace groom
