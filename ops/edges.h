// edges: "baby hairs", the short hairs along the hairline that are laid flat on the skin in swirls
// and waves (edges, in the styles of Black hair: Izzy's and Alisha's looks both have them). Roots in a
// band just inside the hairline, along a chosen part of it (by default the forehead, temples and
// sideburns); each hair is a short curve of prescribed curvature walked on the scalp, so an S-swirl
// follows the head's curvature instead of cutting into it, and lies at a small height above the skin.
// No groom tool we know of has them built in; artists draw them by hand.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "ops/hair_region.h"
#include "ops/hair_widths.h"

#include <cstdint>
#include <string>

namespace groom {

/// Which way a hair is laid, relative to the hairline at its root.
enum class EdgeDirection {
    Face,       ///< out of the hairline onto the face (forehead, temples), bending away from the face's middle first
    Along,      ///< along the hairline, away from the face's middle (toward the ears)
    Alternate,  ///< swoops: neighbouring groups lean out of the hairline to one side, then the other
    Random,     ///< swoops leaning to a random side per group
};

/// "face", "along", "alternate", "random"; throws InvalidParam naming `direction` otherwise.
EdgeDirection parse_edge_direction(const std::string& name);
const char* edge_direction_name(EdgeDirection d);

struct EdgesParams {
    float3 up{0.0f, 1.0f, 0.0f};       ///< (--up) the head's up direction: azimuths are measured around it
    float3 forward{0.0f, 0.0f, 1.0f};  ///< (--forward) the direction the face looks: azimuth 0
    /// The part of the hairline that grows edges: azimuths from `from` to `to`, degrees around `up`
    /// from `forward`, positive toward the head's left (up x forward), as `groom hairline` measures
    /// them (forehead 0, temples +-55, sideburns +-80, nape 180); `to` > `from`, `to` - `from` <= 360.
    float from = -80.0f;
    float to = 80.0f;
    /// Roots lie in a band this deep inside the hairline (measured on the scalp, perpendicular to
    /// it), scene units, >= 0; 0 puts every root on the hairline (--depth).
    float depth = 0.25f;
    /// Hairs per scene unit of hairline length, > 0 (--density); ignored when `count` > 0.
    float density = 10.0f;
    int64_t count = 0;  ///< exact number of hairs, spread evenly along the chosen part; 0 = from density (--count)
    /// Arc length of a hair from the hairline to its tip (a root inside the hairline adds its depth),
    /// scene units, > 0 (--length).
    float length = 2.4f;
    /// Swirl radius: the tightest radius of curvature in a swoop (its innermost hair's), scene
    /// units, > 0 (--radius).
    float radius = 0.15f;
    /// Arcs per hair, bending alternately one way and the other: 1 a C, 2 an S, 3 or more a wave;
    /// [1, 16] (--bends).
    int bends = 2;
    EdgeDirection direction = EdgeDirection::Face;  ///< (--direction)
    /// Width of a swoop: the hairline length whose hairs are laid together as one ribbon (same side,
    /// parallel curves), scene units, > 0 (--swoop).
    float swoop = 1.2f;
    /// Random variation, as a fraction, [0, 0.9] (--variation): of each swoop's turning (+-v/2), each
    /// hair's turning (+-v/5) and length (+-v), and its heading (+-v/10 radians).
    float variation = 0.3f;
    /// Height of a hair above the skin, scene units, >= 0: each hair lies at its own height in
    /// [height/2, height], reached one step from its root (--height).
    float height = 0.05f;
    /// Point `width`, tapered root to tip (--root-width, --tip-width; --width W for both); unset ends
    /// take the human-hair defaults (ops/hair_widths.h).
    HairWidths widths;
    int points = 24;       ///< points per hair, [4, 4096] (--points)
    uint64_t seed = 0;     ///< (--seed)
    int64_t first_id = 0;  ///< hair ids first_id, first_id+1, ... along the hairline, >= 0 (--first-id)
    int32_t kind = 3;      ///< curve `kind` written on every hair (puff 0/1, gather 1/2: 3 = edges), >= 0 (--kind)
    void validate() const;  ///< throws InvalidParam naming the option
};

/// @brief Baby hairs along `hairline` on `scalp`.
///
/// Stations: the part of the hairline with azimuth in [from, to] (around `up` through the hairline's
/// centroid, clipped exactly within segments) is cut into `count` (or density x its length) equal
/// arc-length intervals, one root per interval at a seeded random place in it. Each root is walked on
/// the scalp perpendicular to the hairline, toward its haired side, by depth x u (u uniform in [0, 1]).
///
/// Swoops: the chosen hairline is cut into lengths of `swoop` (w), counted from azimuth 0 when the
/// part holds it (so the face's middle is a swoop boundary), each leaning one way along the
/// hairline: away from the face's middle (face, along), alternately (alternate) or at random (random).
/// The hairs of a swoop are parallel curves, a ribbon: a hair runs straight out of the band to the
/// hairline, then along `bends` arcs of constant geodesic curvature, bending alternately toward the
/// lean and back, each turning by tau = length / (bends (radius + w/2)) radians. A hair t from its
/// swoop's end on the lean side has radius radius + t on the arcs bending toward the lean (all of
/// the swoop's hairs circle one centre there, `radius` past that end) and radius + w - t on the
/// others, so the tightest radius in a swoop is `radius`. It leaves the hairline straight out of it
/// (toward the face). With `along` every arc has radius radius + w/2 (the ribbon runs along its own
/// length) and the hair's mean heading is along the hairline away from the middle: it leaves tilted
/// by tau/2 into the hairline, and its first bend takes it out toward the face.
/// The curve is walked on the scalp in `points` - 1 equal steps (each a chord: turn by the
/// curvature over the step's first half, move in the tangent plane, back onto the surface, carry the
/// heading into the new tangent plane, turn by the second half), then every point but the root is
/// lifted along the normal by the hair's height and kept outside by fields/keep_outside.h
/// (clearance 0).
///
/// @param hairline  one closed curve going once around the head (`groom hairline`), >= 8 points.
/// @param region    optional: where hair may grow. Roots on which region->haired() is false (on a
///                  parting's bare gap: inside its hairline but not haired) are dropped (roots just
///                  outside its hairline are kept: edges grow at the hairline), and a hair that
///                  would cross a parting (region->crosses_parting) bends the other way, or is
///                  dropped when that crosses too.
/// Writes point P, point `width` (params.widths); curve int64 `id` (first_id + station, so dropping one hair does
/// not renumber the others), int32 `kind`, int32 `group` (swoop index along the hairline).
/// Deterministic: every random draw is Rng(seed, hair id or swoop, stream); any thread count gives the same.
/// Throws InvalidParam (params), InvalidGeometry (hairline not one closed curve around `up`, or no
/// part of it in [from, to]).
CurveSet edges(const Surface& scalp, const CurveSet& hairline, const EdgesParams& params, const HairRegion* region = nullptr);

}  // namespace groom
