// braid_plan: what braid() decides for each guide before any output is allocated (internal to
// ops/braid): its length, knots, woven fraction, the amplitudes A and B, the strand width and the
// number of samples along it.
#pragma once

#include "ops/braid.h"

#include <cstdint>
#include <vector>

namespace groom {

/// Per-guide quantities resolved before any output is allocated.
struct GuidePlan {
    double length = 0.0;
    double frequency = 0.0;
    double woven = 1.0;  // t_b, the woven fraction of the guide
    int64_t samples = 0;  // 0 = skipped
    float A = 0.0f, B = 0.0f;
    float strand_width = 0.0f;  // before the amplitude scale s(t)

    /// Arc length of one knot of the woven part (the whole length when nothing is woven).
    double knot_length() const
    {
        const double woven_len = woven * length;
        return frequency > 0.0 && woven_len > 0.0 ? woven_len / frequency : length;
    }
};

/// One plan per guide (samples 0: the guide is skipped, having fewer than 2 points or no length).
/// Unset width, height and strand width are chosen so strands touch without passing through each
/// other (see BraidParams); samples are enough per knot where the knots are densest.
std::vector<GuidePlan> plan_guides(const CurveSet& guides, const BraidParams& params, const KnotRemap& remap,
                                   const BraidWeave& weave);

}  // namespace groom
