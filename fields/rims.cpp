// Open rims: boundary edges chained into loops, and their filling (see rims.h).
#include "fields/rims.h"

#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <unordered_set>
#include <utility>

namespace groom::detail {

namespace PMP = CGAL::Polygon_mesh_processing;

std::vector<Rim> find_rims(const std::vector<RimPoint>& points, const std::vector<std::vector<size_t>>& triangles)
{
    // The directed edges, sorted: a boundary edge a -> b is one whose twin b -> a is not there.
    std::vector<std::pair<size_t, size_t>> edges;
    edges.reserve(triangles.size() * 3);
    for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) edges.emplace_back(t[size_t(k)], t[size_t((k + 1) % 3)]);
    std::sort(edges.begin(), edges.end());
    constexpr size_t kNone = size_t(-1);
    std::vector<size_t> next(points.size(), kNone);
    std::vector<int> outgoing(points.size(), 0);
    for (const auto& [a, b] : edges) {
        if (std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a))) continue;
        next[a] = b;
        ++outgoing[a];
    }
    // Walked from each unvisited boundary vertex in index order, so the rims and their vertices come
    // out the same for the same soup. A vertex with two boundary edges out (two rims touching, a
    // pinch the repair left) ends its walk; the rim is kept but marked not simple.
    std::vector<Rim> rims;
    std::vector<char> seen(points.size(), 0);
    for (size_t start = 0; start < points.size(); ++start) {
        if (next[start] == kNone || seen[start]) continue;
        Rim rim;
        size_t v = start;
        while (v != kNone && !seen[v]) {
            seen[v] = 1;
            rim.loop.push_back(v);
            rim.simple = rim.simple && outgoing[v] == 1;
            const size_t w = next[v];
            if (w != kNone) rim.length += std::sqrt(CGAL::squared_distance(points[v], points[w]));
            v = w;
        }
        rim.simple = rim.simple && v == start;
        rims.push_back(std::move(rim));
    }
    std::stable_sort(rims.begin(), rims.end(), [](const Rim& a, const Rim& b) { return a.length > b.length; });
    return rims;
}

int64_t fill_rims(const std::vector<RimPoint>& points, std::vector<std::vector<size_t>>& triangles, const std::vector<Rim>& rims,
                  double max_length, int64_t& faces_added)
{
    int64_t filled = 0;
    std::unordered_set<uint64_t> edges;  // the soup's directed edges, made on the first rim to fill
    auto edge_key = [](size_t a, size_t b) { return (uint64_t(a) << 32) | uint64_t(b); };
    for (const Rim& rim : rims) {
        const size_t n = rim.loop.size();
        if (!rim.simple || n < 3 || !(rim.length <= max_length)) continue;
        std::vector<RimPoint> polyline;
        for (size_t v : rim.loop) polyline.push_back(points[v]);
        std::vector<CGAL::Triple<int, int, int>> patch;
        PMP::triangulate_hole_polyline(polyline, std::back_inserter(patch));
        if (patch.size() != n - 2) continue;
        // The mesh runs each rim edge a -> b; the patch must run it b -> a. The patch is a disc whose
        // corners all lie on the rim, so each triangle's corners in rim order (i < m < k) run the
        // way the rim does, whatever order CGAL lists them in: each is turned to k, m, i.
        std::vector<std::vector<size_t>> tris;
        for (const auto& t : patch) {
            int c[3] = {t.first, t.second, t.third};
            std::sort(c, c + 3);
            tris.push_back({rim.loop[size_t(c[2])], rim.loop[size_t(c[1])], rim.loop[size_t(c[0])]});
        }
        // Each directed edge at most once keeps the soup an oriented manifold: a patch whose
        // diagonal is an edge the mesh (or another patch) already has stays out. (Asking
        // is_oriented_manifold of the whole soup per rim took 1.3 s for ICT's 134 rims.)
        if (edges.empty()) {
            for (const auto& t : triangles)
                for (int k = 0; k < 3; ++k) edges.insert(edge_key(t[size_t(k)], t[size_t((k + 1) % 3)]));
        }
        bool clash = false;
        for (const auto& t : tris)
            for (int k = 0; k < 3; ++k) clash = clash || edges.count(edge_key(t[size_t(k)], t[size_t((k + 1) % 3)])) > 0;
        if (clash) continue;
        for (const auto& t : tris)
            for (int k = 0; k < 3; ++k) edges.insert(edge_key(t[size_t(k)], t[size_t((k + 1) % 3)]));
        triangles.insert(triangles.end(), tris.begin(), tris.end());
        ++filled;
        faces_added += int64_t(tris.size());
    }
    return filled;
}

}  // namespace groom::detail
