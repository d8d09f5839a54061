#include "kernel/io/edge_chains.h"

#include "kernel/error.h"

#include <algorithm>

namespace groom::io {

EdgeChains join_edge_chains(int64_t n, std::span<const int64_t> from, std::span<const int64_t> to, bool isolated, const std::string& file,
                            int64_t vertex_base, const std::string& edge_word, bool loops)
{
    // Chains: each vertex has at most one edge on each side.
    std::vector<int64_t> nb0(size_t(n), -1), nb1(size_t(n), -1), edge0(size_t(n), -1), succ(size_t(n), -1);
    std::vector<char> is_target(size_t(n), 0);
    for (size_t e = 0; e < from.size(); ++e) {
        const int64_t ia = from[e], ib = to[e];
        is_target[ib] = 1;
        if (succ[ia] < 0) succ[ia] = ib;
        for (int64_t x : {ia, ib}) {
            const int64_t other = x == ia ? ib : ia;
            if (edge0[x] < 0) edge0[x] = int64_t(e);
            if (nb0[x] < 0) nb0[x] = other;
            else if (nb1[x] < 0) nb1[x] = other;
            else {
                throw ParseError(file + ": vertex " + std::to_string(x + vertex_base) + " has more than two " + edge_word +
                                 ": curves must be simple chains");
            }
        }
    }
    EdgeChains out;
    std::vector<char> seen(size_t(n), 0);
    std::vector<int64_t> chain;
    for (int64_t s = 0; s < n; ++s) {
        if (seen[s] || nb1[s] >= 0) continue;  // start at chain ends (and isolated vertices)
        if (nb0[s] < 0 && !isolated) continue;
        chain.assign(1, s);
        seen[s] = 1;
        int64_t first = edge0[s];
        for (int64_t prev = -1, at = s;;) {
            const int64_t next = nb0[at] != prev ? nb0[at] : nb1[at];
            if (next < 0 || seen[next]) break;
            chain.push_back(next);
            seen[next] = 1;
            first = std::min(first, edge0[next]);
            prev = at;
            at = next;
        }
        // Walked from the end that is a target while the other end is not: reverse to root-first.
        if (chain.size() > 1 && is_target[chain.front()] && !is_target[chain.back()]) std::reverse(chain.begin(), chain.end());
        out.order.insert(out.order.end(), chain.begin(), chain.end());
        out.counts.push_back(int64_t(chain.size()));
        out.first_edge.push_back(first);
    }
    for (int64_t s = 0; s < n; ++s) {
        if (!seen[s] && nb0[s] >= 0 && loops) {
            // A loop: every vertex on it has two edges. Its lowest vertex first, then the way its
            // edges point (Blender writes a closed curve's edges a->b, b->c, ..., z->a), closed by
            // that first vertex again.
            chain.assign(1, s);
            seen[s] = 1;
            int64_t first = edge0[s];
            for (int64_t prev = s, at = succ[s] >= 0 ? succ[s] : nb0[s]; !seen[at];) {
                chain.push_back(at);
                seen[at] = 1;
                first = std::min(first, edge0[at]);
                const int64_t next = nb0[at] != prev ? nb0[at] : nb1[at];
                prev = at;
                at = next;
            }
            chain.push_back(s);
            out.order.insert(out.order.end(), chain.begin(), chain.end());
            out.counts.push_back(int64_t(chain.size()));
            out.first_edge.push_back(first);
        }
        else if (!seen[s] && nb0[s] >= 0) {
            throw ParseError(file + ": vertex " + std::to_string(s + vertex_base) + " lies on a closed loop of " + edge_word +
                             "; curves must be open chains");
        }
    }
    return out;
}

}  // namespace groom::io
