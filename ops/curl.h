// curl: coil each hair around its own centreline, cycle by cycle, each cycle's cross-section shape
// drawn at random from a tiered shape list (talk, Sec. 3.1 "Cross-Section Combinations"). The hair
// type sets the average frequency x amplitude ratio and the secondary shapes (ops/hair_types.h);
// the shapes themselves are in ops/curl_shapes.h.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/curl_shapes.h"
#include "ops/float_range.h"
#include "ops/hair_widths.h"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace groom {

struct CurlParams {
    /// Walker hair type "2a".."4c": the average frequency x amplitude ratio, the default amplitude
    /// and the dominant and secondary shapes (ops/hair_types.h).
    std::string hair_type = "3a";
    /// Tier A shape (curl_shapes.h index), drawn with probability exactly `uniformity`;
    /// -1 = the hair type's dominant shape.
    int dominant = -1;
    /// Probability that a cycle takes the dominant shape; [0, 1]. Below 1 the allowed shapes must
    /// include one other than the dominant.
    float uniformity = 0.7f;
    /// Allowed shapes (curl_shapes.h indices, no repeats); empty = the whole dictionary.
    std::vector<int> shapes;

    /// Curl radius, scene units, drawn per cycle; {0, 0} = the hair type's radius x units_per_cm,
    /// +-20%. Otherwise 0 <= lo <= hi, hi > 0.
    FloatRange amplitude;
    /// Cycles per scene unit of centreline, drawn per curve; {0, 0} = the hair type's ratio divided
    /// by the middle of the amplitude range. Otherwise 0 < lo <= hi.
    FloatRange frequency;
    /// Rotation of the cross-section about the centreline, in turns (1 = 360 degrees), drawn per curve.
    FloatRange phase{0.0f, 1.0f};
    /// Displacement of each cycle's centre from the centreline, scene units, drawn per cycle (in a
    /// random direction); 0 <= lo <= hi.
    FloatRange offset;
    /// Scene units per centimetre, for the hair-type default amplitude only; > 0.
    float units_per_cm = 1.0f;

    /// Length of centreline kept straight at the root, scene units; >= 0.
    float root_ease = 0.0f;
    /// After the straight part, the curl amplitude ramps smoothly from 0 to full over this many
    /// cycles; >= 0 (0 = no ramp: the root itself is displaced).
    float root_ramp = 1.0f;
    /// Points per curl cycle in the output; 4..256. Curves never get fewer points than they had.
    int samples = 16;
    /// Half-width, in cycles, of the window over which a cycle blends into the next so that shape
    /// changes keep position and tangent continuous; [0, 0.5). 0 = no blending (jumps).
    float blend = 0.15f;
    /// true: the curled hair keeps the input's length (it covers less of the centreline, as real
    /// curls shrink); false: the whole centreline is curled and the hair gets longer.
    bool preserve_length = true;
    /// false: no point `shape` and `cycle` columns (a caller writing a format that cannot hold them,
    /// .hair, spares their memory: a million hairs' curl then fits in twice its output).
    bool labels = true;
    /// Lame exponent, polygon sides, ellipse aspect, rose petals.
    ShapeParams shape;
    /// Point `width` of the output (--root-width, --tip-width): unset keeps the input's widths
    /// (interpolated), else the human-hair defaults times units_per_cm.
    HairWidths widths;
    uint64_t seed = 0;

    /// Throws InvalidParam naming the option (`curl: --uniformity ...`), the value and the range.
    void validate() const;
    /// validate() for an op that curls its own hairs (puff, gather): the messages name that op
    /// ("puff: `type` must be one of ...", not "curl: ...", which a user of puff never typed).
    void validate_for(const std::string& op) const;
};

/// The curl radius the hair type gives when `amplitude` is left at {0, 0}, scene units: its
/// radius in centimetres x units_per_cm (each cycle draws within +-20% of it). Throws InvalidParam
/// for an unknown type.
float curl_default_radius(const CurlParams& params);

/// The tiered shape list of Sec. 3.1, as probabilities over the dictionary.
struct CurlShapeTiers {
    int dominant = 0;                  ///< tier A
    std::vector<int> secondary;        ///< tier B: the hair type's secondary shapes, allowed, not A
    std::vector<int> rest;             ///< tier C: the other allowed shapes
    std::vector<double> probability;   ///< per dictionary index; sums to 1
    std::vector<double> cumulative;    ///< running sum in pick order A, B..., C...
    std::vector<int> order;            ///< dictionary indices in pick order
};

/// Share of (1 - uniformity) given to tier B when tier C is not empty (tier C gets the rest);
/// a tier's share is split evenly among its shapes. When one of B and C is empty the other takes
/// all of 1 - uniformity.
inline constexpr double kCurlTierBShare = 2.0 / 3.0;

/// Builds the tiers for validated params. Throws InvalidParam like CurlParams::validate().
CurlShapeTiers curl_shape_tiers(const CurlParams& params);

/// The shape picked by a uniform number x in [0, 1): tier A exactly when x < uniformity.
int pick_curl_shape(const CurlShapeTiers& tiers, double x);

/// @brief Curl each curve around its own centreline.
/// The centreline is the input curve (a Catmull-Rom through its points when it has >= 4); frames
/// are rotation-minimising from world +X. Each cycle k spans centreline arc length
/// [root_ease + k / F, root_ease + (k + 1) / F); its cross-section is offset_k + amplitude_k *
/// shape_k(t) rotated by the curve's phase; cycles blend over +-blend cycles around each join.
/// Randomness: Rng(seed, curve id, stream), so the result is the same for any thread count and
/// does not depend on the other curves.
/// Reads point P (and width), curve id. Writes point P, point `width` (see CurlParams::widths),
/// point `shape` (int32 dictionary index of
/// the point's cycle), point `cycle` (int32 index of the cycle within the curve, 0 in the straight
/// root), detail `hair_type`. Point counts change (samples per cycle); `width` is interpolated,
/// other point attributes take the nearest input point's value, curve and detail attributes carry.
/// Curves with fewer than 2 points or no length pass through unchanged.
/// @param scalp when given, curled points that fall inside it are pulled back towards the
///   centreline (or pushed out along its normal when the centreline itself is inside): no output
///   point is inside the scalp.
/// Throws InvalidParam (params), LimitExceeded (more than 2^31 output points).
CurveSet curl(const CurveSet& src, const CurlParams& params, const Surface* scalp = nullptr, Progress* progress = nullptr);

/// @brief curl(), a block of curves at a time, for an output written as it is made and never held
/// whole (a million hairs' curl held its input and its output: issue 17's memory aim). Every curve
/// is curled exactly as curl() curls it: the blocks, concatenated, are curl()'s result.
/// @param block_points  a block ends at the first curve that brings it to this many output points
/// @param start  called once, before the first block, with every output curve's point count
/// @param emit   called with each block in order (curves [c0, c1) of the output, nothing else),
///               one call at a time, possibly from another thread while the next block is curled
///               (kernel/curve_blocks.h; an exception it throws ends the run, rethrown here)
/// Throws as curl() does, before `start` is called; the memory check counts the largest block.
void curl_blocks(const CurveSet& src, const CurlParams& params, const Surface* scalp, Progress* progress, int64_t block_points,
                 const std::function<void(std::span<const int64_t> counts)>& start, const std::function<void(const CurveSet& block)>& emit);

}  // namespace groom
