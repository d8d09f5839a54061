// Curves from an edge list: what PLY line sets and the OBJ files Blender writes (one `l a b` record
// per edge) hold instead of polylines. Shared by the PLY and OBJ curve readers.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace groom::io {

/// Chains found in an edge list; chain k is vertices order[start_k .. start_k + counts[k]).
struct EdgeChains {
    std::vector<int64_t> order;       ///< vertex indices, chain after chain, each root first
    std::vector<int64_t> counts;      ///< vertices per chain
    std::vector<int64_t> first_edge;  ///< per chain: the lowest index among its edges (-1: an isolated vertex)
};

/// Joins edges (from[e], to[e]) over `n` vertices into open chains. Edges are undirected; a chain
/// whose edges all point one way starts at its source (root to tip). Chains come in the order of
/// their lowest end vertex. Indices must already be checked to lie in [0, n) and differ.
/// @param isolated  vertices without an edge become one-point chains (true) or are left out (false).
/// @param file      name for messages; vertices are numbered in them from `vertex_base` (0 for PLY,
///                  1 for OBJ) and the edge records called `edge_word` ("edges", "'l' records").
/// @param loops     closed loops are chains too (true: after the open ones, each from its lowest
///                  vertex, along the edge that leaves it where one does, that vertex repeated at the
///                  end, as a USD periodic curve reads: a hairline) or an error (false: a hair or guide
///                  has a root and a tip, and a loop has neither; one is more likely a mesh's edge ring).
/// @throws ParseError for a vertex with more than two edges (a branch) or, unless `loops`, a closed loop.
EdgeChains join_edge_chains(int64_t n, std::span<const int64_t> from, std::span<const int64_t> to, bool isolated, const std::string& file,
                            int64_t vertex_base, const std::string& edge_word, bool loops = false);

}  // namespace groom::io
