// Reading and writing curve files, chosen by extension:
//   .usda  USD BasisCurves (read: linear, cubic catmullRom/bspline evaluated to polylines; write: linear)
//   .obj   `l` polylines (+ `v`)
//   .ply   ASCII or binary; vertex element with any properties plus an `edge` element
//   .hair  Cem Yuksel's binary hair format
// "-" as a path means stdin/stdout in .usda. Writes are atomic (see atomic_file.h).
#pragma once

#include "kernel/curve_set.h"

#include <string>

namespace groom {

/// Curve formats by extension, lower-case, without dot.
bool is_curve_path(const std::string& path);

struct CurveReadOptions {
    /// Points per segment when evaluating cubic USD curves into polylines.
    int cubic_samples_per_segment = 8;
};

/// Reads a curve file. Throws ParseError (file, line or byte offset, expected vs found) or IoError.
/// The result is validated (CurveSet::validate).
CurveSet read_curves(const std::string& path, const CurveReadOptions& options = {});

enum class PlyEncoding { Binary, Ascii };

struct CurveWriteOptions {
    PlyEncoding ply_encoding = PlyEncoding::Binary;
};

/// Writes `curves` atomically to `path` (format by extension). Throws IoError / InvalidParam.
void write_curves(const CurveSet& curves, const std::string& path, const CurveWriteOptions& options = {});

}  // namespace groom
