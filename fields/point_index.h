// PointIndex: nearest-neighbour search over a fixed set of points, for the ops that ask which guide
// roots or guide points lie nearest (generate, partition's adjacency). A CGAL kd-tree (sliding
// midpoint splits) behind a pimpl, so CGAL's headers stay in fields/. Built once; queries are const
// and thread-safe.
#pragma once

#include "kernel/math/vec.h"

#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

namespace groom {

class PointIndex {
public:
    /// Indexes `points` (copied, in double). An empty set answers every query with nothing. Throws
    /// LimitExceeded past 2^32 - 1 points (the tree's keys are 32-bit).
    explicit PointIndex(std::span<const float3> points);
    ~PointIndex();
    PointIndex(PointIndex&&) noexcept;
    PointIndex& operator=(PointIndex&&) noexcept;

    size_t size() const;

    struct Neighbour {
        uint32_t index = 0;     ///< into the points given to the constructor
        double distance = 0.0;  ///< from the query, scene units
    };

    /// Up to `k` (>= 1) nearest points to `q`, nearest first; equal distances in index order, so the
    /// answer does not depend on how the tree was split.
    void nearest(const float3& q, int k, std::vector<Neighbour>& out) const;

    /// Calls visit(index, squared distance) for the points in order of increasing distance from `q`
    /// (CGAL's incremental search: equal distances in the tree's order), until visit returns false or
    /// the points run out. For searches whose stopping rule depends on what they find.
    template <class Visit>
        requires std::is_invocable_r_v<bool, Visit&, uint32_t, double>
    void walk(const float3& q, Visit&& visit) const
    {
        walk_impl(q, &visit, [](void* v, uint32_t i, double d2) -> bool { return (*static_cast<std::remove_reference_t<Visit>*>(v))(i, d2); });
    }

private:
    void walk_impl(const float3& q, void* visit, bool (*call)(void*, uint32_t, double)) const;

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace groom
