// cornrow_guides: the hand-sculpted source curves of a cornrow style, made procedurally so the demo
// (and users without a groom package) can start from a scalp alone. N guides run front to back over
// the scalp like the rows of a fan: guide i lies in the plane that contains the front-to-back axis
// `pivot` below `center` and leans sideways by phi_i (evenly spaced in [-spread, spread]). Where
// that plane cuts a sphere around the cranium is a circle; the guide is its arc from the hairline
// at the front over the crown down to the nape. Every point is then projected onto the scalp
// (Surface::closest_point; where that jumps across a fold, along rays from the circle's centre
// instead: CornrowGuides::rows), lifted by `offset` along the scalp normal and re-spaced evenly in
// arc length. pivot = 0 gives great circles (rows meeting at the front and back); a pivot below the
// radius gives rows that converge to where its axis pierces the sphere; the default, twice the
// radius with a 24 degree spread, gives nearly parallel straight-back rows whose outer ones run
// above the ears (7.5 and 55 had every row end in one point at the nape: a trial). With a hairline,
// straight-back rows are instead walked on the scalp along their planes' cuts and steered to end
// side by side along the hairline round the back of the head (see cornrow_guides' doc).
// Optionally each guide continues past the nape as a free-hanging tail (the loose ends of the
// braids), which the demo curls.
//
// Frame: `up` and `forward` (the direction the face looks), by default +Y up and the face towards +Z
// (the convention of `groom head`). Below, Y and Z name those two axes and X = Y x Z.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "ops/hair_region.h"

namespace groom {

struct CornrowGuidesParams {
    int count = 8;                    ///< guides, [1, 256]
    float3 center{0.0f, 3.0f, -1.0f}; ///< centre of the sphere paths are laid on (default: the default head's cranium)
    float3 up{0.0f, 1.0f, 0.0f};      ///< the head's up direction; any length > 0
    /// The direction the face looks; any length > 0, at least 10 degrees from `up` (only its part
    /// perpendicular to `up` is used).
    float3 forward{0.0f, 0.0f, 1.0f};
    float radius = 10.0f;             ///< radius of that sphere, scene units; > 0 (roughly the cranium's)
    /// Depth of the fan's axis below center, scene units; >= 0, with pivot x sin(spread) < radius
    /// (every row's plane cuts the sphere). Below radius, rows meet (and would cross) where the axis
    /// pierces the sphere, at elevation -asin(pivot / radius): back_angle must stay above it. From
    /// radius on, the axis misses the sphere and the rows never meet (nearly parallel rows).
    float pivot = 20.0f;
    float spread = 24.0f;             ///< the outermost guides lean this far from vertical, degrees; [0, 90)
    // Angles are measured in each guide's plane around its circle's centre, from the front
    // horizontal (+Z) upwards; for the middle guide they are plain elevations.
    float front_angle = 12.0f;        ///< where the middle guide starts (the hairline), degrees; (-90, 90)
    float hairline_curve = 28.0f;     ///< the outermost guides start this many degrees further back (hairline round the temples); [0, 90)
    float back_angle = -40.0f;        ///< where guides end at the back (the nape; negative = below the horizontal), degrees; (-90, 90)
    int samples = 48;                 ///< points per guide, >= 2
    float offset = 0.0f;              ///< height of the guides above the scalp, scene units; >= 0
    float tail_length = 0.0f;         ///< length of the free tail past the nape, scene units; >= 0 (0 = no tails)
    int tail_samples = 24;            ///< points per tail, >= 2
    /// With a hairline: a row ends where its neighbours come within this fraction of their spacing
    /// over the crown, if that is before the hairline, so converging rows stop short of each other
    /// instead of piling into one point at the nape; (0, 1].
    float min_spacing = 0.3f;
    /// Throws InvalidParam naming the option, value and range. `hairline`: the rows will run between
    /// a hairline's ends instead (cornrow_guides with a region that has one), so front_angle,
    /// hairline_curve and back_angle are not used and back_angle need not stay above the rows' meeting point.
    void validate(bool hairline = false) const;
};

struct CornrowGuides {
    /// Curves root (hairline) to tip (nape). Curve attributes: `id` (int64, = index) and `guide`
    /// (int32, = index, from the -X side to the +X side: left to right seen from the front).
    CurveSet guides;
    /// One tail per guide when tail_length > 0, rooted at its guide's last point, leaving along the
    /// guide's end direction and bending down under gravity; each step is kept `offset` out of the
    /// scalp (keep_outside, fields/keep_outside.h) before the next. Same `id` and `guide` as its
    /// guide. Empty otherwise.
    CurveSet tails;
    /// Per guide, how its arc was laid on the scalp. Each arc point goes to its nearest scalp
    /// point, unless that path jumps across a fold (largest chord over 4 times the median: the
    /// arc passes under a brow or a ridge, and the chord of the jump cuts through the head). Then
    /// the row goes on the outermost scalp along rays from its circle's centre, if that jumps less.
    struct Row {
        bool along_rays = false;  ///< laid along the rays
        float jump = 0.0f;        ///< where the path used still jumps: its largest step, scene units (else 0)
        /// With a hairline: the length cut off the row's ends where, laid on the scalp, it came
        /// within min_spacing of its crown spacing of a neighbouring row (scene units; else 0).
        float trimmed = 0.0f;
        /// Walked on the scalp and steered to its end on the hairline (straight-back rows with a
        /// hairline, see cornrow_guides); then along_rays and jump are false and 0.
        bool walked = false;
    };
    std::vector<Row> rows;
};

/// Makes the guides on `scalp` (any Surface: an exact sphere in tests, a ScalpField for real heads).
/// With a `region` that has a hairline, every row runs from the hairline at the front to the
/// hairline at the nape instead of between front_angle (+ hairline_curve) and back_angle:
/// - straight-back rows (pivot >= radius, 3 rows or more) are walked on the scalp both ways from
///   the highest point of their arc along the cut of their plane with it, to the hairline, the
///   back walk steered so the rows end on the hairline evenly spaced in arc length from 120
///   degrees round from the face on one side to 120 on the other (Row::walked); a row whose walk
///   never leaves the hairline keeps its arc;
/// - other rows' arcs are laid as far as min_spacing lets them (neighbouring rows no closer than
///   that fraction of their crown spacing) and cut where they leave the hairline (found to 1e-4 of
///   the arc's angle), keeping the part through the row's highest point.
/// Either way rows that come closer than min_spacing on the scalp are then cut (Row::trimmed).
/// Throws InvalidParam, and InvalidGeometry when a row never enters the hairline.
CornrowGuides cornrow_guides(const Surface& scalp, const CornrowGuidesParams& params, const HairRegion* region = nullptr);

}  // namespace groom
