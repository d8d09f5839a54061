// hair_region: where hair grows on a scalp. A hairline (a closed curve around the head) bounds the
// haired part; partings (open curves on the scalp) split it into sections and stay bare for a gap
// either side. Every op that places roots asks this one object (`generate`, `gather`, `edges`,
// `partition`, `sections`), so a user's hairline and partings mean the same thing to each of them.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace groom {

struct HairRegionParams {
    /// Up direction of the head (--up): the hairline is read as a height around this axis.
    float3 up{0.0f, 1.0f, 0.0f};
    /// Width of the bare line along each parting, scene units, >= 0 (--parting-gap): roots within
    /// half of it of a parting are not haired.
    float parting_gap = 0.3f;
    void validate() const;  ///< throws InvalidParam naming the option
};

/// @brief The haired part of the scalp: inside the hairline (when given) and not on a parting.
///
/// The hairline is read around the axis through its own centroid along `up`: each of its points has
/// an azimuth and an elevation angle seen from the centroid; a point p is inside when its elevation
/// is above the hairline's at p's azimuth (linear in azimuth between hairline points). So the hairline
/// must go once around that axis (azimuths strictly monotonic along it, one way or the other, closing
/// up); a hairline that doubles back is refused. Every real hairline (forehead, temples, above the ears,
/// nape) does go once around.
/// A parting's side at p is the sign of (p - q) . (t x n) for q the closest point of the parting, t
/// its tangent there and n = `up`-independent scalp normal at q; the sides of all partings form p's
/// section (a bitmask, parting i = bit i; at most 64 partings: a 46-section grid from `groom sections` has 45).
/// The points of `hairline` if it is one: a single curve of at least 8 finite points whose ends
/// close, no more than a tenth of its length apart (an open curve passed by mistake, a parting
/// line, can still turn once around an axis through its centroid, and every op then ran on
/// nonsense without a word: a trial, baby hairs across the eye, "20 sections ... 0 roots").
/// A last point that repeats the first (within float rounding: a closed curve as USD's periodic
/// wrap, an OBJ record back to its first vertex or a loop of edges read) is left out of the span, so
/// every form of one closed hairline gives the same points.
/// Throws InvalidGeometry otherwise, each message starting with `who` ("hairline",
/// "edges: the hairline"). HairRegion and edges both ask it.
std::span<const float3> check_hairline(const CurveSet& hairline, const std::string& who);

class HairRegion {
public:
    /// @param hairline  one closed curve (first point may repeat at the end: check_hairline), or empty for "all
    ///                  of the scalp"; >= 8 points.
    /// @param partings  open curves on the scalp, >= 2 points each, at most 64; may be empty.
    /// Throws InvalidParam / InvalidGeometry naming `hairline` or `parting` and what is wrong.
    HairRegion(const Surface& scalp, const CurveSet& hairline, const CurveSet& partings, const HairRegionParams& params);

    bool has_hairline() const { return !elevation_.empty(); }
    /// The hairline's points in its own order (a closed curve, the first point not repeated), or
    /// empty: cornrow-guides spreads its rows' ends along it.
    std::span<const float3> hairline_points() const { return hairline_; }
    size_t num_partings() const { return partings_.size(); }

    /// Inside the hairline (true when there is none).
    bool inside_hairline(const float3& p) const;
    /// Angle, radians, by which p's elevation exceeds the hairline's at its azimuth (negative outside).
    float hairline_margin(const float3& p) const;
    /// Distance from p to the nearest parting polyline, scene units (+infinity with none).
    float parting_distance(const float3& p) const;
    /// Bitmask of p's side of every parting.
    uint64_t section(const float3& p) const;
    /// Inside the hairline and farther than parting_gap / 2 from every parting.
    bool haired(const float3& p) const;
    /// True when the segment a-b crosses a parting (the section changes between a and b while the
    /// segment passes within reach of that parting; far from a parting's ends the sign test alone).
    bool crosses_parting(const float3& a, const float3& b) const;

    const float3& centroid() const { return centroid_; }

private:
    struct Parting {
        std::vector<float3> points;
        std::vector<float3> side;  ///< per segment: t x n, the direction of the positive side
    };
    void azimuth_elevation(const float3& p, float& azimuth, float& elevation) const;
    int side_of(const Parting& part, const float3& p, float* dist) const;

    HairRegionParams params_;
    float3 centroid_{}, e1_{}, e2_{};
    std::vector<float> azimuth_, elevation_;  ///< hairline samples sorted by azimuth in [-pi, pi)
    std::vector<float3> hairline_;
    std::vector<Parting> partings_;
};

}  // namespace groom
