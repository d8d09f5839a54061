// surface_path: a curve that walks on the scalp from one point to another, the way a comb pulls hair
// or a parting is drawn: each step goes toward the target within the tangent plane, then back onto
// the surface. On a sphere this is the great circle (the chord's projection onto the tangent plane
// lies in the plane through the centre), so the path is the geodesic there; on a head it is a close
// and stable stand-in, with no mesh connectivity needed (the scalp is a field, fields/surface.h).
// Used by partings (`groom parting`), gathered hair (`groom gather`) and sections.
#pragma once

#include "fields/surface.h"

#include <vector>

namespace groom {

/// @brief Points on `scalp` from the surface point nearest `from` to the one nearest `to`, `step`
/// apart (the last step may be shorter), lifted `lift` along the normal (0 = on the surface).
/// @param step  scene units, > 0. When eight steps in a row bring it no closer to the target (a fold
///              that pulls each step back, behind an ear), the walk finishes along the chord to the
///              target with each point put back on the surface. It gives up after 4 |from - to| / step
///              + 16 steps and returns false; `out` then holds the path so far.
/// Both ends are included; a point on a fold where the tangent direction vanishes steps along any
/// tangent. Deterministic; thread-safe.
bool surface_path(const Surface& scalp, const float3& from, const float3& to, float step, float lift, std::vector<float3>& out);

/// The same through several waypoints in order (a parting drawn through chosen points). Returns false
/// when any leg fails.
bool surface_path_through(const Surface& scalp, const std::vector<float3>& waypoints, float step, float lift, std::vector<float3>& out);

}  // namespace groom
