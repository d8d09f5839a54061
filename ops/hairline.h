// hairline: a default hairline for a head, as a closed curve on its scalp: the edge of the haired
// part, high over the forehead, a small recession at the temples, down in front of the ears to the
// sideburns, up and over the ears, and down behind them to the nape. Written by `groom hairline`,
// read by every op that takes --hairline (ops/hair_region.h). Artists draw their own; this one makes
// `groom head` (and any head with +Y up and a known face direction) groomable with no other input.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/math/vec.h"

#include <string>
#include <utility>
#include <vector>

namespace groom {

struct HairlineParams {
    float3 up{0.0f, 1.0f, 0.0f};       ///< (--up) the head's up direction
    float3 forward{0.0f, 0.0f, 1.0f};  ///< (--forward) the direction the face looks
    /// Where the head is: the top of the cranium is found from here by walking up (--center; default:
    /// the middle of the scalp's bounds in the two horizontal directions, used when `has_center` is false).
    float3 center{};
    bool has_center = false;
    /// The head's length front to back, scene units (--head-length); 0 = measured on the scalp at the
    /// first depth below the top that is 0.36 of the length measured there (wherever the centre is).
    float head_length = 0.0f;
    /// Heights of the hairline below the top of the head, as fractions of head_length, at the
    /// forehead (azimuth 0), the temples (55 deg), the sideburns (80 deg), over the ears (100 deg)
    /// and at the nape (180 deg); in (0, 2) (--forehead, --temple, --sideburn, --ear, --nape).
    float forehead = 0.26f;
    float temple = 0.31f;
    float sideburn = 0.62f;
    float ear = 0.47f;
    float nape = 0.86f;
    int points = 180;  ///< points on the closed curve, [16, 100000] (--points)
    void validate() const;  ///< throws InvalidParam naming the option
};

/// @brief The hairline on `scalp`, a closed curve of params.points points (the last does not repeat
/// the first), in order of increasing azimuth around `up` (from the face to the left, seen from above).
///
/// For each azimuth phi the height y(phi) below the top is a smooth periodic interpolation of the
/// five key heights (mirrored left/right); the point is where the horizontal ray from the head's axis
/// at that height, in direction phi, last leaves the scalp (the outermost surface: ears are a bump,
/// not a hole). The top of the head is the highest surface point above `center`.
/// @param bounds  the scalp's bounding box (for the default centre and how far out rays start).
/// Writes point P and curve int64 `id` = 0.
/// Throws InvalidParam (params), InvalidGeometry (no scalp above the centre, or a ray that finds none).
/// `report`, when given, receives which way the head seems to face (HairlineReport).
struct HairlineReport;
CurveSet make_hairline(const Surface& scalp, const Bounds3& bounds, const HairlineParams& params, HairlineReport* report = nullptr);

/// Which way the head seems to face, read from the scalp below the hairline: 0.8 and 0.9 head lengths
/// below the top, a face and chin stand farther in front of the head's middle than the neck behind it
/// (1.2-10x on the default head, ICT, Lee Perry-Smith, Sintel, Nefertiti and the ponytail head). A head
/// turned the other way from `forward` (the ponytail head looks along -Z) got a hairline whose nape
/// ran across the eyes without a word (a trial).
struct HairlineReport {
    bool measured = false;  ///< false where a ray missed the scalp (nothing said of the facing)
    float front = 0.0f;     ///< the scalp's reach in front of the head's middle, summed over the two depths
    float back = 0.0f;      ///< ... behind it
    /// True when the back reaches over 1.15 times as far as the front: `forward` is probably reversed
    /// (the ponytail head looked at along +Z: 1.43; the right way round 0.1-0.83 on the heads above,
    /// MakeHuman's body 0.92 either way, its helper shells behind the head).
    bool faces_backward() const { return measured && back > 1.15f * front; }
    /// The warning to print when faces_backward(), naming the option to pass.
    std::string warning(const std::string& command, const float3& forward) const;

    /// The axis the rays started from (the centre, or the head's middle when the axis moved).
    float3 axis{};
    /// The head's middle 0.36 head lengths below its top, from the centre's axis, horizontally; the
    /// axis is off the middle when that is over 0.15 head lengths (0.06 at most on every head alone
    /// tried, 0.26 on MakeHuman's body from the middle of its bounds).
    float3 middle_offset{};
    bool axis_off_middle = false;
    /// Without `has_center`, an axis off the middle is moved to it (and the top and length found
    /// again from there); a given centre is kept.
    bool moved_axis = false;
    /// A centre in the head's middle, halfway down: what to pass as --center.
    float3 suggested_center{};
    /// What to print when axis_off_middle: a note that the axis moved, or a warning naming --center.
    std::string axis_message(const std::string& command) const;
    /// Everything a command prints of this report, in order: {is a warning, text}.
    std::vector<std::pair<bool, std::string>> messages(const std::string& command, const float3& forward) const;
};

}  // namespace groom
