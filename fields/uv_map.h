// UvMap: a scalp mesh's texture coordinates, looked up at the closest point on the mesh. Kept apart
// from the repaired mesh the distance queries use: the repair welds, splits and reorients vertices,
// and a vertex on a UV seam has one coordinate per side, so the UVs stay face-varying on the user's
// own triangles (same positions as the repaired mesh's). Stored in a scalp .vdb as grid metadata
// (fields/scalp_file.cpp), so a field loaded from a file answers as one built from the mesh.
#pragma once

#include "kernel/math/vec.h"
#include "kernel/polygon_soup.h"

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace groom::detail {

class UvMap {
public:
    /// The triangles of `soup` whose corners all have texture coordinates: triangles as they are,
    /// quads split along the shorter diagonal (as the repair splits them), larger polygons fanned.
    /// Returns null when the soup has no texture coordinates (or no face with all of them).
    static std::unique_ptr<UvMap> from_soup(const PolygonSoup& soup);

    /// points: #vertices; tris: vertex indices; uvs: (u, v) pairs; tri_uvs: each corner's pair.
    UvMap(std::vector<float3> points, std::vector<std::array<int32_t, 3>> tris, std::vector<float> uvs,
          std::vector<std::array<int32_t, 3>> tri_uvs);
    ~UvMap();

    /// The coordinate at the closest point on the mesh to p, interpolated barycentrically on its
    /// triangle. Where several triangles are equally close (a point on an edge or a vertex, a seam),
    /// the lowest-numbered one answers, so the value does not depend on the tree's traversal.
    /// Thread-safe. Returns false only for a map without triangles.
    bool lookup(const float3& p, float& u, float& v) const;

    size_t num_triangles() const { return tris_.size(); }

    /// Text (printable, as OpenVDB metadata strings are shown by vdb_print and decoded by
    /// pyopenvdb): "groom-uv-mesh 1 #points #uvs #tris" then the numbers, shortest round-trip floats.
    std::string encode() const;
    /// The inverse of encode(); throws ParseError naming `what` for anything malformed (counts that
    /// disagree with the text, indices out of range, non-finite values).
    static std::unique_ptr<UvMap> decode(std::string_view text, const std::string& what);

private:
    std::vector<float3> points_;
    std::vector<std::array<int32_t, 3>> tris_;
    std::vector<float> uvs_;
    std::vector<std::array<int32_t, 3>> tri_uvs_;
    struct Tree;
    const Tree& tree() const;
    std::unique_ptr<Tree> build() const;
    mutable std::once_flag built_;
    mutable std::unique_ptr<Tree> tree_;
};

}  // namespace groom::detail
