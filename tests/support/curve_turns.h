// How sharply a curve turns: what a person sees as a kink or a hair folded back on itself.
#pragma once

#include "kernel/curve_set.h"

#include <vector>

namespace groom::test {

/// A curve's largest turn between consecutive segments that have a length, degrees (points gathered
/// at one place make segments of none: the turn is taken across them), and the point it is at.
struct Turn {
    double degrees = 0.0;
    float3 at;
};

/// Each curve's largest turn.
std::vector<Turn> largest_turns(const CurveSet& cs);

}  // namespace groom::test
