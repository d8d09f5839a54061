// braid_strands: the N strand centrelines of one guide (internal to ops/braid). The guide is sampled
// evenly in arc length; frames carry the weave's cross-section along it (talk, Sec. 2.1); past t_b
// the strands part into the loose end's row; then each cross-section is lifted off the scalp whole
// (lift_outside), so the braid keeps its shape.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "ops/braid.h"
#include "ops/braid_fibers.h"
#include "ops/braid_plan.h"

#include <cstdint>
#include <span>

namespace groom {

/// Everything one guide's braid needs from the op's parameters.
struct BraidContext {
    const BraidParams& params;
    const KnotRemap& remap;
    const BraidWeave& weave;
    const Surface* scalp;
    float margin;  // float slack added to every clearance so rounding never lands a point inside
};

/// Section lift statistics for one guide.
struct LiftStats {
    int64_t lifted = 0, lowered = 0;
    float max_lift = 0.0f, max_lower = 0.0f;
    int64_t blocked = 0;    ///< sections with no clear place along the scalp normal short of passing through the scalp
    float short_by = 0.0f;  ///< the most a blocked section still lacked of its clearance, scene units
    float3 blocked_at;      ///< the guide point of the first blocked section
    int64_t deep = 0;       ///< sections whose guide point is inside the scalp deeper than the braid is wide (left inside)
    float depth = 0.0f;     ///< how far the guide runs inside the scalp at the deepest of those, scene units
    float3 deepest;         ///< that guide point
};

/// Builds the N strands of one guide into `dst` (curves first..first+N-1), their sections into `sec`,
/// and records, for each output point, the guide point nearest in arc length, and sets `left_inside`
/// (per strand point, 0 otherwise) to 1 where the guide runs too deep in the scalp for its section to
/// be lifted out (its hair is then not pushed out either).
LiftStats braid_guide(const BraidContext& ctx, const GuidePlan& plan, std::span<const float3> guide, int64_t guide_point0,
                      CurveSet& dst, int64_t first_curve, StrandSections& sec, std::span<int64_t> src_point,
                      std::span<uint8_t> left_inside);

}  // namespace groom
