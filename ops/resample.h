// resample: re-space every curve's points evenly in arc length, by count or by segment length.
#pragma once

#include "kernel/curve_set.h"

namespace groom {

struct ResampleParams {
    int count = 0;              ///< points per curve (>= 2); 0 = use segment_length
    float segment_length = 0;   ///< target spacing, scene units (> 0) when count is 0
    void validate() const;      ///< throws InvalidParam: exactly one of count / segment_length
};

/// @brief Resample each curve to evenly spaced points; roots and tips are kept exactly.
/// Reads point P. Writes point P. Curve and detail attributes carry through; other point
/// attributes take the value of the nearest source point along the curve (by arc length).
CurveSet resample(const CurveSet& src, const ResampleParams& params);

}  // namespace groom
