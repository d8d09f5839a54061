// --scalp-xform: the rigid pose of the scalp on each frame, read from a text file, and the rigid
// transform of a curve set between the scalp's rest frame and a frame's pose.
#pragma once

#include "kernel/curve_set.h"

#include <array>
#include <map>
#include <string>

namespace groom::cli {

/// x -> R x + t, R a rotation. Kept in double so that a pose and its inverse round to float once.
struct RigidXform {
    std::array<std::array<double, 3>, 3> r{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    std::array<double, 3> t{0, 0, 0};

    /// From translate (tx, ty, tz) and rotate (rx, ry, rz degrees: about X, then Y, then Z).
    static RigidXform from_trs(const double t[3], const double degrees[3]);
};

/// The poses of a --scalp-xform file by frame. One frame per line: the frame number, then either
/// 6 numbers (tx ty tz rx ry rz, degrees, rotation about X then Y then Z, then the translation),
/// 12 (a 3x4 matrix [R|t], row by row) or 16 (a 4x4 matrix, row by row, last row 0 0 0 1); blank
/// lines and `#` comments are skipped. R must be a rotation (orthonormal to 1e-5, determinant +1):
/// a head that changes shape is a frame pattern of meshes, not a transform. Throws ParseError naming
/// the file and line, IoError when it cannot be read.
std::map<long, RigidXform> read_scalp_xforms(const std::string& path);

/// Moves `curves` by `xform` (inverse = false: rest frame -> pose; true: pose -> rest frame):
/// positions (P, and the detail points puff_base, puff_sphere_center a puff carries) as points,
/// a float3 `N` on any domain as a direction; other columns (colours, widths, ids) are left alone.
void transform_curves(CurveSet& curves, const RigidXform& xform, bool inverse);

}  // namespace groom::cli
