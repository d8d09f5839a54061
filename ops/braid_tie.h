// braid_tie: the hair tie of a braid (internal to ops/braid): per braided guide, a band of
// params.tie_turns wraps around the braid where it is pinched at params.tie, appended after the hair
// as its own curve (kind 1).
#pragma once

#include "kernel/curve_set.h"
#include "ops/braid.h"
#include "ops/braid_fibers.h"
#include "ops/braid_plan.h"

#include <cstdint>
#include <span>

namespace groom {

/// `hair` followed by one tie curve per guide g with first_strand[g] >= 0, in guide order. Keeps the
/// hair's point P and width and curve id, kind, strand and fiber (with fibers), and carries its other
/// attributes; a tie gets width = the band's, id = one past the largest hair id plus its index among
/// the ties, kind 1, strand and fiber -1, the other attributes from its guide's first hair curve and
/// point. `strands` are the strand centrelines (the hair itself without fibers) and `sec` their
/// sections. Throws LimitExceeded when the tie ids would overflow.
CurveSet append_ties(const CurveSet& hair, const CurveSet& strands, const StrandSections& sec, const BraidParams& params,
                     std::span<const GuidePlan> plans, std::span<const int64_t> first_strand);

}  // namespace groom
