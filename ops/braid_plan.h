// braid_plan: what braid() decides for each guide before any output is allocated (internal to
// ops/braid): its length, knots, woven fraction, the amplitudes A and B, the strand width and the
// number of samples along it.
#pragma once

#include "ops/braid.h"

#include <algorithm>
#include <cmath>
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

    /// The fraction of the guide over which fibers feed in: `feed_length` scene units, or three
    /// knots when it is 0, at most the whole guide.
    double feed_t(float feed_length) const
    {
        return std::min((feed_length > 0.0f ? double(feed_length) : 3.0 * knot_length()) / length, 1.0);
    }
};

/// How a braid's cross-section grows while its hair feeds in (BraidParams::feed_in): the share of its
/// fibers present at t is 1 - feed_in (1 - t / feed_t) up to feed_t, and the section's size follows
/// the square root of it, as a bundle's width follows its hair count. So a cornrow starts narrow at the
/// hairline and reaches its full width where the last fibers have joined (it started at full width,
/// like a cut rope: a trial's pictures). 1 without feed-in.
inline float feed_scale(float feed_in, double feed_t, float t)
{
    if (!(feed_in > 0.0f) || !(feed_t > 0.0)) return 1.0f;
    return std::sqrt(1.0f - feed_in * (1.0f - std::min(float(double(t) / feed_t), 1.0f)));
}

/// One plan per guide (samples 0: the guide is skipped, having fewer than 2 points or no length).
/// Unset width, height and strand width are chosen so strands touch without passing through each
/// other (see BraidParams); samples are enough per knot where the knots are densest.
std::vector<GuidePlan> plan_guides(const CurveSet& guides, const BraidParams& params, const KnotRemap& remap,
                                   const BraidWeave& weave);

}  // namespace groom
