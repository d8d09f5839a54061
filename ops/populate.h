// populate: fill a disc around each input curve with M hair fibers that run along it, so a braid
// strand or a guide becomes a groom rather than a centreline. Used by `groom braid --fibers`, by the
// standalone `groom populate`, and by generate/puff. Each fiber keeps a fixed offset in the curve's
// rotation-minimising frame, drawn area-uniformly in the disc from Rng(seed, curve id, fiber stream),
// so the result depends only on the seed and the curve ids, never on thread count or curve order.
#pragma once

#include "kernel/curve_set.h"
#include "ops/hair_widths.h"
#include "kernel/progress.h"

#include <cstdint>
#include <string>

namespace groom {

struct PopulateParams {
    int count = 16;        ///< M, fibers per input curve; 1 .. kMaxFibersPerCurve
    /// Disc radius, scene units; >= 0. 0 = half of each point's `width` attribute (the curve is
    /// filled within its own thickness; the input must then have point `width`).
    float radius = 0.0f;
    /// Fiber width written on output points, scene units; >= 0. 0 = automatic: 2 r / sqrt(M) at a
    /// point of disc radius r, so the M fibers about cover the disc's area.
    float width = 0.0f;
    /// Given (--root-width, --tip-width): each fiber's width tapers linearly in its own arc length
    /// instead (an unset end takes the human-hair default, ops/hair_widths.h); exclusive with `width`.
    HairWidths widths;
    uint64_t seed = 0;
    /// Name of a point float attribute of the input that scales the disc radius (and the automatic
    /// width) per point, e.g. a braid's amplitude taper. Empty = no scaling.
    std::string radius_scale;

    static constexpr int kMaxFibersPerCurve = 1'000'000;

    /// Throws InvalidParam naming the option (--count, --radius, --width), the value and the range.
    void validate() const;
};

/// @brief M fibers per input curve, in a disc of params.radius around it.
///
/// Reads point P, curve id (else the index), point width (radius = 0), point params.radius_scale.
/// Writes, for input curve c, curves c*M .. c*M+M-1 with c's point count:
///   point P = C(j) + r(j) (u n(j) + v b(j)), (u, v) uniform in the unit disc per fiber, n, b the
///   rotation-minimising frame of curve c; point width (see PopulateParams::width, ::widths);
///   curve fiber (int32, 0..M-1); curve id (int64, source id * M + fiber);
///   every other curve, point and detail attribute of curve c.
/// @throws InvalidParam (bad params, radius 0 without a point width attribute, radius_scale absent),
///         LimitExceeded (more than kMaxPopulatePoints output points, or ids that would overflow int64).
CurveSet populate(const CurveSet& src, const PopulateParams& params, Progress* progress = nullptr);

/// Largest output populate() makes before refusing (points; about 16 bytes each).
inline constexpr int64_t kMaxPopulatePoints = 400'000'000;

}  // namespace groom
