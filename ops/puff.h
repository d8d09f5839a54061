// puff: Izzy's afro puffs (talk, Sec. 3.2 "Curls with Graphic Shapes"): a clean spherical silhouette.
// N rows x M columns of guide curves rooted within a radius on the scalp, each ending exactly on a
// perfect mathematical sphere, then curls rooted at random within the same radius that follow the
// guides (ops/generate.h) and are curled with the curl op.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/curl.h"
#include "ops/generate.h"

#include <cstdint>

namespace groom {

/// The tip's tangent length of a puff guide at the top of the cap, as a fraction of its root-to-tip
/// distance: long enough that the guide arrives along the sphere's normal (the silhouette). It
/// shrinks with the tip's height on the cap, to nothing at and below the equator.
inline constexpr float kPuffTipHandle = 0.4f;

struct PuffParams {
    /// The region on the scalp: roots lie within `radius` of c0, the point of the scalp closest to
    /// `center` (--center X,Y,Z, --radius r; scene units, radius > 0).
    float3 center{};
    float radius = 0.0f;
    /// The sphere the silhouette follows (--sphere-center X,Y,Z, --sphere-radius R; R > 0).
    float3 sphere_center{};
    float sphere_radius = 0.0f;
    /// Guides: rows x cols (--rows, --cols; each 1..256).
    int rows = 5;
    int cols = 5;
    /// Half-angle, degrees, of the cap of the sphere the guide tips cover, around the axis from c0 to
    /// the sphere centre: the part of the sphere facing away from the head (--cap-angle; (0, 180)).
    float cap_angle = 110.0f;
    /// Points per guide, evenly spaced in arc length (--guide-points; >= 4).
    int guide_points = 16;
    /// Length of each guide's root tangent (along the scalp normal) as a fraction of its root-to-tip
    /// distance; larger bends the guides later (--bend; (0, 1]). The tip's tangent (along the sphere's
    /// normal) is kPuffTipHandle of the distance times the tip's height on the cap (see puff_guides).
    float bend = 0.4f;
    int64_t first_id = 0;   ///< guide ids are first_id .. first_id + rows*cols - 1 (--first-id), >= 0;
                            ///< hair ids follow on from the last guide id

    // --- Hairs (Sec. 3.2: "curls randomly rooted within the radius on the scalp that follow the
    // directionality of the sphere curves").
    int64_t hairs = 0;       ///< curls to grow, >= 0 (--hairs); 0 = guides only
    int hair_points = 24;    ///< points per hair centreline before curling, >= 4 (--hair-points)
    int neighbours = 4;      ///< guides blended per hair (--neighbours), >= 1
    float power = 2.0f;      ///< inverse-distance exponent of that blend (--power), > 0
    /// Every `groom curl` option; curl.seed also seeds the hair roots. Puff always curls the whole
    /// centreline (preserve_length is ignored: a length-preserving curl would stop short of the
    /// sphere and break the silhouette).
    CurlParams curl;

    /// Throws InvalidParam naming the option, the value and the valid range.
    void validate() const;
};

/// @brief The rows x cols sphere guides of a puff (Sec. 3.2).
///
/// The region's disc (radius `radius` in the tangent plane at c0) is divided into rows x cols
/// equal-area cells by Shirley and Chiu's concentric square-to-disc map; each cell centre, projected
/// onto the scalp, roots one guide. The same cell, mapped onto the sphere's cap by the equal-area
/// map 1 - cos(theta) = rho^2 (1 - cos(cap_angle)), gives its tip direction d, so tips cover the cap
/// evenly and keep the grid's neighbourhoods (no guide crosses another). Each guide is the cubic
/// Bezier root -> tip with root tangent the scalp normal (bend x the root-to-tip distance) and tip
/// tangent d (kPuffTipHandle x that distance x max(0, d . axis): along the normal at the top of the
/// cap, from the base toward its rim), resampled to
/// guide_points points evenly spaced in arc length; its tip is sphere_center + sphere_radius * d
/// (on the sphere to float rounding). Interior points inside the scalp are moved onto it (keep_outside,
/// fields/keep_outside.h, clearance 0).
/// Writes point P, point `width` (curl.widths), curve int64 `id`, int32 `kind` (0 = guide), int32
/// `guide` (its own index), and
/// the detail attributes `groom gather` reads: float3 `puff_base` (c0), float `puff_radius`, float3
/// `puff_sphere_center`, float `puff_sphere_radius`, float `puff_cap_angle` (degrees).
/// Throws InvalidParam (params; a tip that would lie inside the scalp), InvalidGeometry (the region
/// has no scalp within `radius` of c0 along the grid, or guides would cross).
CurveSet puff_guides(const Surface& scalp, const PuffParams& params, Progress* progress = nullptr);

/// What puff() makes: the guides (kind 0) and the curled hairs (kind 1).
struct PuffResult {
    CurveSet guides;
    CurveSet hairs;
};

/// @brief A whole afro puff (Sec. 3.2): puff_guides(), then params.hairs curls.
///
/// Hair roots are drawn area-uniformly from the scalp within `radius` of c0 (by `sample`, seeded
/// from curl.seed); each hair's centreline is interpolated from its nearest guides by
/// generate_at_roots() (so it follows them), its tip is then moved to its root's point of the cap
/// (PuffCap::tip_for: tips cover the cap as evenly as the roots cover the base, out to its rim) by a
/// smooth warp (p += (tip' - tip) s^2 for arc-length fraction s, which keeps the root and the root
/// direction), and it is curled by curl(); curled points that
/// fall inside the scalp are then moved onto it (keep_outside on the curves, clearance 0: roots stay).
/// A curl moves points at most curl_reach(curl) off the centreline, so every hair tip lies within
/// that distance of the sphere.
/// Hairs: point P, `width` (curl.widths tapered over each curled hair; the defaults when unset) (+ the
/// curl op's point `shape`, `cycle`), curve `id` (after the guides' ids),
/// `kind` = 1, `guide` = nearest guide; detail `hair_type`. No hair point lies inside the scalp.
/// Throws as puff_guides(), generate() and curl() do.
PuffResult puff(const Surface& scalp, const RootSampler& sample, const PuffParams& params, Progress* progress = nullptr);

/// The farthest a curl with `params` moves a point from its centreline, scene units: the largest
/// amplitude (the hair type's radius x units_per_cm x 1.2 when unset) times the largest radius of a
/// unit cross-section (2^(1/2 - 1/n) for a Lame curve with exponent n > 2, else 1), plus the largest offset.
float curl_reach(const CurlParams& params);

/// The equal-area map from a puff's base onto its sphere's cap (Sec. 3.2's "tips cover the cap"):
/// a point of the base's disc (the tangent plane at the base, `radius` across) at polar radius rho of
/// the radius and azimuth phi ends at the sphere's point at polar angle theta around the axis from the
/// base to the sphere's centre, 1 - cos(theta) = rho^2 (1 - cos(cap_angle)), azimuth phi. Guides take
/// their tips from it (puff_guides); so do the hairs, from their roots (puff) or from the point of
/// the base whose guides they follow (gather): blending guides only ever reached the outermost
/// guides' tips, so every hair rooted outside their ring ended on that one circle, a sharp edge
/// around the ball with bare sphere below it.
struct PuffCap {
    float3 base, u, v;     ///< the disc's centre (on the scalp) and its axes in the tangent plane
    float3 axis, ut, vt;   ///< the cap's axis and the axes its azimuth is measured on
    float radius = 0.0f;
    double cos_cap = -1.0;
    float3 sphere_center;
    float sphere_radius = 0.0f;

    /// The cap of a puff based at `base` (a scalp point), as puff_guides lays it out.
    static PuffCap make(const Surface& scalp, const float3& base, float radius, const float3& sphere_center, float sphere_radius,
                        float cap_angle_degrees);
    /// The sphere point of the disc point (dx, dy), in units of the radius (|(dx, dy)| <= 1).
    float3 tip_at(double dx, double dy) const;
    /// The sphere point for a hair following the guides at base point x, whose blended tip is
    /// `blended`: the polar angle from x's distance from the centre in the disc (clamped to the rim),
    /// the azimuth the blended guides give it (so it never depends on how the disc's axes were
    /// chosen, which a later transform of the puff may change; x's own azimuth where the blended tip
    /// lies on the axis).
    float3 tip_for(const float3& x, const float3& blended) const;
    /// Each curve's tip warped (warp_tips_to) to tip_for(follows[c], its tip); `follows` (#curves,
    /// or empty for each curve's root): the base point whose guides it follows.
    void warp_onto(CurveSet& centres, std::span<const float3> follows = {}) const;

private:
    /// The sphere point at the disc radius rho (polar angle by the equal-area map) toward the unit
    /// direction `side`, perpendicular to the axis.
    float3 at(double rho, const float3& side) const;
};

/// Moves each curve's tip to targets[c] (#curves) by the warp p += (tip' - tip) s^2, s the arc-length
/// fraction, which keeps the root and the root direction. Curves with fewer than 2 points are left.
void warp_tips_to(CurveSet& centres, std::span<const float3> targets);

/// Moves each curve's tip onto the sphere (C, R) along the direction from C (for a tip at C: along the
/// curve's root-to-tip direction) by the warp p += (tip' - tip) s^2, s the arc-length fraction, which
/// keeps the root and the root direction. Curves with fewer than 2 points are left as they are.
void warp_tips_to_sphere(CurveSet& centres, const float3& C, float R);

/// Smallest distance between two different curves of `curves` (segment to segment), scene units;
/// +infinity with fewer than two curves. O(points^2): for checks and tests, not big grooms.
double min_curve_separation(const CurveSet& curves);

}  // namespace groom
