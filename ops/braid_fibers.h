// braid_fibers: the hair fibers of a braid's strands (internal to ops/braid). Each fiber keeps a seeded
// place in its strand's cross-section, an ellipse that flattens where the strand is pressed against
// another and turns slowly about the centreline (a rope's or twist's fibers against the plies' lay);
// a seeded few leave the strand in a loop (flyaways), and a seeded few join along the braid from beside
// and below it (feed-in). Randomness comes from (seed, fiber id) only, so the output is the same for any
// thread count or guide order.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/braid.h"

#include <cstdint>
#include <span>
#include <vector>

namespace groom {

/// A strand's fibers spread wider across the braid than its round width, as hair does when strands
/// are pulled tight against each other: the ellipse's half-width is kFiberSpreadAcross times the strand's radius.
/// Measured on 3- and 5-strand plaits of 40 fibers seen from above (tests/ops/braid_weave_test.cpp):
/// at 1.0, 6-8% of the footprint is see-through; at 1.25, 1.4-2.6%; at 1.4, up to 1%; at 1.55, none
/// beyond 0.2%.
inline constexpr float kFiberSpreadAcross = 1.55f;

/// Per strand point: the braid section the point belongs to, as braid() built it.
struct StrandSections {
    std::vector<float3> centre;    ///< the guide point of the section (after scalp lifts)
    std::vector<float3> lateral;   ///< frame binormal b (across the braid)
    std::vector<float3> up;        ///< frame normal n (height; the scalp normal for cornrows)
    std::vector<float> phase;      ///< knot phase u
    std::vector<float> press;      ///< [0, 1]: 1 where the strand is pressed against another
    std::vector<float> spread;     ///< loose-end opening factor, 1 in the weave
    std::vector<float> t;          ///< arc-length fraction along the guide
    std::vector<float> half_width;   ///< A s + w / 2: half the braid's width
    std::vector<float> half_height;  ///< B s + w / 2: half its height
    void resize(size_t n)
    {
        for (auto* v : {&centre, &lateral, &up}) v->resize(n);
        for (auto* v : {&phase, &press, &spread, &t, &half_width, &half_height}) v->resize(n);
    }
};

/// Per strand: lengths in arc-length fractions of its guide.
struct StrandFiberPlan {
    float knot_t = 1.0f;  ///< one knot
    float feed_t = 1.0f;  ///< the stretch over which fibers feed in
};

struct FiberStats {
    int64_t flyaways = 0;
    int64_t fed_in = 0;
};

/// params.fibers fibers per strand (curve c * M + f for strand c), each from the strand point its
/// first point sits on to the tip. Writes point P, width; curve fiber, id (strand id * M + f); carries
/// the strands' other attributes. `reach` gets, per output point, its distance from its strand point;
/// `strand_point` the strand point it was built from. `scalp` (cornrows only): where hair joining the
/// braid, and the first stitch's hair, is rooted (on it at the clearance); null: beside the braid.
CurveSet braid_fibers(const CurveSet& strands, const StrandSections& sec, std::span<const StrandFiberPlan> plans,
                      const BraidParams& params, const BraidWeave& weave, const Surface* scalp, FiberStats& stats,
                      std::vector<float>& reach, std::vector<int64_t>& strand_point, Progress* progress);

}  // namespace groom
