// keep_outside: the one rule every op uses to keep hair out of the scalp.
//
// The rule. A point p is clear of the scalp when
//     scalp.distance(p) >= need,        need = clearance + extra
// where `extra` is the point's own addition (half a hair's width, so that the hair's surface and not
// its centreline keeps the clearance; a height that rises along a partition segment; 0 unless the
// caller gives one). A point that is not clear is put need + margin out along the outward normal
// from its closest scalp point:
//     p <- scalp.closest_point(p) + scalp.normal(p) * (need + margin)
// For an exact surface that is the least move that clears p (plus the margin), and the same as a step
// along the normal by the missing distance. With max_steps > 1 the field is asked again, and a point
// it still finds closer than `need` is moved again with the margin doubled: where a level set
// disagrees with itself by more than the margin, a larger one settles it. A clear point is never
// moved, so applying the rule twice moves nothing more (for a field that agrees with itself).
//
// The forms below apply it; each documents only what it adds:
//   keep_outside(p, ...)       one point, optionally pulled back toward an anchor first (curl; the
//                              cornrow tails and partition segments, point by point as they are built);
//   keep_outside(points, ...)  every point of a span on its own (braid's hair, puff's guide interiors);
//   keep_outside(curves, ...)  every point but each curve's root, then folded runs draped over the
//                              scalp (fields/drape_runs.h) (generate, puff's hairs, cull);
//   lift_outside(group, ...)   a group that must keep its shape (a braid's cross-section) moves as one
//                              along one direction, and may rest on the scalp; never through it.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace groom {

/// The rule's numbers (see the file comment).
struct KeepOutside {
    /// Least distance from the scalp, scene units; >= 0.
    float clearance = 0.0f;
    /// Slack added to where a moved point is put, scene units; >= 0. 0 puts it at exactly `need`
    /// (on the scalp for clearance 0), where rounding may leave it either side; a few ulps of the
    /// scene's size keep it strictly clear.
    float margin = 0.0f;
    /// Moves per point, >= 1: 1 moves once and trusts the move; more re-check and move again with a
    /// doubled margin (lift_outside: iterations of its fixed point).
    int max_steps = 1;
};

/// The margin for a scene of these bounds: a millionth of its diagonal, a few float ulps of its
/// coordinates, so a moved point lands strictly clear (0 for empty bounds). generate and cull use it.
inline float scene_margin(const Bounds3& box)
{
    return box.empty() ? 0.0f : 1e-6f * std::max(length(box.hi - box.lo), 1e-30f);
}

/// @brief The rule on one point.
/// With `anchor` (a point the caller expects to be clear, e.g. the curl's centreline under a curled
/// point): a point that is not clear is first pulled back along the segment toward the anchor to a
/// place that is clear and within rule.margin / 16 of not being so along the segment (2^-24 of the
/// segment for a zero margin), which keeps the direction of its offset. Where the segment crosses
/// the scalp more than once any of those crossings may be the one found. Only when the
/// anchor itself is not clear does the normal move apply.
/// @param extra  added to rule.clearance for this point, scene units
/// @return true when p moved
bool keep_outside(float3& p, const Surface& scalp, const KeepOutside& rule, float extra = 0.0f, const float3* anchor = nullptr);

/// @brief The rule on every point of `points`, each on its own, in parallel (the result does not
/// depend on the thread count).
/// @param widths  per point (#points, or empty): hair widths, scene units; half of each is the
///                point's extra, so the hair's surface keeps the clearance, not its centreline
/// @param known_clear  per point (#points, or empty): 1 where the caller has shown the point is at
///                     need + margin or more (a signed distance changes no faster than the point
///                     moves, so a point near one whose distance is known has a bound); not queried
/// @return the number of points moved
int64_t keep_outside(std::span<float3> points, const Surface& scalp, const KeepOutside& rule, std::span<const float> widths = {},
                     std::span<const uint8_t> known_clear = {}, Progress* progress = nullptr);

/// What keep_outside(curves) moved.
struct KeepOutsideCount {
    int64_t points = 0;  ///< points moved
    int64_t curves = 0;  ///< curves with at least one point moved
    int64_t draped = 0;  ///< runs of moved points laid again as a whole (fields/drape_runs.h)
};

/// A point keep_outside(curves) moved: its index among the curves' points, and where it was.
struct MovedPoint {
    int64_t index = 0;
    float3 before;
};

/// @brief The rule on every point of every curve but its root: a root is where the hair grows, on
/// the scalp, and stays there (a root inside the scalp stays inside). Walking from the root, a point
/// whose predecessor's distance less the segment between them is above `need` is clear without a
/// query (far from a level set's narrow band each query is an exact mesh search); a moved point
/// counts as being at `need`. That bound is used only where scalp.lipschitz(). A run of moved
/// points that the moves folded back (a thin part of the scalp: an ear flap) is then laid again
/// over the scalp as a whole (drape_runs, fields/drape_runs.h). Writes point P only. Parallel over
/// the curves.
/// @param moved  optional: every point moved and where it was before the move, by index
KeepOutsideCount keep_outside(CurveSet& curves, const Surface& scalp, const KeepOutside& rule, std::vector<MovedPoint>* moved = nullptr);

/// What lift_outside found besides the lift.
struct LiftOutcome {
    /// The way along `direction` was blocked before the group was clear: going on would have taken
    /// one of its points into the scalp, or the group closer to it (a gap narrower than the group, a
    /// thin part such as an ear or a collar in the way; further on, the far side of the head). The
    /// lift is then the clearest place the iteration found before that.
    bool blocked = false;
    /// At the lift returned, the least distance of a point of the group from the scalp less
    /// need + margin, scene units: negative is how far it is still short (0 for a group that was clear
    /// and did not move; otherwise within the iteration's rounding of 0 where it converged).
    float worst = 0.0f;
};

/// @brief The rule for a group that moves as one: the least lift along `direction` (unit) that puts
/// every point of `group` at need + margin or more (need = rule.clearance + extra), found by a fixed
/// point iteration (at most rule.max_steps steps, until a step changes the lift by no more than the
/// margin): off-centre points move by less than the lift where the scalp curves. Without `rest` the
/// lift is >= 0 (a clear group is not moved); with it a group floating above is also lowered until
/// its lowest point rests at need + margin (cornrows lie on the head). Does not move the points.
/// The group never passes through the scalp on its way out: no step out takes a point that was
/// outside inside, or leaves the worst point shorter than before; where the way is blocked before the
/// group is clear the lift stops at the least short place found (outcome->blocked).
/// @param outcome  optional: whether the way was blocked and how far the group is still short
/// @return the lift, scene units along `direction` (negative: lowered)
double lift_outside(std::span<const float3> group, const float3& direction, const Surface& scalp, const KeepOutside& rule,
                    float extra, bool rest, LiftOutcome* outcome = nullptr);

}  // namespace groom
