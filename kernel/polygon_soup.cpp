#include "kernel/polygon_soup.h"

#include "kernel/error.h"
#include "kernel/position_key.h"

#include <algorithm>
#include <limits>
#include <string>
#include <numeric>
#include <unordered_map>

namespace groom {

namespace {

int64_t find_root(std::vector<int64_t>& parent, int64_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

}  // namespace

void append(PolygonSoup& to, const PolygonSoup& more, const std::string& what)
{
    constexpr size_t kMost = size_t(std::numeric_limits<int32_t>::max());
    if (to.points.size() + more.points.size() > kMost || (to.uvs.size() + more.uvs.size()) / 2 > kMost) {
        throw LimitExceeded(what + ": " + std::to_string(to.points.size() + more.points.size()) +
                            " vertices together, more than a face index holds (2^31 - 1): convert the meshes one by one, or fewer at once");
    }
    // Parts before the faces grow: a side without names gets one unnamed part.
    if (to.has_parts() || more.has_parts()) {
        if (!to.has_parts()) {
            to.face_part.assign(to.num_faces(), int32_t(to.part_names.size()));
            to.part_names.emplace_back();
        }
        const auto part_base = int32_t(to.part_names.size());
        if (more.has_parts()) {
            to.part_names.insert(to.part_names.end(), more.part_names.begin(), more.part_names.end());
            for (const int32_t k : more.face_part) to.face_part.push_back(k + part_base);
        }
        else {
            to.part_names.emplace_back();
            to.face_part.resize(to.face_part.size() + more.num_faces(), part_base);
        }
    }
    const auto base = int32_t(to.points.size()), uv_base = int32_t(to.uvs.size() / 2);
    const bool uvs = to.has_uvs() || more.has_uvs();
    if (uvs) to.face_uv_indices.resize(to.face_indices.size(), -1);  // the first mesh's corners without one
    to.points.insert(to.points.end(), more.points.begin(), more.points.end());
    to.uvs.insert(to.uvs.end(), more.uvs.begin(), more.uvs.end());
    const int64_t index_base = int64_t(to.face_indices.size());
    for (const int32_t i : more.face_indices) to.face_indices.push_back(i + base);
    for (size_t f = 1; f < more.face_offsets.size(); ++f) to.face_offsets.push_back(index_base + more.face_offsets[f]);
    if (uvs) {
        if (more.has_uvs()) {
            for (const int32_t t : more.face_uv_indices) to.face_uv_indices.push_back(t < 0 ? -1 : t + uv_base);
        }
        else {
            to.face_uv_indices.resize(to.face_indices.size(), -1);
        }
    }
}

MeshStats mesh_stats(const PolygonSoup& soup)
{
    MeshStats s;
    s.vertices = static_cast<int64_t>(soup.points.size());
    s.faces = static_cast<int64_t>(soup.num_faces());

    // Weld exact duplicate positions: vertex -> welded id.
    std::vector<int64_t> weld(soup.points.size());
    std::unordered_map<PositionKey, int64_t, PositionHash> ids;
    ids.reserve(soup.points.size());
    for (size_t i = 0; i < soup.points.size(); ++i) {
        const float3& p = soup.points[i];
        const auto [it, fresh] = ids.emplace(PositionKey::of(p), static_cast<int64_t>(ids.size()));
        weld[i] = it->second;
        if (!fresh) ++s.duplicate_vertices;
    }
    const int64_t welded = static_cast<int64_t>(ids.size());

    std::vector<int64_t> parent(welded);
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<char> used(welded, 0);
    std::unordered_map<uint64_t, int32_t> edge_use;
    edge_use.reserve(soup.face_indices.size());
    std::vector<int64_t> w;
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        const auto face = soup.face(f);
        const size_t n = face.size();
        if (n == 3) ++s.triangles;
        else if (n == 4) ++s.quads;
        else if (n > 4) ++s.ngons;
        w.assign(n, 0);
        for (size_t k = 0; k < n; ++k) w[k] = weld[face[k]];
        // Degenerate: fewer than 3 corners, a repeated (welded) corner, or zero area (Newell normal).
        bool degenerate = n < 3;
        std::vector<int64_t> sorted = w;
        std::sort(sorted.begin(), sorted.end());
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) degenerate = true;
        if (!degenerate) {
            double nx = 0, ny = 0, nz = 0;
            for (size_t k = 0; k < n; ++k) {
                const float3& a = soup.points[face[k]];
                const float3& b = soup.points[face[(k + 1) % n]];
                nx += (double(a.y) - b.y) * (double(a.z) + b.z);
                ny += (double(a.z) - b.z) * (double(a.x) + b.x);
                nz += (double(a.x) - b.x) * (double(a.y) + b.y);
            }
            if (nx == 0 && ny == 0 && nz == 0) degenerate = true;
        }
        if (degenerate) ++s.degenerate_faces;
        for (size_t k = 0; k < n; ++k) {
            used[w[k]] = 1;
            const int64_t a = w[k], b = w[(k + 1) % n];
            if (n < 2 || a == b) continue;
            const int64_t ra = find_root(parent, a), rb = find_root(parent, b);
            if (ra != rb) parent[ra] = rb;
            const uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint64_t>(std::max(a, b));
            ++edge_use[key];
        }
    }
    for (const auto& [key, count] : edge_use) {
        if (count == 1) ++s.boundary_edges;
        else if (count >= 3) ++s.non_manifold_edges;
    }
    for (int64_t i = 0; i < welded; ++i)
        if (used[i] && find_root(parent, i) == i) ++s.shells;
    return s;
}

}  // namespace groom
