// PolygonSoup: a mesh exactly as a file has it (n-gons, flipped, non-manifold, duplicate vertices),
// because a half-edge structure silently drops faces it cannot insert; repair happens later, in
// fields/. Readers in kernel/io/ produce it; fields/ and ops/ consume it without any io header.
#pragma once

#include "kernel/math/vec.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace groom {

struct PolygonSoup {
    std::vector<float3> points;           ///< #vertices
    std::vector<int64_t> face_offsets{0}; ///< #faces+1; face f uses indices [face_offsets[f], face_offsets[f+1])
    std::vector<int32_t> face_indices;    ///< vertex indices, each < points.size()
    /// Texture coordinates, face-varying (a vertex on a UV seam has one per side): `uvs` holds
    /// (u, v) pairs, `face_uv_indices` parallels face_indices with each corner's pair, -1 for a
    /// corner without one. Both empty when the mesh has no texture coordinates.
    std::vector<float> uvs;               ///< #texture coordinates * 2
    std::vector<int32_t> face_uv_indices; ///< empty, or face_indices.size() entries in [-1, uvs.size()/2)

    /// Names of the file's parts, for reports (which shell of a messy mesh is the eyes): OBJ objects
    /// and groups, and the file itself where several meshes are joined. `face_part` holds each face's
    /// index into `part_names`, or is empty when the file names no part; a name may be empty (a
    /// mesh joined to named ones without names of its own).
    std::vector<std::string> part_names;
    std::vector<int32_t> face_part;       ///< empty, or #faces entries in [0, part_names.size())

    bool has_uvs() const { return !face_uv_indices.empty(); }
    bool has_parts() const { return !face_part.empty(); }

    size_t num_faces() const { return face_offsets.size() - 1; }
    std::span<const int32_t> face(size_t f) const
    {
        return {face_indices.data() + face_offsets[f], static_cast<size_t>(face_offsets[f + 1] - face_offsets[f])};
    }
    void add_face(std::span<const int32_t> idx)
    {
        face_indices.insert(face_indices.end(), idx.begin(), idx.end());
        face_offsets.push_back(static_cast<int64_t>(face_indices.size()));
        if (has_uvs()) face_uv_indices.resize(face_indices.size(), -1);
    }
    /// A face with each corner's texture coordinate (`uv_idx` as long as `idx`, -1 = none).
    void add_face(std::span<const int32_t> idx, std::span<const int32_t> uv_idx)
    {
        face_uv_indices.resize(face_indices.size(), -1);
        face_uv_indices.insert(face_uv_indices.end(), uv_idx.begin(), uv_idx.end());
        add_face(idx);
    }
};

/// Appends `more` to `to`: its vertices after `to`'s, its faces (and texture coordinates and part
/// names, where either has them) renumbered to match. Several meshes become one surface this way (a head and
/// its eyeballs). Throws LimitExceeded when the vertices (or texture coordinates) together pass
/// 2^31 - 1, the most a face index holds; `what` names the meshes in that message.
void append(PolygonSoup& to, const PolygonSoup& more, const std::string& what);

/// Topology statistics of a soup, for `groom info` and repair reports.
struct MeshStats {
    int64_t vertices = 0, faces = 0, triangles = 0, quads = 0, ngons = 0;
    int64_t shells = 0;               ///< connected components over shared vertex positions
    int64_t boundary_edges = 0;       ///< edges used by exactly one face (after welding duplicates)
    int64_t non_manifold_edges = 0;   ///< edges used by three or more faces (after welding)
    int64_t duplicate_vertices = 0;   ///< vertices at exactly the position of an earlier vertex
    int64_t degenerate_faces = 0;     ///< faces with a repeated vertex or zero area
};
MeshStats mesh_stats(const PolygonSoup& soup);

}  // namespace groom
