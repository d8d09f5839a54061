// transform: place curves in another scene: translate, rotate, scale, change the up axis or the
// length unit, with the attributes that hold positions, directions and lengths following.
#pragma once

#include "kernel/curve_set.h"

#include <string>

namespace groom {

struct TransformParams {
    float3 translate{0, 0, 0};  ///< scene units (of the output), applied last
    float3 rotate{0, 0, 0};     ///< degrees about X, then Y, then Z (USD's rotateXYZ), finite
    float3 scale{1, 1, 1};      ///< per axis, finite and non-zero (negative mirrors)
    /// Output up axis "y" or "z" ("" = unchanged). Y-up to Z-up turns (x, y, z) into (x, -z, y), the
    /// reverse (x, z, -y): a rotation, so handedness is kept. The input's axis is the detail string
    /// `up_axis` when it has one, else the other axis; the output carries the new one.
    std::string up_axis;
    /// Output length unit "mm", "cm", "m" or "in" ("" = unchanged); the input's is `from_units`, else
    /// the detail string `units`, else an error. The output carries `units`.
    std::string units;
    std::string from_units;
    void validate() const;  ///< throws InvalidParam naming the field, what was expected and what was found
};

/// @brief p' = T + Rz Ry Rx S (k A p): A the up-axis change, k the unit factor, S the scale, R the
/// rotation, T the translation. Reads and writes point P. Attributes follow by name (Houdini's
/// conventions): float3 `rest`, `puff_base`, `puff_sphere_center` as positions (the full
/// transform); `N`, `normal` and names ending `_normal` as normals (inverse transpose, length kept);
/// `tangent`, `dir`, `direction`, `up` as directions (the linear part, length kept); `v`, `vel`,
/// `velocity` as vectors (the linear part). Lengths (float `width`, `puff_radius`,
/// `puff_sphere_radius`, `scalp_length`) scale by k * cbrt(|sx sy sz|), the uniform part of the
/// scale (exact for a uniform one), `area` by its square. Every other attribute is carried
/// unchanged; topology unchanged. Throws InvalidParam (params, or `units` without a known input unit).
CurveSet transform(const CurveSet& src, const TransformParams& params);

}  // namespace groom
