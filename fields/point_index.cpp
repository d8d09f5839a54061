#include "fields/point_index.h"

#include "kernel/error.h"

#include <CGAL/Orthogonal_incremental_neighbor_search.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace groom {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point3 = Kernel::Point_3;

/// The tree stores point indices; this map turns an index into its position, so a hit names its point.
struct IndexPointMap {
    const std::vector<Point3>* points = nullptr;
    using key_type = uint32_t;
    using value_type = Point3;
    using reference = const Point3&;
    using category = boost::readable_property_map_tag;
    friend reference get(const IndexPointMap& m, key_type i) { return (*m.points)[i]; }
};

using Traits = CGAL::Search_traits_adapter<uint32_t, IndexPointMap, CGAL::Search_traits_3<Kernel>>;
using KNearest = CGAL::Orthogonal_k_neighbor_search<Traits>;
using Incremental = CGAL::Orthogonal_incremental_neighbor_search<Traits>;
using Tree = Incremental::Tree;
using Distance = Incremental::Distance;
static_assert(std::is_same_v<KNearest::Tree, Tree> && std::is_same_v<KNearest::Distance, Distance>,
              "both searches must walk the same tree");

Point3 to_point(const float3& p) { return {p.x, p.y, p.z}; }

}  // namespace

struct PointIndex::Impl {
    std::vector<Point3> points;
    std::unique_ptr<Tree> tree;
};

PointIndex::PointIndex(std::span<const float3> points) : impl_(std::make_unique<Impl>())
{
    if (points.size() > size_t(std::numeric_limits<uint32_t>::max())) {
        throw LimitExceeded("point index: " + std::to_string(points.size()) + " points is more than 2^32 - 1");
    }
    impl_->points.reserve(points.size());
    for (const float3& p : points) impl_->points.push_back(to_point(p));
    if (points.empty()) return;
    std::vector<uint32_t> keys(points.size());
    for (size_t i = 0; i < keys.size(); ++i) keys[i] = uint32_t(i);
    impl_->tree = std::make_unique<Tree>(keys.begin(), keys.end(), Tree::Splitter(), Traits(IndexPointMap{&impl_->points}));
    // CGAL builds lazily on the first query, which is not safe when the first queries come from
    // several threads at once: build now, so queries only read.
    impl_->tree->build();
}

PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

size_t PointIndex::size() const { return impl_->points.size(); }

void PointIndex::nearest(const float3& q, int k, std::vector<Neighbour>& out) const
{
    out.clear();
    if (!impl_->tree || k < 1) return;
    KNearest search(*impl_->tree, to_point(q), static_cast<unsigned>(k), 0.0, true, Distance(IndexPointMap{&impl_->points}));
    for (auto it = search.begin(); it != search.end(); ++it) out.push_back({it->first, std::sqrt(it->second)});
    std::stable_sort(out.begin(), out.end(), [](const Neighbour& a, const Neighbour& b) {
        return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
    });
}

void PointIndex::walk_impl(const float3& q, void* visit, bool (*call)(void*, uint32_t, double)) const
{
    if (!impl_->tree) return;
    Incremental search(*impl_->tree, to_point(q), 0.0, true, Distance(IndexPointMap{&impl_->points}));
    for (auto it = search.begin(); it != search.end(); ++it) {
        if (!call(visit, it->first, it->second)) return;
    }
}

}  // namespace groom
