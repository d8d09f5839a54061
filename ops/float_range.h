// FloatRange: an op parameter drawn per item from a range the user gives as "lo,hi" (a single
// value is lo = hi: no draw).
#pragma once

namespace groom {

/// A closed range [lo, hi] a value is drawn from uniformly.
struct FloatRange {
    float lo = 0.0f, hi = 0.0f;
};

}  // namespace groom
