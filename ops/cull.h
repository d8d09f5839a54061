// cull: keep hair out of the head. Points closer than a clearance to the inside of the scalp are
// moved out to it (fields/keep_outside.h), or each offending curve is cut at its first entry, or deleted.
// Roots are exempt: they sit on the scalp by design (place them with `project`).
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"

namespace groom {

enum class CullMode { Push, Trim, Delete };

struct CullParams {
    CullMode mode = CullMode::Push;
    float clearance = 0.0f;  ///< minimum signed distance a point may have, scene units; >= 0
    void validate() const;   ///< throws InvalidParam for a negative or non-finite clearance
};

struct CullStats {
    int64_t curves_affected = 0;  ///< curves with at least one non-root point below the clearance
    int64_t points_pushed = 0;    ///< push: points moved
    int64_t curves_trimmed = 0;   ///< trim: curves cut short
    int64_t curves_deleted = 0;   ///< delete (and trim, when nothing but the root was outside)
    int64_t points_removed = 0;   ///< trim + delete: points dropped
};

/// @brief Enforce distance(p) >= clearance for every non-root point.
/// Reads point P. Writes point P. Push: keep_outside on the curves (fields/keep_outside.h: a point
/// closer than the clearance goes to closest_point(p) + n(p) * clearance, re-checked up to 16
/// times, roots stay), then a run of them the moves folded back laid again over the scalp as a
/// whole (fields/drape_runs.h); topology unchanged. Trim: a
/// curve ends at its first segment entering the clearance zone, the new tip placed where the
/// distance, linear along the segment, equals the clearance (point attributes of the new tip come
/// from the segment's outer point); a curve left with no length is deleted. Delete: curves with any
/// offending point are removed. Curve, detail and other point attributes carry through (curve ids
/// stay stable). Deterministic for any thread count (count -> scan -> fill).
CurveSet cull(const CurveSet& src, const Surface& scalp, const CullParams& params, CullStats* stats = nullptr);

}  // namespace groom
