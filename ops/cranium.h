// cranium: the sphere a head's haired scalp lies on, fitted to it, so cornrow-guides can lay its
// rows on any head without the user measuring one.
#pragma once

#include "fields/surface.h"
#include "ops/hair_region.h"

namespace groom {

/// A sphere: the cranium's centre and radius, scene units.
struct Cranium {
    float3 center;
    float radius = 0.0f;
    int samples = 0;  ///< scalp points the fit used
};

/// @brief The least-squares sphere through the scalp inside `region`'s hairline.
/// The scalp is sampled where rays from far outside towards the hairline's centroid first enter
/// it, over the hemisphere around `up` (and 20 degrees below it), keeping the points inside the
/// hairline; the sphere is the algebraic least-squares fit |p - c|^2 = r^2 (linear in c and
/// r^2 - |c|^2), exact for points on a sphere.
/// Throws InvalidGeometry when the region has no hairline or fewer than 16 points are found.
Cranium fit_cranium(const Surface& scalp, const HairRegion& region, const float3& up);

}  // namespace groom
