// partition: the edge hairs between braids (talk, Sec. 2.2, "Creating Partitions between Braids").
// From the same guide curves the braids follow, every guide (the source) gets short segments on
// each side, rooted on the scalp part-way to the adjacent guide and ending on the source, so the hair
// between two braids reads as parted down the middle and pulled into each braid.
#pragma once

#include "ops/hair_region.h"

#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/adjacency.h"
#include "ops/braid.h"
#include "ops/float_range.h"
#include "ops/hair_widths.h"

#include <cstdint>
#include <vector>

namespace groom {

class Surface;

/// Where the segments of one side of a source converge.
enum class CentroidMode {
    Stations,  ///< no grouping: each segment ends at its own station on the source (the default)
    Every,     ///< every `every` consecutive stations form a group ending at the group's middle station
    Knots,     ///< each segment joins the nearest braid knot centre (braid_knot_parameters(knots, length))
    Points,    ///< centroids given per guide (`centroid_points`); each segment joins the nearest one
};

/// A centroid given by the user: a point of guide `guide` at normalised arc length `u` (0 root, 1 tip).
struct CentroidPoint {
    int32_t guide = -1;
    float u = 0.0f;
};

/// With neither count nor spacing: segments kAutoSpacingPerGap to the typical gap between guides
/// along each source.
inline constexpr float kAutoSpacingPerGap = 200.0f;
/// The automatic count a side when there is no gap to measure (fewer than two guides).
inline constexpr int kAutoCountWithoutGap = 24;

struct PartitionParams {
    /// Where roots sit between the source (0) and the nearest point of the adjacent guide (1), drawn
    /// per segment from [lo, hi]; 0 <= lo <= hi <= 1. Sec. 2.2 roots every segment at the midpoint
    /// ({0.5, 0.5}); on a head that reads as hair growing densest along the parting, with bare scalp
    /// beside each braid (a trial's pictures). The default spreads the roots over the strip between
    /// the braid and the parting, denser toward the parting (see partition()), and leaves the middle
    /// 6% bare: the parting line.
    FloatRange mediate{0.1f, 0.47f};
    /// Segments per side of each source, spread evenly in arc length (>= 1). Exclusive with spacing.
    /// Both 0 (the default): a segment every kAutoSpacingPerGap-th of the typical gap between guides
    /// (typical_guide_gap), about 2,500 a side on a head of cornrows, enough to read as hair rather
    /// than as lines (24 a side did: a trial's pictures); kAutoCountWithoutGap a side for one guide.
    int count = 0;
    /// Arc length between segments along the source, scene units (> 0) when count is 0.
    float spacing = 0.0f;
    /// Points per segment (>= 2): the root, points that follow the scalp, the end on the source.
    int samples = 8;
    /// Point `width`, tapered root to tip (--root-width, --tip-width; --width W for both); unset ends
    /// take the human-hair defaults (ops/hair_widths.h).
    HairWidths widths;
    /// Scene units per centimetre, for the default widths (a head in metres: 0.01); > 0.
    float units_per_cm = 1.0f;
    /// Random shift of each station along the source, as a fraction of the spacing; [0, 1].
    float jitter = 0.0f;
    uint64_t seed = 0;
    /// Neighbours farther than this are ignored (scene units), and a station whose closest adjacent
    /// point is farther than this gets no segment. 0 = automatic: the neighbour search reaches
    /// kAutoGapFactor typical gaps between guides (typical_guide_gap) and no station is dropped.
    float max_gap = 0.0f;
    /// Stations where the source is more than this above the scalp get no segment (e.g. a braid
    /// hanging free past the nape), scene units; 0 = no limit.
    float max_height = 0.0f;

    CentroidMode centroids = CentroidMode::Stations;
    /// With centroids: how far a group's segments converge on its centroid, [0, 1]. 1 = all end on
    /// the centroid (the talk's); 0 = each ends at its own station. Between, the ends spread over
    /// (1 - converge) of the group's span around the centroid, so the hair combs into each knot.
    float converge = 0.6f;
    int every = 0;                               ///< stations per group for CentroidMode::Every (>= 1)
    std::vector<CentroidPoint> centroid_points;  ///< for CentroidMode::Points; guides absent get Stations
    /// For CentroidMode::Knots: the knot placement of `groom braid` (frequency or knot_length, and the
    /// knot_bias / knot_density remap), so the edge hairs meet the braid at its knots. A guide too
    /// short for one knot (F < 1/2) gets Stations.
    BraidParams knots;

    /// Neighbours chosen by the user; empty = found by find_adjacent_guides(). When given, only the
    /// sources listed get segments.
    std::vector<AdjacentGuides> adjacent;

    /// Where hair grows (--hairline, --parting): a segment whose root is not haired there is not
    /// made (past the hairline, on a parting's bare line). Null = everywhere. Not owned.
    const HairRegion* region = nullptr;

    /// Throws InvalidParam naming the option, the value and the valid range. Guide indices (in
    /// `adjacent`, `centroid_points`) are checked by partition(), which knows the guide count.
    void validate() const;
};

/// @brief Edge hairs between braids (talk, Sec. 2.2).
/// For each source guide and each side with an adjacent guide, stations are spread along the source
/// (count, or spacing centred on the source; shifted by jitter). At a station p with closest point q
/// on the adjacent guide (exact polyline closest point, PolylineNearest), the segment's root is
/// scalp.closest_point(lerp(p, q, mediate)) and its end is p, or the group's centroid on the source
/// with CentroidMode::Every/Knots/Points. Between them the segment follows the scalp: each sample of the
/// straight root-to-end line that is lower than a height rising linearly from 0 at the root to the
/// end's height is moved out to that height (keep_outside, fields/keep_outside.h, two moves), so no
/// point but possibly the end (when the source itself dips inside) lies inside the scalp.
///
/// Reads guide point P and every curve attribute. Writes one curve per segment with curve attributes
/// `guide` (int32 source index), `side` (int32, 0 left = normal x tangent side, 1 right), `group`
/// (int32 centroid index along the source; the station index with CentroidMode::Stations), `id`
/// (int64, a hash of the guide's id, side and station, stable when other guides are removed), point
/// `width` (params.widths, root to end); the source's curve attributes carry through (its `id` is replaced). Curves are ordered by
/// guide, then side, then station.
/// Deterministic for any thread count.
/// @throws InvalidParam from params.validate(), or for a guide index out of range in
///         params.adjacent / params.centroid_points; LimitExceeded when the output would exceed
///         2e9 points (checked before anything is allocated).
CurveSet partition(const CurveSet& guides, const Surface& scalp, const PartitionParams& params, Progress* progress = nullptr);

}  // namespace groom
