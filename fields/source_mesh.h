// The repaired mesh a scalp field was built from, as text for the .vdb's grid metadata
// "groom_source_mesh" (fields/scalp_file.cpp). With it, a field loaded from the file has the very
// mesh the field was built from, so queries outside the band and root sampling answer exactly as
// when the mesh itself is passed; without it (other programs' files, older groom) the mesh must be
// extracted from the level set's zero crossing. Text, like "groom_uv_mesh" (fields/uv_map.h),
// because vdb_print shows and pyopenvdb decodes metadata strings.
#pragma once

#include "kernel/math/vec.h"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace groom::detail {

struct SourceMesh {
    std::vector<float3> points;
    std::vector<std::array<int32_t, 3>> tris;
};

/// "groom-source-mesh 1 #points #triangles" then x y z per point and three vertex indices per
/// triangle, floats as shortest round-trip text (read back to the bit).
std::string encode_source_mesh(std::span<const float3> points, std::span<const std::array<int32_t, 3>> tris);

/// The inverse of encode_source_mesh(). Throws ParseError naming `what` and the metadata for
/// anything malformed: a wrong header or version, counts that disagree with the text, a
/// non-finite coordinate, an index out of range, a triangle with a repeated corner, or a directed
/// edge used twice (the repaired mesh is an oriented manifold: each edge side has one face).
SourceMesh decode_source_mesh(std::string_view text, const std::string& what);

}  // namespace groom::detail
