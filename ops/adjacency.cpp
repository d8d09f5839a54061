#include "ops/adjacency.h"

#include "fields/point_index.h"
#include "fields/surface.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace groom {

namespace {

struct SegmentHit {
    double d2 = INFINITY, t = 0.0;
};

/// Closest point of segment [a, b] to q, in double so distances compare exactly across calls.
SegmentHit closest_on_segment(const float3& a, const float3& b, const float3& q)
{
    const double abx = double(b.x) - a.x, aby = double(b.y) - a.y, abz = double(b.z) - a.z;
    const double aqx = double(q.x) - a.x, aqy = double(q.y) - a.y, aqz = double(q.z) - a.z;
    const double len2 = abx * abx + aby * aby + abz * abz;
    double t = len2 > 0.0 ? (abx * aqx + aby * aqy + abz * aqz) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const double dx = aqx - t * abx, dy = aqy - t * aby, dz = aqz - t * abz;
    return {dx * dx + dy * dy + dz * dz, t};
}

}  // namespace

// --- PolylineNearest ----------------------------------------------------------------------------------

struct PolylineNearest::Impl {
    std::vector<float3> pts;
    PointIndex index;
    double half_longest = 0.0;  // half the longest segment: the search radius beyond the best distance
    explicit Impl(std::span<const float3> p) : pts(p.begin(), p.end()), index(p) {}
};

PolylineNearest::PolylineNearest(std::span<const float3> pts) : impl_(std::make_unique<Impl>(pts))
{
    for (size_t i = 1; i < pts.size(); ++i) impl_->half_longest = std::max(impl_->half_longest, 0.5 * double(distance(pts[i - 1], pts[i])));
}

PolylineNearest::~PolylineNearest() = default;
PolylineNearest::PolylineNearest(PolylineNearest&&) noexcept = default;
PolylineNearest& PolylineNearest::operator=(PolylineNearest&&) noexcept = default;

PolylineNearest::Hit PolylineNearest::closest(const float3& q) const
{
    const auto& pts = impl_->pts;
    Hit hit;
    if (pts.empty()) return hit;
    if (pts.size() == 1) {
        hit.point = pts[0];
        hit.segment = 0;
        hit.distance = distance(q, pts[0]);
        return hit;
    }
    const int64_t nseg = int64_t(pts.size()) - 1;
    double best_d2 = INFINITY, best_t = 0.0;
    int64_t best_seg = -1;
    auto test = [&](int64_t s) {
        if (s < 0 || s >= nseg) return;
        const SegmentHit h = closest_on_segment(pts[s], pts[s + 1], q);
        if (h.d2 < best_d2 || (h.d2 == best_d2 && s < best_seg)) {
            best_d2 = h.d2;
            best_t = h.t;
            best_seg = s;
        }
    };
    impl_->index.walk(q, [&](uint32_t v, double d2) {
        // The closest segment's nearer end lies within best + half_longest of q: stop past that.
        const double reach = std::sqrt(best_d2) + impl_->half_longest;
        if (best_seg >= 0 && d2 > reach * reach) return false;
        test(int64_t(v) - 1);
        test(int64_t(v));
        return true;
    });
    hit.segment = best_seg;
    hit.t = float(best_t);
    hit.point = lerp(pts[best_seg], pts[best_seg + 1], hit.t);
    hit.distance = float(std::sqrt(best_d2));
    return hit;
}

// --- sides --------------------------------------------------------------------------------------------

int classify_side(const float3& offset, const float3& normal, const float3& left)
{
    const float along_normal = dot(offset, normal);
    const float3 in_plane = offset - normal * along_normal;
    const float plane2 = length_squared(in_plane);
    if (!(plane2 > 0.0f)) return -1;
    // Compared squared to avoid square roots: cos^2 60 deg = 0.25 out of the plane, cos^2 45 deg =
    // 0.5 from the lateral axis.
    if (plane2 < 0.25f * length_squared(offset)) return -1;
    const float lateral = dot(in_plane, left);
    if (lateral * lateral < 0.5f * plane2) return -1;
    return lateral > 0.0f ? 0 : 1;
}

float3 tangent_at_length(std::span<const float3> pts, std::span<const double> cumulative, std::span<const float3> tangents,
                         double s)
{
    if (pts.size() < 2) return {0, 1, 0};
    if (s <= 0.0) return tangents.front();
    if (s >= cumulative.back()) return tangents.back();
    const ArcSpot a = locate_at_length(cumulative, s);
    return normalize(lerp(tangents[a.lo], tangents[a.hi], float(a.t)), tangents[a.lo]);
}

float3 left_direction(const float3& normal, const float3& tangent)
{
    const float3 along = tangent - normal * dot(tangent, normal);
    return normalize(cross(normal, along), any_perpendicular(normal));
}

struct GuidePointIndex::Impl {
    std::vector<float3> positions;
    std::vector<int32_t> guide_of;
    PointIndex index;
    explicit Impl(std::span<const float3> P) : positions(P.begin(), P.end()), index(P) {}
};

GuidePointIndex::GuidePointIndex(const CurveSet& guides) : impl_(std::make_unique<Impl>(guides.positions()))
{
    impl_->guide_of.resize(impl_->positions.size());
    for (size_t c = 0; c < guides.num_curves(); ++c) {
        const IndexRange r = guides.points_of(c);
        std::fill(impl_->guide_of.begin() + r.begin, impl_->guide_of.begin() + r.end, int32_t(c));
    }
}

GuidePointIndex::~GuidePointIndex() = default;
GuidePointIndex::GuidePointIndex(GuidePointIndex&&) noexcept = default;
GuidePointIndex& GuidePointIndex::operator=(GuidePointIndex&&) noexcept = default;

std::array<GuidePointIndex::SideHit, 2> GuidePointIndex::nearest_on_sides(const float3& p, const float3& normal,
                                                                           const float3& left, int32_t exclude,
                                                                           float max_gap) const
{
    std::array<SideHit, 2> out;
    const double limit2 = max_gap > 0.0f ? double(max_gap) * max_gap : INFINITY;
    int found = 0;
    impl_->index.walk(p, [&](uint32_t i, double d2) {
        if (d2 > limit2) return false;
        const int32_t g = impl_->guide_of[i];
        if (g == exclude) return true;
        const int side = classify_side(impl_->positions[i] - p, normal, left);
        if (side < 0 || out[side].guide >= 0) return true;
        out[side] = {g, int64_t(i), float(std::sqrt(d2))};
        return ++found < 2;
    });
    return out;
}

GuidePointIndex::SideHit GuidePointIndex::nearest_other(const float3& p, int32_t exclude) const
{
    SideHit out;
    impl_->index.walk(p, [&](uint32_t i, double d2) {
        const int32_t g = impl_->guide_of[i];
        if (g == exclude) return true;
        out = {g, int64_t(i), float(std::sqrt(d2))};
        return false;
    });
    return out;
}

float typical_guide_gap(const CurveSet& guides, const GuidePointIndex& index)
{
    const auto P = guides.positions();
    const size_t nc = guides.num_curves();
    std::vector<float> gaps(nc, INFINITY);
    parallel_for(int64_t(nc), 16, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = guides.points_of(c);
            if (r.size() < 2) continue;
            const auto pts = P.subspan(r.begin, r.size());
            const auto cum = cumulative_lengths(pts);
            gaps[c] = index.nearest_other(point_at_length(pts, cum, 0.5 * cum.back()), int32_t(c)).distance;
        }
    });
    std::erase_if(gaps, [](float g) { return !std::isfinite(g); });
    if (gaps.size() < 2) return 0.0f;
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    return gaps[gaps.size() / 2];
}

// --- adjacency ------------------------------------------------------------------------------------------

std::vector<AdjacentGuides> find_adjacent_guides(const CurveSet& guides, const Surface& scalp, float max_gap, Progress* progress)
{
    const size_t nc = guides.num_curves();
    std::vector<AdjacentGuides> out(nc);
    const GuidePointIndex index(guides);
    if (!(max_gap > 0.0f)) max_gap = kAutoGapFactor * typical_guide_gap(guides, index);
    const auto P = guides.positions();
    ProgressStep step(progress, "partition: neighbours", int64_t(nc));
    parallel_for(int64_t(nc), 4, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            out[c].source = int32_t(c);
            const IndexRange r = guides.points_of(c);
            if (r.size() < 2) continue;
            const auto pts = P.subspan(r.begin, r.size());
            const auto cum = cumulative_lengths(pts);
            const auto tangents = polyline_tangents(pts);
            // Votes per side: guide -> (stations won, summed distance). std::map keeps the order fixed.
            std::map<int32_t, std::pair<int, double>> votes[2];
            for (int k = 0; k < kAdjacencyStations; ++k) {
                const double s = cum.back() * (k + 0.5) / kAdjacencyStations;
                const float3 p = point_at_length(pts, cum, s);
                const float3 n = scalp.normal(p);
                const float3 left = left_direction(n, tangent_at_length(pts, cum, tangents, s));
                const auto hits = index.nearest_on_sides(p, n, left, int32_t(c), max_gap);
                for (int side = 0; side < 2; ++side) {
                    if (hits[side].guide < 0) continue;
                    auto& v = votes[side][hits[side].guide];
                    v.first += 1;
                    v.second += hits[side].distance;
                }
            }
            // Per side, the guide nearest at the most stations (ties: smaller summed distance; the map
            // visits guides in index order, so the lower index wins a full tie).
            auto best = [&](int side, int32_t exclude, int* won) {
                int32_t pick = -1;
                int best_votes = 0;
                double best_sum = INFINITY;
                for (const auto& [g, v] : votes[side]) {
                    if (g == exclude) continue;
                    if (v.first > best_votes || (v.first == best_votes && v.second < best_sum)) {
                        best_votes = v.first;
                        best_sum = v.second;
                        pick = g;
                    }
                }
                if (won) *won = best_votes;
                return best_votes >= kAdjacencyMinVotes ? pick : -1;
            };
            int won_left = 0, won_right = 0;
            int32_t left = best(0, -1, &won_left), right = best(1, -1, &won_right);
            // A neighbour that bends round the source can win both sides: it stays where it won more.
            if (left >= 0 && left == right) {
                if (won_left >= won_right) right = best(1, left, nullptr);
                else left = best(0, right, nullptr);
            }
            out[c].left = left;
            out[c].right = right;
            step.advance(1);
        }
    });
    return out;
}

}  // namespace groom
