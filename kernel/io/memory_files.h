// In-memory "files": a program that embeds groom (the Python module) hands curve sets to a command
// where it takes a path, as "mem:NAME", and gets its outputs back the same way. read_curves and
// write_curves look such paths up here instead of on disk, so an embedded call runs exactly the code
// the command line runs, options, defaults and all. Thread-safe; names are the caller's to keep
// unique (the Python module numbers them per call).
#pragma once

#include "kernel/curve_set.h"

#include <string>
#include <string_view>

namespace groom {

/// True for "mem:NAME" paths.
bool is_memory_path(std::string_view path);

/// Stores `curves` under `path` ("mem:NAME"), replacing what was there.
void store_memory_curves(const std::string& path, CurveSet curves);

/// A copy of what `path` holds. Throws IoError naming the path when nothing is stored there.
CurveSet read_memory_curves(const std::string& path);

/// Removes and returns what `path` holds. Throws IoError when nothing is stored there.
CurveSet take_memory_curves(const std::string& path);

/// Removes `path` if present.
void erase_memory_curves(const std::string& path);

}  // namespace groom
