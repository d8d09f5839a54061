// Reading meshes (.obj .ply .off .stl) into a polygon soup (kernel/polygon_soup.h), every face kept
// exactly as the file has it.
#pragma once

#include "kernel/polygon_soup.h"

#include <string>

namespace groom {

bool is_mesh_path(const std::string& path);

/// Reads a mesh file. Throws ParseError naming file and line/byte offset for malformed input
/// (indices out of range, NaN coordinates, truncated data, absurd counts) and IoError.
PolygonSoup read_mesh(const std::string& path);

/// Writes a soup as .obj or .ply (atomic).
void write_mesh(const PolygonSoup& soup, const std::string& path);

}  // namespace groom
