// The linear test for an oriented manifold triangle soup that lets a clean mesh skip CGAL's
// orientation (the slow part of the repair).
#include "fields/scalp_impl.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace groom {
namespace detail {

/// True when the triangles form an oriented manifold: every directed edge used at most once (so an
/// edge has at most two faces, wound oppositely) and the faces around every vertex one fan. That is
/// what PMP::orient_polygon_soup leaves unchanged and polygon_soup_to_polygon_mesh needs; most meshes
/// users bring already are, and this check is linear where CGAL's orient and is_polygon_soup_a_polygon_mesh
/// (ordered sets of edges) cost 70% of the repair on a clean 70k-face head.
bool is_oriented_manifold(const std::vector<std::vector<size_t>>& tris, size_t num_points)
{
    // The link of vertex v: for each face (v, a, b) in rotation, the arc a -> b.
    std::vector<uint32_t> offsets(num_points + 1, 0);
    for (const std::vector<size_t>& t : tris) {
        if (t.size() != 3) return false;
        for (size_t v : t) ++offsets[v + 1];
    }
    for (size_t v = 0; v < num_points; ++v) offsets[v + 1] += offsets[v];
    std::vector<std::pair<uint32_t, uint32_t>> arcs(offsets.back());
    {
        std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
        for (const std::vector<size_t>& t : tris) {
            for (int k = 0; k < 3; ++k) arcs[fill[t[k]]++] = {uint32_t(t[(k + 1) % 3]), uint32_t(t[(k + 2) % 3])};
        }
    }
    std::vector<uint32_t> targets;
    for (size_t v = 0; v < num_points; ++v) {
        const auto first = arcs.begin() + offsets[v], last = arcs.begin() + offsets[v + 1];
        const size_t n = size_t(last - first);
        if (n == 0) continue;
        std::sort(first, last);
        targets.clear();
        for (auto it = first; it != last; ++it) targets.push_back(it->second);
        std::sort(targets.begin(), targets.end());
        // A repeated source is directed edge v -> a twice, a repeated target b -> v twice.
        for (size_t i = 1; i < n; ++i) {
            if (first[i].first == first[i - 1].first || targets[i] == targets[i - 1]) return false;
        }
        // Unique sources and targets make the link paths and cycles; a fan is exactly one of them.
        size_t start = 0, starts = 0;
        for (size_t i = 0; i < n; ++i) {
            if (!std::binary_search(targets.begin(), targets.end(), first[i].first)) {
                start = i;
                ++starts;
            }
        }
        if (starts > 1) return false;
        size_t steps = 0;
        for (size_t i = start;;) {
            ++steps;
            const uint32_t next = first[i].second;
            const auto it = std::lower_bound(first, last, std::make_pair(next, uint32_t(0)));
            if (it == last || it->first != next) break;  // the end of a path
            i = size_t(it - first);
            if (i == start) break;  // back round a cycle
        }
        if (steps != n) return false;
    }
    return true;
}

}  // namespace detail
}  // namespace groom
