// drape_runs: where keep_outside folded a curve back on itself, the points it moved are laid again
// over the obstacle as a whole.
//
// Why. keep_outside moves each point that is inside to its own closest scalp point. Where a curve
// runs through a thin part of the scalp (a blend of guides that pass either side of an ear runs
// through the ear flap; a fringe runs down into an open eye socket), the closest points of a run of
// inside points are all on the same rim, or on alternating sides of the flap, and the curve comes
// out folded: on Sintel's head, 121 of 15,000 generated hairs turned by more than 90 degrees between
// consecutive segments (up to 177), where no guide turns by more than 53.
//
// What. For each run of moved points next to a turn of more than 90 degrees that the curve did not
// have before the move, each point of the run, where it was before the move, is lifted along one
// direction `d` to a clear place (the first found stepping out along d, at least 1/64 of the run's
// reach a step, so a wall thinner than that may be stepped over; every place taken is clear by the
// rule). Four directions are tried, each less its part along the chord between the clear points
// either end of the run: the mean of the moves keep_outside made, the mean of the scalp's normals
// at those ends, and both reversed (the moves go to whichever side of a flap is nearer; beside an
// open rim the normal can point into the head). The first that leaves no turn over 90 degrees is
// kept, else the one that turns least, and only where it turns less than keep_outside's result.
// Points lifted along one direction keep their order and spacing across it, so the run drapes
// over the ear's outer side instead of gathering at its rim.
#pragma once

#include "fields/keep_outside.h"

#include <span>

namespace groom {

/// What drape_runs changed.
struct DrapeCount {
    int64_t runs = 0;    ///< runs laid again
    int64_t curves = 0;  ///< curves with at least one
};

/// @brief Lays again, along one direction each, the runs of points of `curves` that keep_outside
/// moved (`moved`: its record, sorted by index) where the move folded the curve back (a turn of more
/// than 90 degrees at a point where the curve before the move turned by 90 or less). `rule` is the
/// one keep_outside applied. Parallel over the curves; the result does not depend on the thread
/// count. Writes point P only.
DrapeCount drape_runs(CurveSet& curves, std::span<const MovedPoint> moved, const Surface& scalp, const KeepOutside& rule);

}  // namespace groom
