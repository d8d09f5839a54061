// Reading meshes (.obj .ply .off .stl) into a polygon soup (kernel/polygon_soup.h), every face kept
// exactly as the file has it.
#pragma once

#include "kernel/polygon_soup.h"

#include <cstdint>
#include <string>
#include <vector>

namespace groom {

bool is_mesh_path(const std::string& path);

/// Reads a mesh file. Throws ParseError naming file and line/byte offset for malformed input
/// (indices out of range, NaN coordinates, truncated data, absurd counts) and IoError.
PolygonSoup read_mesh(const std::string& path);

/// The same, keeping only the faces of the OBJ object (`o`) or group (`g`) named `group` (empty:
/// all): real heads come with eyes, teeth and hair proxies in other groups. InvalidParam for a group
/// with a format that has none (PLY, OFF, STL); ParseError when no face has that name.
PolygonSoup read_mesh(const std::string& path, const std::string& group);

/// Faces per OBJ object (`o`) and group (`g`) name, in the order the names first appear; a face
/// counts under each name in force at it. Empty for other formats and for OBJ files without names.
struct MeshGroup {
    std::string name;
    int64_t faces = 0;
};
std::vector<MeshGroup> read_mesh_groups(const std::string& path);

/// Writes a soup as .obj or .ply (atomic).
void write_mesh(const PolygonSoup& soup, const std::string& path);

}  // namespace groom
