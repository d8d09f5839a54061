// Neighbour search between guide curves, for `groom partition` (talk, Sec. 2.2): which guide lies
// beside a source guide on its left and on its right, and the exact closest point on a guide to a
// query point. Both walk a kd-tree outward from the query (PointIndex, fields/point_index.h).
#pragma once

#include "kernel/curve_set.h"
#include "kernel/progress.h"

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace groom {

class Surface;

/// Exact closest-point queries on one polyline (a guide's points, root to tip).
class PolylineNearest {
public:
    /// Indexes `pts` (copied). An empty polyline answers every query with segment -1.
    explicit PolylineNearest(std::span<const float3> pts);
    ~PolylineNearest();
    PolylineNearest(PolylineNearest&&) noexcept;
    PolylineNearest& operator=(PolylineNearest&&) noexcept;

    struct Hit {
        float3 point;                                         ///< closest point on the polyline
        int64_t segment = -1;                                 ///< segment [segment, segment+1]; -1 when empty
        float t = 0.0f;                                       ///< fraction along that segment, [0, 1]
        float distance = std::numeric_limits<float>::infinity();  ///< |q - point|, scene units
    };

    /// The point of the polyline closest to `q`, exact (not just the nearest vertex): the kd-tree over
    /// the vertices is walked outwards from q and the segments at each vertex are tested until no
    /// farther vertex can start a closer segment (a segment's closest point lies within half the
    /// longest segment of one of its ends). Ties go to the lower segment. Thread-safe.
    Hit closest(const float3& q) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Which side of a source guide an offset lies on, in the scalp's tangent plane.
/// `offset` = neighbour point - source point; `normal` = unit scalp normal at the source point;
/// `left` = unit normal x tangent (the left hand looking from root to tip with the normal up).
/// Returns 0 (left), 1 (right) or -1 when the offset is not beside the source: when it points more
/// than 60 degrees out of the tangent plane (through the head: a guide on the far side of the skull)
/// or more than 45 degrees from the lateral axis (a guide ahead of or behind the source; the nearest
/// point of a guide running beside is square to the source, up to half its point spacing).
int classify_side(const float3& offset, const float3& normal, const float3& left);

/// The points of every guide in one kd-tree, each tagged with its curve, for finding the nearest
/// other guide on each side of a point.
class GuidePointIndex {
public:
    explicit GuidePointIndex(const CurveSet& guides);
    ~GuidePointIndex();
    GuidePointIndex(GuidePointIndex&&) noexcept;
    GuidePointIndex& operator=(GuidePointIndex&&) noexcept;

    struct SideHit {
        int32_t guide = -1;                                       ///< -1: nothing on that side
        int64_t point = -1;                                       ///< point index in the guides' CurveSet
        float distance = std::numeric_limits<float>::infinity();  ///< scene units
    };

    /// Nearest point of any guide other than `exclude` on the left ([0]) and right ([1]) of `p`, as
    /// decided by classify_side(point - p, normal, left). `max_gap` > 0 ignores points farther than
    /// that (scene units); 0 = no limit. Thread-safe.
    std::array<SideHit, 2> nearest_on_sides(const float3& p, const float3& normal, const float3& left, int32_t exclude,
                                            float max_gap = 0.0f) const;

    /// Nearest point of any guide other than `exclude`, on any side. Thread-safe.
    SideHit nearest_other(const float3& p, int32_t exclude) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The typical distance between neighbouring guides: the median over guides (with >= 2 points) of
/// the distance from the guide's arc-length midpoint to the nearest point of any other guide, scene
/// units. 0 when fewer than two guides have points.
float typical_guide_gap(const CurveSet& guides, const GuidePointIndex& index);

/// find_adjacent_guides() with max_gap 0 searches only this many typical gaps away, so a guide at the
/// edge of the layout does not walk every point of the groom looking for a neighbour it lacks.
inline constexpr float kAutoGapFactor = 4.0f;

/// Unit tangent of a polyline at arc length `s` (clamped), blending the vertex tangents of
/// polyline_tangents() across the segment that holds s. `cumulative` from cumulative_lengths(pts).
float3 tangent_at_length(std::span<const float3> pts, std::span<const double> cumulative, std::span<const float3> tangents,
                         double s);

/// The left direction at a point of a guide: unit normal x (tangent projected onto the tangent
/// plane). Falls back to any perpendicular of the normal when the guide leaves the scalp straight up.
float3 left_direction(const float3& normal, const float3& tangent);

/// A source guide and its neighbours (guide indices, -1 for none).
struct AdjacentGuides {
    int32_t source = -1;
    int32_t left = -1;   ///< side 0: on the normal x tangent side
    int32_t right = -1;  ///< side 1
};

/// Sample stations along each guide used to vote for its neighbours.
inline constexpr int kAdjacencyStations = 32;
/// Stations a guide must be the nearest on a side at to be the neighbour there: a guide that only
/// comes near the source at one end (guides crossing or meeting near the nape) is not beside it.
inline constexpr int kAdjacencyMinVotes = kAdjacencyStations / 4;

/// @brief The closest guide on either side of every guide (talk, Sec. 2.2: "the closest adjacent
/// curves on either side").
/// At kAdjacencyStations points spread evenly in arc length along each guide, the nearest other
/// guide on each side is found (GuidePointIndex::nearest_on_sides, tangent from the polyline, normal
/// from `scalp`); per side the guide nearest at the most stations wins (ties: smaller summed
/// distance, then lower index) if it is nearest at kAdjacencyMinVotes stations or more. A guide at
/// the edge of the groom gets -1 on its open side.
/// @param max_gap  scene units; > 0 ignores guides farther than this; 0 = automatic, kAutoGapFactor
///                 times typical_guide_gap() (no limit when that is 0)
/// @return one entry per guide, in guide order (guides with < 2 points get none on either side)
std::vector<AdjacentGuides> find_adjacent_guides(const CurveSet& guides, const Surface& scalp, float max_gap = 0.0f,
                                                 Progress* progress = nullptr);

}  // namespace groom
