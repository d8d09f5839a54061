#include "fields/point_queries.h"

#include "kernel/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace groom {
namespace {

/// The points in the order they are queried, and whether they are dense (below).
struct QueryOrder {
    std::vector<uint32_t> order;  ///< point indices; empty: the file's order
    bool dense = false;
};

/// Sorts the points by their cell of side `side` (one of ScalpField::query_dense's), cells grouped
/// in blocks of 4^3. Queried in that order, points of one cell come together: its candidate faces,
/// the band's bricks and the near faces' table stay in cache (2M hair points on Sintel: hairs come
/// in random order, 71% of the queries changed cells and the query loop took 1.29 s at 1 thread;
/// sorted by 2-voxel cells, 0.91-0.98 s). The same sort counts the cells: `dense` is true when the
/// points average at least 16 a cell (counted over the cells they occupy), where the cells pay for
/// themselves (hair: 47 a 2-voxel cell; 2M points spread through Sintel's box: 4.6 a 2-voxel cell,
/// 1.7 s more CPU than the tree, about 30 a 4-voxel cell, 2.2x faster than the tree). Both are
/// functions of the points alone, and every answer is a function of its point, so the result does
/// not depend on the thread count (nor on the order).
QueryOrder query_order(std::span<const float3> points, float side)
{
    QueryOrder out;
    if (points.size() < 16 || !(side > 0.0f) || points.size() > size_t(UINT32_MAX)) return out;
    const size_t n = points.size();
    const double inv = 1.0 / double(side);
    // A point's cell along one axis (clamped first: a float beyond int64's range does not convert).
    const auto cell = [&](float v) { return int64_t(std::clamp(std::floor(double(v) * inv), -0x1p62, 0x1p62)); };
    using Box = std::array<int64_t, 6>;  // lowest x y z, highest x y z
    const Box box = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 1 << 14), Box{INT64_MAX, INT64_MAX, INT64_MAX, INT64_MIN, INT64_MIN, INT64_MIN},
        [&](const tbb::blocked_range<size_t>& r, Box b) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const int64_t c[3] = {cell(points[i].x), cell(points[i].y), cell(points[i].z)};
                for (int k = 0; k < 3; ++k) {
                    b[size_t(k)] = std::min(b[size_t(k)], c[k]);
                    b[size_t(k) + 3] = std::max(b[size_t(k) + 3], c[k]);
                }
            }
            return b;
        },
        [](Box a, const Box& b) {
            for (int k = 0; k < 3; ++k) {
                a[size_t(k)] = std::min(a[size_t(k)], b[size_t(k)]);
                a[size_t(k) + 3] = std::max(a[size_t(k) + 3], b[size_t(k) + 3]);
            }
            return a;
        });
    // Blocks of 4^3 cells over the points' box, in z, y, x order, then the cell in its block.
    uint64_t blocks[3];
    bool small = true;
    for (int k = 0; k < 3; ++k) {
        const uint64_t span = uint64_t(box[size_t(k) + 3]) - uint64_t(box[size_t(k)]);  // no overflow in unsigned
        small &= span < (uint64_t(1) << 20);
        blocks[k] = small ? (span >> 2) + 1 : 0;
    }
    size_t occupied = 0;
    out.order.resize(n);
    if (small && blocks[0] * blocks[1] * blocks[2] * 64 <= 4 * uint64_t(n)) {
        // A counting sort (stable: a cell's points in the file's order), where a comparison sort
        // of 2M keys took 0.13 s.
        const auto key = [&](const float3& p) {
            const uint64_t x = uint64_t(cell(p.x) - box[0]), y = uint64_t(cell(p.y) - box[1]), z = uint64_t(cell(p.z) - box[2]);
            const uint64_t block = ((z >> 2) * blocks[1] + (y >> 2)) * blocks[0] + (x >> 2);
            return size_t(block << 6 | (x & 3) | (y & 3) << 2 | (z & 3) << 4);
        };
        std::vector<uint32_t> start(size_t(blocks[0] * blocks[1] * blocks[2] * 64) + 1, 0);
        for (const float3& p : points) ++start[key(p) + 1];
        for (size_t k = 1; k < start.size(); ++k) {
            occupied += start[k] != 0;
            start[k] += start[k - 1];
        }
        for (size_t i = 0; i < n; ++i) out.order[start[key(points[i])]++] = uint32_t(i);
    }
    else {
        // Points spread far apart: sort keys of 21 bits an axis, wrapping (a collision only merges
        // two cells in the count, an estimate either way; within 2^20 cells, above, there is none).
        std::vector<std::pair<uint64_t, uint32_t>> keys(n);
        parallel_for(int64_t(n), 1 << 14, [&](int64_t b, int64_t e) {
            for (int64_t i = b; i < e; ++i) {
                const float3& p = points[size_t(i)];
                const uint64_t x = uint64_t(cell(p.x)) & 0x1fffff, y = uint64_t(cell(p.y)) & 0x1fffff, z = uint64_t(cell(p.z)) & 0x1fffff;
                const uint64_t block = (x >> 2) | (y >> 2) << 19 | (z >> 2) << 38;
                keys[size_t(i)] = {block << 6 | (x & 3) | (y & 3) << 2 | (z & 3) << 4, uint32_t(i)};
            }
        });
        tbb::parallel_sort(keys.begin(), keys.end());
        for (size_t i = 0; i < n; ++i) {
            occupied += i == 0 || keys[i].first != keys[i - 1].first;
            out.order[i] = keys[i].second;
        }
    }
    out.dense = n >= 16 * occupied;
    return out;
}

}  // namespace

void query_points(const ScalpField& scalp, std::span<const float3> points,
                  const std::function<void(size_t i, float distance, const float3& normal, const float3& closest)>& out)
{
    // The smallest cells the points crowd; none (the tree for each point) where no size is
    // crowded, in the order of the smallest cells (their band bricks stay in cache).
    QueryOrder sorted = query_order(points, scalp.dense_cell_size(0));
    int level = sorted.dense ? 0 : -1;
    for (int l = 1; level < 0 && l < ScalpField::kDenseLevels; ++l) {
        QueryOrder coarser = query_order(points, scalp.dense_cell_size(l));
        if (!coarser.dense) continue;
        sorted = std::move(coarser);
        level = l;
    }
    parallel_for(int64_t(points.size()), 1024, [&](int64_t b, int64_t e) {
        for (int64_t j = b; j < e; ++j) {
            const size_t i = sorted.order.empty() ? size_t(j) : size_t(sorted.order[size_t(j)]);
            float3 n, c;
            const float d = level >= 0 ? scalp.query_dense(points[i], n, c, level) : scalp.query(points[i], n, c);
            out(i, d, n, c);
        }
    });
}

}  // namespace groom
