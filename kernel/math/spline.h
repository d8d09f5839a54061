// Cubic spline evaluation: uniform Catmull-Rom (interpolating) and uniform cubic B-spline
// (approximating), as USD BasisCurves define them, plus a 1-D spline for artist curves
// ("taper" values over t in [0,1]).
#pragma once

#include "kernel/math/vec.h"

#include <span>
#include <vector>

namespace groom {

/// Uniform Catmull-Rom segment between p1 (t=0) and p2 (t=1).
float3 catmull_rom(const float3& p0, const float3& p1, const float3& p2, const float3& p3, float t);
float catmull_rom(float p0, float p1, float p2, float p3, float t);

/// Uniform cubic B-spline segment over control points p0..p3, t in [0,1].
float3 bspline(const float3& p0, const float3& p1, const float3& p2, const float3& p3, float t);

enum class CubicBasis { CatmullRom, BSpline };

/// Evaluates a non-periodic cubic curve with vstep 1 (USD catmullRom/bspline) into a polyline with
/// `samples_per_segment` (>= 1) points per segment. `pinned` adds phantom end points so the curve
/// reaches the first and last control points (USD wrap = "pinned"). A curve with fewer than 4
/// control points (2 or 3 when pinned) yields the control points unchanged.
std::vector<float3> evaluate_cubic(std::span<const float3> cvs, CubicBasis basis, bool pinned, int samples_per_segment);
/// The same into `out` (resized), for a loop over many curves that keeps its buffers.
void evaluate_cubic(std::span<const float3> cvs, CubicBasis basis, bool pinned, int samples_per_segment, std::vector<float3>& out);

/// A smooth 1-D function through `values` placed uniformly over t in [0,1] (Catmull-Rom with
/// clamped ends), evaluated at t (clamped). One value gives a constant; none gives 1.
float sample_uniform_spline(std::span<const float> values, float t);

}  // namespace groom
