// generate: from a few guide curves to a full groom. Roots are scattered area-uniformly on the scalp,
// each root takes a shape interpolated from its nearest guides, and the result is pushed out of the
// scalp. The general step behind `groom generate` and behind the hairs of `groom puff` (talk, Sec. 3.2:
// "curls randomly rooted within the radius on the scalp that follow the directionality of the sphere
// curves").
#pragma once

#include "fields/scalp_field.h"
#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/hair_region.h"
#include "ops/hair_widths.h"

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace groom {

/// Draws `count` samples (position and surface normal) area-uniformly on the scalp among the parts of it near the ball
/// (center, radius), deterministically for `seed`. It may return points outside the ball (a face
/// straddling the sphere, say) and fewer than asked for; generate() keeps only those inside the ball
/// and asks again with fresh seeds until it has enough, so any superset sampler stays area-uniform.
/// The CLI wraps ScalpField::sample_ball; tests wrap an exact spherical-cap sampler.
/// The normal is the sampler's (a face normal for a mesh): exact where the sample lies, which a
/// level set's gradient need not be on the zero crossing itself.
using RootSampler = std::function<std::vector<SurfaceSample>(const float3& center, float radius, int64_t count, uint64_t seed)>;

/// ScalpField::sample_ball as a RootSampler (the sampler every command uses). `scalp` must outlive it.
inline RootSampler scalp_root_sampler(const ScalpField& scalp)
{
    return [&scalp](const float3& center, float radius, int64_t count, uint64_t seed) {
        return scalp.sample_ball(center, radius, count, seed);
    };
}

struct GenerateParams {
    int64_t count = 1000;     ///< roots to scatter, >= 1 (--count)
    int neighbours = 4;       ///< guides blended per root, >= 1 (--neighbours)
    float power = 2.0f;       ///< inverse-distance weight exponent, > 0 (--power)
    int points = 0;           ///< points per generated curve, >= 2; 0 = keep the guides' count when they
                              ///< all share one, else the largest guide count (--points)
    /// Where roots go. A ball (--region X,Y,Z,R) when region_radius > 0; otherwise the guides' own
    /// footprint: scalp within footprint_scale * D of some guide root, D being the largest distance
    /// from a guide root to its nearest other guide root (the coarsest guide spacing).
    float3 region_center{};
    float region_radius = 0.0f;     ///< scene units; 0 = use the footprint
    float footprint_scale = 1.0f;   ///< > 0 (--footprint-scale)
    /// Roots whose scalp normal is more than this many degrees from their nearest guide's root
    /// normal are not used (ears, the underside of a fold: scalp the guides do not describe, where a
    /// shape turned through so large an angle would point anywhere); (0, 180], 180 = keep all
    /// (--max-angle). 35: between neighbouring guides a head turns its normal by 25 degrees at most
    /// (Sintel: 99% of the roots of the ponytail head's and Ratboy's guides within 21); at 75 the
    /// roots on Sintel's ears took their guides' shapes turned sideways (185 of 30,000 hairs).
    float max_angle = 35.0f;
    float clearance = 0.0f;   ///< points found inside the scalp are pushed out to this distance, scene units, >= 0
    uint64_t seed = 0;        ///< root scattering (--seed)
    int64_t first_id = 0;     ///< curve ids are first_id, first_id+1, ..., in root order (--first-id), >= 0
    /// Where hair grows (--hairline, --parting): roots only where region->haired(); null = anywhere.
    /// Not owned; must outlive the call.
    const HairRegion* region = nullptr;
    /// Point `width` (--root-width, --tip-width): unset keeps the guides' widths (each point takes
    /// its nearest guide's, as other point attributes do), else the human-hair defaults.
    HairWidths widths;
    /// Scene units per centimetre, for the default widths only (--units-per-cm); > 0.
    float units_per_cm = 1.0f;
    /// Make only hairs [range_begin, range_end) of the count (a shard of a farm job): the same
    /// curves, ids and every column as those of the whole run; range_end < 0 = to the end.
    int64_t range_begin = 0, range_end = -1;

    /// Throws InvalidParam naming the option, the value and the valid range.
    void validate() const;
};

/// @brief Scatters params.count roots on the scalp inside the region (or footprint) and grows a curve
/// from each, interpolated from the guides (see generate_at_roots).
/// @param guides  root-to-tip curves with >= 2 points each; at least one guide, two for the footprint.
/// @param scalp   the surface roots lie on; normals orient the blend, points inside are pushed out.
/// @param sample  area-uniform scalp sampler (see RootSampler).
/// Reads point P of the guides. Writes point P, point `width` (GenerateParams::widths), curve int64
/// `id`, curve int32 `guide` (nearest guide);
/// every other curve attribute of the nearest guide is carried, and point attributes from the nearest
/// guide's point at the same fraction of arc length.
/// Throws InvalidParam (bad params, too few guides), InvalidGeometry (a guide with < 2 points or no
/// length), LimitExceeded (the region holds too little scalp to find the roots).
CurveSet generate(const CurveSet& guides, const Surface& scalp, const RootSampler& sample, const GenerateParams& params,
                  Progress* progress = nullptr);

/// @brief generate(), a block of hairs at a time, for an output written as it is made and never held
/// whole (kernel/curve_blocks.h). The roots are scattered once; each block is generate_at_roots()
/// over its range of them, so the blocks laid end to end are generate()'s output bit for bit.
/// @param block_points  a block ends at the first hair that brings it to this many points
/// @param start  called once, before the first block, with every output curve's point count
/// @param emit   called with each block in order, one call at a time, possibly from another thread
///               while the next block is grown
/// Throws as generate() does; the memory check counts one block.
void generate_blocks(const CurveSet& guides, const Surface& scalp, const RootSampler& sample, const GenerateParams& params,
                     Progress* progress, int64_t block_points, const std::function<void(std::span<const int64_t> counts)>& start,
                     const std::function<void(const CurveSet& block)>& emit);

/// The roots generate() would use: params.count samples, area-uniform inside the region (or
/// footprint) among those within params.max_angle of their nearest guide's root normal (taken from
/// `scalp`) and haired in params.region (when given), in a deterministic order for params.seed.
std::vector<SurfaceSample> scatter_roots(const CurveSet& guides, const Surface& scalp, const RootSampler& sample,
                                         const GenerateParams& params);

/// @brief One curve per root, shaped from the K = params.neighbours guides whose roots are nearest
/// (a kd-tree search, PointIndex in fields/point_index.h).
///
/// Each guide is first resampled to the common point count (params.points). A guide's shape is its
/// points relative to its root, expressed in its root frame (normal = scalp normal at the guide root);
/// at a new root x with normal n (normals[i], or scalp.normal(x) when `normals` is empty) that frame is carried over by the minimal rotation taking the guide's
/// normal onto n, so shapes follow the curvature of the scalp. Shapes are blended with Franke-Little
/// inverse-distance weights w_g = ((d_{K+1} - d_g) / (d_{K+1} d_g))^power (d_{K+1}: the next guide
/// out, so a guide's weight falls to zero as it leaves the K nearest and shapes vary continuously).
/// A root exactly on a guide's root (distance 0) takes that guide alone, copied bit for bit. Points
/// (all but the root) closer to the scalp than params.clearance are moved out to it by keep_outside
/// (fields/keep_outside.h: up to 16 moves each, the margin a millionth of the groom's extent,
/// doubling), and a run of them that the moves folded back is laid again over the scalp as a whole
/// (fields/drape_runs.h).
/// With `blend_at` (#roots, or empty): hair i takes its guides and weights at blend_at[i] instead of
/// at its root, and their shapes are carried to its root and normal as above (gather: a hair entering
/// a puff at its base's rim follows the guides of a point inside the base, so the gathered hair fills
/// the ball instead of all following the rim's guides as one sheet).
/// Uses params: neighbours, power, points, clearance, first_id. Attributes as for generate().
CurveSet generate_at_roots(const CurveSet& guides, const Surface& scalp, std::span<const float3> roots,
                           std::span<const float3> normals, const GenerateParams& params, Progress* progress = nullptr,
                           std::span<const float3> blend_at = {});

}  // namespace groom
