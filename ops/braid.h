// braid: turn each hand-sculpted guide curve into an N-strand braid (or a cornrow lying on the scalp):
// strand centrelines whose cross-section follows a braid pattern (ops/braid_weave.h: a woven plait by
// default, fishtail, twist, rope, round, or the talk's Lissajous formula), carried along the guide by
// orthonormal frames (talk, Sec. 2.1), optionally filled with hair fibers, with a loose flared end, a
// hair tie, flyaways and fibers feeding in along the braid. Also the knot placement that
// `groom partition --centroids knots` shares, so --frequency / --knot-length / the alpha remap mean the
// same thing in both commands.
//
// Strand i of N at guide parameter t sits at
//     P_i(t) = C(t) + A s(t) x_i(u) b(t) + B s(t) y_i(u) n(t),     u = F alpha(t / t_b)
// C the guide, (b, n) the frame's binormal (lateral) and normal (height), (x_i, y_i) the pattern's
// cross-section at knot phase u (BraidWeave), s(t) the amplitude scale (root/tip blend times the taper
// spline, pinched at a tie). t in [0,1] is the arc-length fraction along the guide (0 = root); the
// braid is woven over [0, t_b] (t_b = 1 - loose length / guide length) and loose after it.
//
// Knots: a knot is one full lateral cycle of a strand, so F is the number of knots along the woven part
// (when alpha is the identity each knot is length / F long). With --knot-length L, F = woven length / L
// per guide, so every braid's knots keep the same physical size whatever its guide's length. Knot k
// (k = 0, 1, ...) is centred where F alpha = k + 1/2; only knots whose centre lies on the woven part
// count.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/braid_weave.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace groom {

/// How the cross-section is oriented along the guide.
enum class BraidOrient {
    Frame,  ///< rotation-minimising frames along the guide (no flips at inflections, unlike Frenet)
    Scalp,  ///< cornrows: frame normal replaced by the scalp normal at the guide point's projection
};

struct BraidParams {
    BraidPattern pattern = BraidPattern::Plait;  ///< how the strands cross (ops/braid_weave.h)
    /// Which strand is on top at a crossing (plait, fishtail, round), or the lay of a rope / twist
    /// (over: plies wind from the binormal toward the normal). Auto: under with orient Scalp, else over.
    BraidHand hand = BraidHand::Auto;
    /// N, strands per braid; 0 = the pattern's own (default_strands: plait 3, fishtail 8, twist 2,
    /// rope 3, round 4). Must suit the pattern (validate_pattern_strands).
    int strands = 0;
    /// F, knots (x cycles) over the whole guide; >= 0. Exclusive with knot_length. When neither is
    /// set F = kDefaultFrequency.
    std::optional<float> frequency;
    /// L, arc length of one knot, scene units; > 0. F = guide length / L per guide.
    std::optional<float> knot_length;
    /// A, lateral amplitude, scene units; >= 0. Unset: a third of the guide's knot length.
    std::optional<float> width;
    /// B, amplitude along the normal, scene units; >= 0. Unset: the height at which strands touch
    /// where they cross (BraidWeave::touching_height; A / (N - 1) for a plait, A for a rope).
    std::optional<float> height;
    /// N_cv, points per strand; 0 = automatic (per knot where knots are densest: 16, and 4 per weave
    /// step of a plait or fishtail; at least the guide's own point count, at least 8); otherwise >= 2.
    int samples = 0;
    float root_amplitude = 1.0f;      ///< a0, amplitude scale at the root (t = 0); >= 0
    float tip_amplitude = 1.0f;       ///< a1, amplitude scale at the tip (t = 1); >= 0; blended linearly
    /// Amplitude scale spline over t (values >= 0, uniformly spaced, see sample_uniform_spline);
    /// multiplies the root/tip blend. Empty = 1.
    std::vector<float> taper;
    /// Knot-distribution remap of alpha: bias in (-1, 1); > 0 packs knots toward the tip, < 0 toward
    /// the root (Schlick's bias curve, so knot length changes smoothly; at b = 0.5 tip knots are 9x
    /// shorter than root knots).
    float knot_bias = 0.0f;
    /// Knot-distribution remap of alpha: relative knot density over t as a spline (values > 0,
    /// uniformly spaced); alpha' is proportional to it. Applied before knot_bias. Empty = uniform.
    std::vector<float> knot_density;
    BraidOrient orient = BraidOrient::Frame;
    /// Frame mode: the normal at the root (need not be unit or perpendicular to the guide). Zero =
    /// automatic: the scalp normal at the root when there is a scalp, else world +Y (the up axis of
    /// our files), or +Z when the guide starts within ~25 degrees of vertical.
    float3 initial_normal{0, 0, 0};
    /// With a scalp: the least distance, scene units, from any output point to the scalp; >= 0.
    float clearance = 0.0f;
    /// With a scalp: also lower cross-sections that float above the scalp until they rest on it at
    /// `clearance` (cornrows lie on the head). Without it sections are only ever lifted.
    bool rest = false;
    /// Strand thickness, scene units; 0 = automatic: the width at which neighbouring strands touch
    /// (A times BraidWeave::touching_width: 2 A / (N - 1) for a plait). Scaled by s(t) along the strand.
    float strand_width = 0.0f;
    int fibers = 0;                   ///< M, hair fibers per strand (see ops/populate.h); 0 = centrelines
    /// Radius of the disc the fibers fill around each strand centreline, scene units, scaled by s(t);
    /// 0 = automatic (half the strand width).
    float fiber_radius = 0.0f;
    /// Fiber width, scene units; 0 = automatic (fibers together about cover their disc), see PopulateParams.
    float fiber_width = 0.0f;
    /// Turns of a fiber around its strand's centreline per knot (a slight twist keeps a strand
    /// together); any finite value. A rope's or twist's fibers turn against the plies' lay.
    float fiber_twist = 0.25f;
    /// How much a strand's fiber cross-section flattens where it is pressed against another, [0, 0.9]:
    /// the ellipse's height shrinks by this fraction (and its width grows by half of it) at a crossing.
    float flatten = 0.3f;
    /// Unbraided length at each guide's tip, scene units; >= 0. The strands stop crossing there and
    /// part into a row; the weave fits the rest of the guide.
    float loose_length = 0.0f;
    /// How far the loose end opens, >= 0: at the tip, strands lie (1 + flare) times their touching
    /// distance apart and their fibers fill (1 + flare) times their disc.
    float flare = 1.0f;
    /// Arc-length fraction in [0, 1] of a hair tie: the braid is pinched there and a band of
    /// `tie_turns` wraps is emitted as its own curve (curve kind = 1). Unset: no tie.
    std::optional<float> tie;
    float tie_width = 0.0f;           ///< thickness of the tie band, scene units; 0 = 0.35 strand widths
    int tie_turns = 3;                ///< wraps of the tie band; [1, 64]
    /// Fraction of fibers, [0, 1], that leave their strand in a loop (a flyaway), chosen per fiber id.
    float flyaways = 0.0f;
    /// How far a flyaway loop leaves its strand, scene units; 0 = automatic (one strand width).
    float flyaway_height = 0.0f;
    /// Fraction of fibers, [0, 1), that join the braid along its first `feed_length` instead of at the
    /// root (feed-in: the braid thickens from the root, as cornrows fed by the edge hairs do). Each
    /// joining fiber starts beside the braid, below it, and merges into its strand.
    float feed_in = 0.0f;
    /// Arc length over which fibers feed in, scene units; 0 = automatic (three knots).
    float feed_length = 0.0f;
    uint64_t seed = 0;                ///< seeds the fiber placement, flyaways and feed-in

    /// N actually used: strands, or the pattern's default when strands is 0.
    int strand_count() const { return strands > 0 ? strands : default_strands(pattern); }
    /// hand with Auto resolved from the orientation.
    BraidHand resolved_hand() const
    {
        return hand != BraidHand::Auto ? hand : orient == BraidOrient::Scalp ? BraidHand::Under : BraidHand::Over;
    }

    static constexpr float kDefaultFrequency = 8.0f;

    /// Throws InvalidParam naming the option, the value and the valid range, e.g.
    /// "braid: --strands must be >= 2 (got 1)".
    void validate() const;
};

/// The knot-distribution remap alpha(t): [0,1] -> [0,1], increasing, alpha(0) = 0, alpha(1) = 1.
/// Identity unless knot_bias or knot_density is set. Built once per params; evaluation is cheap and
/// thread-safe.
class KnotRemap {
public:
    explicit KnotRemap(const BraidParams& params);
    /// alpha at t (t clamped to [0,1]).
    double alpha(double t) const;
    /// The t with alpha(t) = a (a clamped to [0,1]).
    double inverse(double a) const;
    /// The largest slope d alpha / d t over [0,1] (1 for the identity): where knots are densest.
    double max_slope() const { return max_slope_; }
    bool identity() const { return density_.empty() && bias_k_ == 0.0; }

private:
    double density_alpha(double t) const;
    double density_inverse(double a) const;
    std::vector<double> density_;  // alpha before bias on a uniform table over t; empty = identity
    double bias_k_ = 0.0;          // Schlick bias: alpha = x / (k (1 - x) + 1)
    double max_slope_ = 1.0;
};

/// F for one guide of arc length `guide_length` (scene units): params.frequency, or the woven length
/// (guide_length less params.loose_length) / params.knot_length, or kDefaultFrequency.
double braid_frequency(const BraidParams& params, double guide_length);

/// t_b for one guide of arc length `guide_length`: the arc-length fraction that is woven, 1 - loose
/// length / guide length clamped to [0, 1] (1 with no loose length).
double braid_woven_fraction(const BraidParams& params, double guide_length);

/// Knot centres along a guide of arc length `guide_length`, as arc-length fractions t_k in [0,1]
/// (multiply by the length for a distance from the root), increasing from root to tip: the t where
/// F alpha(t / t_b) = k + 1/2, k = 0, 1, ... (see the file comment). Empty when F < 1/2. Throws
/// InvalidParam when params are invalid.
std::vector<float> braid_knot_parameters(const BraidParams& params, double guide_length);

/// A guide whose braid could not simply be lifted off the scalp along it (braid() lists them; the
/// CLI names them in a warning).
struct BraidScalpIssue {
    int64_t guide = 0;      ///< guide index
    int64_t id = 0;         ///< its curve id (its index where the guides have none)
    int64_t blocked = 0;    ///< its sections with no clear place along the scalp normal short of passing through the scalp
                            ///< (a gap narrower than the braid): left where clearest, their hair pushed out point by point
    float short_by = 0.0f;  ///< the most one of those still lacked of its clearance, scene units
    float3 blocked_at;      ///< the guide point of the first of them
    int64_t deep = 0;       ///< its sections whose guide point is inside the scalp deeper than the braid is wide: lifted
                            ///< less the deeper it runs (none from twice that), left inside with the guide, not pushed out
    float depth = 0.0f;     ///< how far the guide runs inside the scalp at its deepest, scene units
    float3 deepest;         ///< the guide point there
};

/// What braid() did, for the CLI to report.
struct BraidReport {
    int64_t guides = 0;            ///< guides braided
    int64_t skipped_guides = 0;    ///< guides with fewer than 2 points or no length (no output)
    int64_t strands = 0;           ///< strand centrelines made (guides x N)
    int64_t ties = 0;              ///< tie bands made
    int64_t flyaways = 0;          ///< fibers that leave their strand in a loop
    int64_t fed_in = 0;            ///< fibers that join along the braid
    int64_t curves = 0;            ///< output curves (strands, or strands x M with fibers)
    int64_t points = 0;            ///< output points
    int64_t lifted_sections = 0;   ///< cross-sections moved off the scalp (they cut into it, or lay closer than clearance)
    int64_t lowered_sections = 0;  ///< cross-sections lowered onto the scalp (rest = true)
    float max_lift = 0.0f;         ///< largest lift along the scalp normal, scene units
    float max_lower = 0.0f;        ///< largest lowering, scene units
    int64_t pushed_points = 0;     ///< points still too close after lifting, pushed out one by one
    int64_t blocked_sections = 0;  ///< cross-sections with no clear place along the scalp normal (see BraidScalpIssue)
    std::vector<BraidScalpIssue> scalp_issues;  ///< guides with blocked sections or running deep in the scalp, in guide order
};

struct BraidResult {
    CurveSet curves;
    BraidReport report;
};

/// @brief Braid every guide: N strands per guide (times M fibers each with params.fibers > 0), plus
/// one tie band per guide when params.tie is set.
///
/// Reads guide point P (curves root to tip) and curve id (else the curve index). Writes, per guide in
/// guide order, strands 0..N-1 (fibers 0..M-1 per strand), each running root to tip (a fiber that
/// feeds in starts where it joins), then the guide's tie:
///   point P, point width (scene units);
///   curve guide (int32, source curve index), strand (int32, 0..N-1; -1 on a tie), fiber (int32,
///   0..M-1, with fibers only; -1 on a tie), kind (int32: 0 hair, 1 tie), id (int64: guide id * N +
///   strand, times M plus fiber with fibers; a tie's id is one past the largest hair id plus its index among the ties; unique when guide ids are);
///   every other curve and detail attribute of the guide; point attributes of the guide from its
///   point nearest in arc length (P and width excepted).
///
/// @param scalp   required for orient = Scalp; with it no output point ends inside the scalp (whole
///                cross-sections are lifted along the scalp normal by what is needed plus clearance,
///                never through the scalp, and any point still closer than clearance is pushed out
///                alone), except where a guide runs inside it deeper than its braid is wide: the braid
///                follows the guide in there. Guides with such places, or with sections that found no
///                clear place, are listed in report.scalp_issues.
/// @throws InvalidParam (bad params; Scalp orientation, clearance > 0 or rest without a scalp), LimitExceeded (output over
///         kMaxBraidPoints points, or ids that would overflow).
BraidResult braid(const CurveSet& guides, const BraidParams& params, const Surface* scalp = nullptr,
                  Progress* progress = nullptr);

/// Largest output braid() makes before refusing (points; about 16 bytes each).
inline constexpr int64_t kMaxBraidPoints = 400'000'000;

}  // namespace groom
