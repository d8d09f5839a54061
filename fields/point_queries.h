// query_points: the scalp's distance, normal and closest point at many points at once (`groom probe`,
// the Python module's Scalp queries), as ScalpField::query answers each one, but in the order of the
// cells the points fall in and, where they crowd, from the per-cell candidate faces of
// ScalpField::query_dense instead of a search of the mesh's tree for each.
#pragma once

#include "fields/scalp_field.h"

#include <cstddef>
#include <functional>
#include <span>

namespace groom {

/// Calls out(i, distance, normal, closest) once for every point i, with what scalp.query(points[i])
/// gives (to float rounding where two faces tie for closest: a shared edge or vertex). In parallel
/// (`out` is called from several threads at once, each i once); every answer is a function of its
/// point alone, so what `out` receives is the same for any thread count and any order of the points.
void query_points(const ScalpField& scalp, std::span<const float3> points,
                  const std::function<void(size_t i, float distance, const float3& normal, const float3& closest)>& out);

}  // namespace groom
