// Container operations on whole curves: joining two sets and removing curves, every attribute
// carried. Ops that change which curves exist call these rather than rebuilding columns themselves.
#pragma once

#include "kernel/curve_set.h"

#include <span>

namespace groom {

/// One set holding the curves of `a` then those of `b`. Columns only one side has are filled with
/// -1 (integers) or 0 (floats, float3) on the other; a detail column both have keeps a's value,
/// except `closed`, kept only where both sides are closed loops.
/// Throws InvalidGeometry naming the column when it has different types in a and b.
CurveSet join(const CurveSet& a, const CurveSet& b);

/// A copy of `src` without the curves c where remove[c] is non-zero (#curves values); every point,
/// curve and detail column carried, order kept. `kept` (optional) receives the source index of
/// each curve left. Throws InvalidParam when `remove` has the wrong size.
CurveSet remove_curves(const CurveSet& src, std::span<const char> remove, std::vector<int64_t>* kept = nullptr);

/// A copy of `src` without each curve's last point where it repeats the first (at 3 or more points:
/// a closed loop as the readers give one), every column carried, and without the detail `closed`:
/// what a format that says "closed" itself (.usda periodic, .obj) writes.
CurveSet without_closing_points(const CurveSet& src);

/// The inverse: a copy of `src` with each curve's first point repeated at its end where it is not
/// already (at 2 or more points), every column carried, marked `closed`. What a format that cannot
/// say "closed" itself (.ply, .hair) writes for a loop, so the loop is read back one.
CurveSet with_closing_points(const CurveSet& src);

/// Whether every curve ends where it starts, at 3 or more points (true for no curves).
bool all_loops(const CurveSet& curves);

}  // namespace groom
