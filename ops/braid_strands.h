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
};

/// Builds the N strands of one guide into `dst` (curves first..first+N-1), their sections into `sec`,
/// and records, for each output point, the guide point nearest in arc length.
LiftStats braid_guide(const BraidContext& ctx, const GuidePlan& plan, std::span<const float3> guide, int64_t guide_point0,
                      CurveSet& dst, int64_t first_curve, StrandSections& sec, std::span<int64_t> src_point);

}  // namespace groom
