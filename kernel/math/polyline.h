// Arc length and arc-length parameterisation of polylines (one curve's points, root to tip).
#pragma once

#include "kernel/math/vec.h"

#include <span>
#include <vector>

namespace groom {

/// Total length of the polyline, scene units.
float polyline_length(std::span<const float3> pts);

/// Cumulative arc length at each point: out[0] = 0, out.back() = total length. Computed in double
/// so long curves do not drift.
std::vector<double> cumulative_lengths(std::span<const float3> pts);

/// Position at arc length `s` (clamped to [0, length]) given the cumulative lengths of `pts`.
float3 point_at_length(std::span<const float3> pts, std::span<const double> cumulative, double s);

/// `count` points (>= 2) equally spaced in arc length from root to tip; the root and tip are kept
/// exactly. A single-point or zero-length input yields `count` copies of its first point.
std::vector<float3> resample_by_count(std::span<const float3> pts, int count);

/// Unit tangents per point: central differences inside, one-sided at the ends. Zero-length
/// segments take the neighbouring tangent; a curve with no extent gets +Y (the up axis).
std::vector<float3> polyline_tangents(std::span<const float3> pts);

}  // namespace groom
