// Point lists in and number tables out, for commands that answer per point (`groom probe`): `x y z`
// text or a NumPy `.npy` array in; CSV or `.npy` out. Text is parsed and formatted in parallel
// chunks with std::from_chars / std::to_chars (2M points: iostream and printf were 60% of probe's
// time); the bytes written never depend on the thread count.
#pragma once

#include "kernel/math/vec.h"

#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace groom {

/// True for a `.npy` path (case-insensitive extension).
bool is_npy_path(const std::string& path);

/// `x y z` per line; commas, tabs and carriage returns count as spaces; blank lines and lines
/// whose first non-space character is '#' are skipped. Every other line holds exactly three finite
/// numbers. `path` "-" reads standard input. Throws IoError (cannot read) or ParseError
/// "path:LINE: expected three finite numbers 'x y z', got 'LINE TEXT'" (the first bad line).
std::vector<float3> read_points_text(const std::string& path);
/// The same from text already in memory; `name` is used in messages.
std::vector<float3> parse_points_text(std::string_view text, const std::string& name);

/// A NumPy array file (format 1.0, 2.0 or 3.0) of shape (N, 3), C order, dtype little-endian float32
/// ('<f4') or float64 ('<f8', rounded to float). Anything else (another dtype, big-endian, Fortran
/// order, another shape, a truncated or overlong file, a non-finite value) is a ParseError naming
/// the file, what was expected and what was found. Throws IoError when it cannot be read.
std::vector<float3> read_points_npy(const std::string& path);
std::vector<float3> parse_points_npy(std::string_view bytes, const std::string& name);

/// read_points_npy for a `.npy` path, else read_points_text.
std::vector<float3> read_points(const std::string& path);

/// `header` (one line, without the newline), then values.size() / columns rows of `columns`
/// comma-separated numbers, each the shortest text that parses back to exactly that float. Rows
/// are formatted in parallel, fixed-size chunks written in order. Throws InvalidParam when the
/// size is not a multiple of `columns`.
void write_csv_table(std::ostream& out, std::string_view header, std::span<const float> values, int columns);
/// A NumPy `.npy` (format 1.0) array of shape (values.size() / columns, columns), dtype '<f4', C order.
void write_npy_table(std::ostream& out, std::span<const float> values, int columns);

}  // namespace groom
