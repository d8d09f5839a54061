// Open rims of a repaired scalp mesh (the holes of a head: eye sockets, mouth, the neck), and the
// filling of those up to a length (`groom scalp --fill-holes`): a head with empty eye sockets and no
// eyeballs to join shows hair hanging inside them, and a filled socket keeps it in front.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cstdint>
#include <vector>

namespace groom::detail {

using RimPoint = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

struct Rim {
    std::vector<size_t> loop;  ///< vertices in the order of the faces' boundary edges (a -> b, no b -> a)
    double length = 0.0;       ///< scene units
    bool simple = true;        ///< no vertex on it twice and none on another rim (only such rims are filled)
};

/// The rims of an oriented manifold triangle soup, longest first (ties by their smallest vertex).
std::vector<Rim> find_rims(const std::vector<RimPoint>& points, const std::vector<std::vector<size_t>>& triangles);

/// Closes every simple rim no longer than `max_length` with CGAL's hole triangulation of its
/// polyline (no new vertices), wound so the soup stays an oriented manifold; a rim CGAL cannot
/// triangulate, or whose patch would not keep the soup manifold, stays open. Appends the triangles;
/// returns the rims filled and adds the triangles made to `faces_added`.
int64_t fill_rims(const std::vector<RimPoint>& points, std::vector<std::vector<size_t>>& triangles, const std::vector<Rim>& rims,
                  double max_length, int64_t& faces_added);

}  // namespace groom::detail
