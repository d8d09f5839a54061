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
/// The same into `out` (resized), for a loop over many curves that keeps its buffers.
void cumulative_lengths(std::span<const float3> pts, std::vector<double>& out);

/// Where arc length `s` falls along a polyline, found from its cumulative lengths.
struct ArcSpot {
    size_t lo = 0, hi = 0;  ///< the segment from point lo to point hi = lo + 1 (both 0 for one point)
    double t = 0.0;         ///< fraction along it, [0, 1]; 0 on a zero-length segment
    size_t nearest = 0;     ///< lo or hi, whichever is nearer s in arc length; hi on a tie
};

/// The arc-length lookup every "where along the curve" question uses. `cumulative` from
/// cumulative_lengths (not empty); s is clamped to [0, length]. The segment is the last that starts
/// at or before s, so s at a point's own arc length gives that point as lo with t = 0 (and the tip,
/// hi of the last segment with t = 1); of points at the same arc length (a zero-length segment) the
/// last is the nearest.
ArcSpot locate_at_length(std::span<const double> cumulative, double s);
/// The same for a caller walking along the curve: `cursor` (start it at 0) remembers where the last
/// lookup ended, so lengths that only grow cost a step or two each instead of a binary search (the
/// answer is the same; a length smaller than the last is searched for).
ArcSpot locate_at_length(std::span<const double> cumulative, double s, size_t& cursor);

/// Position at arc length `s` (clamped to [0, length]) given the cumulative lengths of `pts`.
float3 point_at_length(std::span<const float3> pts, std::span<const double> cumulative, double s);

/// `count` points (>= 2) equally spaced in arc length from root to tip; the root and tip are kept
/// exactly. A single-point or zero-length input yields `count` copies of its first point.
std::vector<float3> resample_by_count(std::span<const float3> pts, int count);
/// The same into `out` (resized); `cumulative` is scratch.
void resample_by_count(std::span<const float3> pts, int count, std::vector<float3>& out, std::vector<double>& cumulative);

/// Unit tangents per point: central differences inside, one-sided at the ends. Zero-length
/// segments take the neighbouring tangent; a curve with no extent gets +Y (the up axis).
std::vector<float3> polyline_tangents(std::span<const float3> pts);
/// The same into `out` (resized).
void polyline_tangents(std::span<const float3> pts, std::vector<float3>& out);

/// Squared distance between segments [p1,q1] and [p2,q2] (Ericson, Real-Time Collision Detection
/// 5.1.9), in double so near-touching curves are measured reliably.
double segment_distance_sq(const float3& p1, const float3& q1, const float3& p2, const float3& q2);

}  // namespace groom
