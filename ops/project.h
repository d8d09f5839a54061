// project: put curves onto the scalp. `root` moves each curve rigidly so its root lies on the
// surface (plus an offset along the normal); `all` moves every point onto the surface (cornrow
// guides that must lie on the scalp).
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"

namespace groom {

enum class ProjectMode { Root, All };

struct ProjectParams {
    ProjectMode mode = ProjectMode::Root;
    float offset = 0.0f;   ///< distance along the outward normal to leave above the surface, scene units (any finite value)
    void validate() const; ///< throws InvalidParam for a non-finite offset
};

struct ProjectStats {
    int64_t curves = 0, points_moved = 0;
    double max_move = 0.0;  ///< largest distance a point moved, scene units
};

/// @brief Project curves onto `scalp` (closest point + offset * normal).
/// Reads point P. Writes point P; every other attribute carries through unchanged (topology unchanged).
/// Mode Root: each curve translated by (closest(root) + offset * n - root). Mode All: every point
/// replaced by closest(p) + offset * n(p). Deterministic and thread-count independent.
CurveSet project(const CurveSet& src, const Surface& scalp, const ProjectParams& params, ProjectStats* stats = nullptr);

}  // namespace groom
