// puff: Izzy's afro puffs (talk, Sec. 3.2 "Curls with Graphic Shapes"): a clean spherical silhouette.
// N rows x M columns of guide curves rooted within a radius on the scalp, each ending exactly on a
// perfect mathematical sphere, then curls rooted at random within the same radius that follow the
// guides (ops/generate.h) and are curled with the curl op.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"

#include <cstdint>

namespace groom {

struct PuffParams {
    /// The region on the scalp: roots lie within `radius` of c0, the point of the scalp closest to
    /// `center` (--center X,Y,Z, --radius r; scene units, radius > 0).
    float3 center{};
    float radius = 0.0f;
    /// The sphere the silhouette follows (--sphere-center X,Y,Z, --sphere-radius R; R > 0).
    float3 sphere_center{};
    float sphere_radius = 0.0f;
    /// Guides: rows x cols (--rows, --cols; each 1..256).
    int rows = 5;
    int cols = 5;
    /// Half-angle, degrees, of the cap of the sphere the guide tips cover, around the axis from c0 to
    /// the sphere centre: the part of the sphere facing away from the head (--cap-angle; (0, 180)).
    float cap_angle = 110.0f;
    /// Points per guide, evenly spaced in arc length (--guide-points; >= 4).
    int guide_points = 16;
    /// Length of each guide's end tangents (root: scalp normal, tip: sphere normal) as a fraction of
    /// its root-to-tip distance; larger bends the guides later (--bend; (0, 1]).
    float bend = 0.4f;
    int64_t first_id = 0;   ///< guide ids are first_id .. first_id + rows*cols - 1 (--first-id), >= 0

    /// Throws InvalidParam naming the option, the value and the valid range.
    void validate() const;
};

/// @brief The rows x cols sphere guides of a puff (Sec. 3.2).
///
/// The region's disc (radius `radius` in the tangent plane at c0) is divided into rows x cols
/// equal-area cells by Shirley and Chiu's concentric square-to-disc map; each cell centre, projected
/// onto the scalp, roots one guide. The same cell, mapped onto the sphere's cap by the equal-area
/// map 1 - cos(theta) = rho^2 (1 - cos(cap_angle)), gives its tip direction d, so tips cover the cap
/// evenly and keep the grid's neighbourhoods (no guide crosses another). Each guide is the cubic
/// Bezier root -> tip with root tangent the scalp normal and tip tangent d, resampled to
/// guide_points points evenly spaced in arc length; its tip is sphere_center + sphere_radius * d
/// (on the sphere to float rounding). Interior points inside the scalp are pushed out.
/// Writes point P, curve int64 `id`, int32 `kind` (0 = guide), int32 `guide` (its own index).
/// Throws InvalidParam (params; a tip that would lie inside the scalp), InvalidGeometry (the region
/// has no scalp within `radius` of c0 along the grid, or guides would cross).
CurveSet puff_guides(const Surface& scalp, const PuffParams& params, Progress* progress = nullptr);

/// Smallest distance between two different curves of `curves` (segment to segment), scene units;
/// +infinity with fewer than two curves. O(points^2): for checks and tests, not big grooms.
double min_curve_separation(const CurveSet& curves);

}  // namespace groom
