#include "ops/braid.h"

#include "fields/keep_outside.h"
#include "kernel/error.h"
#include "kernel/math/frames.h"
#include "kernel/math/polyline.h"
#include "kernel/math/spline.h"
#include "kernel/parallel.h"
#include "ops/braid_fibers.h"
#include "ops/populate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <tuple>
#include <numbers>
#include <string>

namespace groom {

namespace {

std::string fmt(double v) { return format_number(v); }

void require_finite_at_least(const char* option, float value, float lo)
{
    if (!std::isfinite(value) || value < lo) {
        throw InvalidParam(std::string("braid: ") + option + " must be a finite number >= " + fmt(lo) + " (got " + fmt(value) + ")");
    }
}

/// Intervals of the knot-density table: fine enough that the piecewise-linear alpha is within
/// ~1e-7 of the exact integral for any spline of a few dozen values.
constexpr int kDensityTable = 4096;

}  // namespace

void BraidParams::validate() const
{
    if (strands != 0 && strands < 2) {
        throw InvalidParam("braid: --strands must be >= 2 (got " + std::to_string(strands) + ")");
    }
    if (strands > 4096) throw InvalidParam("braid: --strands must be <= 4096 (got " + std::to_string(strands) + ")");
    validate_pattern_strands(pattern, strand_count());
    if (pattern == BraidPattern::Lissajous && hand != BraidHand::Auto) {
        throw InvalidParam("braid: --hand does not apply to --pattern lissajous (the talk's formula fixes who is on top)");
    }
    if (frequency && knot_length) {
        throw InvalidParam("braid: --frequency and --knot-length are exclusive (got both: --frequency " + fmt(*frequency) +
                           ", --knot-length " + fmt(*knot_length) + ")");
    }
    if (frequency) require_finite_at_least("--frequency", *frequency, 0.0f);
    if (knot_length && !(std::isfinite(*knot_length) && *knot_length > 0.0f)) {
        throw InvalidParam("braid: --knot-length must be a finite number > 0 (got " + fmt(*knot_length) + ")");
    }
    if (width) require_finite_at_least("--width", *width, 0.0f);
    if (height) require_finite_at_least("--height", *height, 0.0f);
    if (samples != 0 && samples < 2) {
        throw InvalidParam("braid: --samples must be >= 2, or 0 for automatic (got " + std::to_string(samples) + ")");
    }
    require_finite_at_least("--root-amplitude", root_amplitude, 0.0f);
    require_finite_at_least("--tip-amplitude", tip_amplitude, 0.0f);
    for (size_t i = 0; i < taper.size(); ++i) {
        if (!std::isfinite(taper[i]) || taper[i] < 0.0f) {
            throw InvalidParam("braid: --taper values must be finite and >= 0 (value " + std::to_string(i + 1) + " is " +
                               fmt(taper[i]) + ")");
        }
    }
    if (!std::isfinite(knot_bias) || knot_bias <= -1.0f || knot_bias >= 1.0f) {
        throw InvalidParam("braid: --knot-bias must be in (-1, 1) (got " + fmt(knot_bias) + ")");
    }
    for (size_t i = 0; i < knot_density.size(); ++i) {
        if (!std::isfinite(knot_density[i]) || knot_density[i] <= 0.0f) {
            throw InvalidParam("braid: --knot-density values must be finite and > 0 (value " + std::to_string(i + 1) +
                               " is " + fmt(knot_density[i]) + ")");
        }
    }
    if (!isfinite(initial_normal)) throw InvalidParam("braid: --initial-normal must be finite");
    require_finite_at_least("--clearance", clearance, 0.0f);
    require_finite_at_least("--strand-width", strand_width, 0.0f);
    if (fibers < 0 || fibers > PopulateParams::kMaxFibersPerCurve) {
        throw InvalidParam("braid: --fibers must be in [0, " + std::to_string(PopulateParams::kMaxFibersPerCurve) + "] (got " +
                           std::to_string(fibers) + ")");
    }
    require_finite_at_least("--fiber-radius", fiber_radius, 0.0f);
    require_finite_at_least("--fiber-width", fiber_width, 0.0f);
    if (!std::isfinite(fiber_twist) || std::fabs(fiber_twist) > 1000.0f) {
        throw InvalidParam("braid: --fiber-twist must be a finite number of turns per knot in [-1000, 1000] (got " + fmt(fiber_twist) + ")");
    }
    if (!std::isfinite(flatten) || flatten < 0.0f || flatten > 0.9f) {
        throw InvalidParam("braid: --flatten must be in [0, 0.9] (got " + fmt(flatten) + ")");
    }
    require_finite_at_least("--loose-length", loose_length, 0.0f);
    require_finite_at_least("--flare", flare, 0.0f);
    if (flare > 100.0f) throw InvalidParam("braid: --flare must be <= 100 (got " + fmt(flare) + ")");
    if (tie && !(std::isfinite(*tie) && *tie >= 0.0f && *tie <= 1.0f)) {
        throw InvalidParam("braid: --tie must be an arc-length fraction in [0, 1] (got " + fmt(*tie) + ")");
    }
    require_finite_at_least("--tie-width", tie_width, 0.0f);
    if (tie_turns < 1 || tie_turns > 64) {
        throw InvalidParam("braid: --tie-turns must be in [1, 64] (got " + std::to_string(tie_turns) + ")");
    }
    if (!std::isfinite(flyaways) || flyaways < 0.0f || flyaways > 1.0f) {
        throw InvalidParam("braid: --flyaways must be a fraction in [0, 1] (got " + fmt(flyaways) + ")");
    }
    require_finite_at_least("--flyaway-height", flyaway_height, 0.0f);
    if (!std::isfinite(feed_in) || feed_in < 0.0f || feed_in >= 1.0f) {
        throw InvalidParam("braid: --feed-in must be a fraction in [0, 1) (got " + fmt(feed_in) + ")");
    }
    require_finite_at_least("--feed-length", feed_length, 0.0f);
    if (fibers == 0 && (flyaways > 0.0f || feed_in > 0.0f)) {
        throw InvalidParam(std::string("braid: ") + (flyaways > 0.0f ? "--flyaways" : "--feed-in") +
                           " moves fibers; give --fibers M > 0");
    }
}

// --- knot distribution ------------------------------------------------------------------------------

KnotRemap::KnotRemap(const BraidParams& params)
{
    // Schlick's bias curve x / ((1/g - 2)(1 - x) + 1) with g = (1 - b) / 2: smooth, monotonic, slope
    // g/(1-g) at the root and (1-g)/g at the tip, identity at b = 0.
    bias_k_ = 2.0 * double(params.knot_bias) / (1.0 - double(params.knot_bias));
    if (!params.knot_density.empty()) {
        // alpha' proportional to the density spline: integrate it (Simpson per interval) into a table.
        // Catmull-Rom can undershoot between positive values; a floor keeps alpha strictly increasing.
        const float lowest = *std::min_element(params.knot_density.begin(), params.knot_density.end());
        const auto density = [&](double t) {
            return std::max(double(sample_uniform_spline(params.knot_density, float(t))), 1e-3 * lowest);
        };
        density_.assign(kDensityTable + 1, 0.0);
        for (int j = 0; j < kDensityTable; ++j) {
            const double a = double(j) / kDensityTable, b = double(j + 1) / kDensityTable;
            density_[j + 1] = density_[j] + (b - a) / 6.0 * (density(a) + 4.0 * density(0.5 * (a + b)) + density(b));
        }
        const double total = density_.back();
        for (double& v : density_) v /= total;
        density_.back() = 1.0;
    }
    if (!identity()) {
        double prev = 0.0;
        max_slope_ = 0.0;
        for (int j = 1; j <= kDensityTable; ++j) {
            const double a = alpha(double(j) / kDensityTable);
            max_slope_ = std::max(max_slope_, (a - prev) * kDensityTable);
            prev = a;
        }
        // The bias curve is steepest at an end; the secant above slightly underestimates it there.
        if (density_.empty()) max_slope_ = std::max(1.0 / (bias_k_ + 1.0), bias_k_ + 1.0);
    }
}

double KnotRemap::density_alpha(double t) const
{
    if (density_.empty()) return t;
    const double x = t * kDensityTable;
    const int j = std::min(int(x), kDensityTable - 1);
    return density_[j] + (density_[j + 1] - density_[j]) * (x - j);
}

double KnotRemap::density_inverse(double a) const
{
    if (density_.empty()) return a;
    const size_t hi = std::clamp<size_t>(std::upper_bound(density_.begin(), density_.end(), a) - density_.begin(), 1,
                                         density_.size() - 1);
    const size_t lo = hi - 1;
    const double seg = density_[hi] - density_[lo];
    return (double(lo) + (seg > 0.0 ? (a - density_[lo]) / seg : 0.0)) / kDensityTable;
}

double KnotRemap::alpha(double t) const
{
    t = std::clamp(t, 0.0, 1.0);
    const double x = density_alpha(t);
    return bias_k_ == 0.0 ? x : x / (bias_k_ * (1.0 - x) + 1.0);
}

double KnotRemap::inverse(double a) const
{
    a = std::clamp(a, 0.0, 1.0);
    const double x = bias_k_ == 0.0 ? a : a * (bias_k_ + 1.0) / (1.0 + a * bias_k_);
    return density_inverse(std::clamp(x, 0.0, 1.0));
}

double braid_frequency(const BraidParams& params, double guide_length)
{
    if (params.frequency) return *params.frequency;
    if (params.knot_length) return std::max(guide_length - double(params.loose_length), 0.0) / *params.knot_length;
    return BraidParams::kDefaultFrequency;
}

namespace {
/// t_b: the arc-length fraction of a guide that is woven (the rest is the loose end).
double woven_fraction(const BraidParams& params, double guide_length)
{
    if (!(params.loose_length > 0.0f) || !(guide_length > 0.0)) return 1.0;
    return std::clamp(1.0 - double(params.loose_length) / guide_length, 0.0, 1.0);
}
}  // namespace

std::vector<float> braid_knot_parameters(const BraidParams& params, double guide_length)
{
    params.validate();
    const double F = braid_frequency(params, guide_length);
    if (F > 1e8) {
        throw LimitExceeded("braid: " + fmt(F) + " knots on one guide is more than 1e8; raise --knot-length or lower --frequency");
    }
    const KnotRemap remap(params);
    std::vector<float> t;
    const double woven = woven_fraction(params, guide_length);
    for (int64_t k = 0; (double(k) + 0.5) <= F; ++k) t.push_back(float(woven * remap.inverse((double(k) + 0.5) / F)));
    return t;
}

// --- the op ------------------------------------------------------------------------------------------

namespace {

/// Per-guide quantities resolved before any output is allocated.
struct GuidePlan {
    double length = 0.0;
    double frequency = 0.0;
    double woven = 1.0;  // t_b, the woven fraction of the guide
    int64_t samples = 0;  // 0 = skipped
    float A = 0.0f, B = 0.0f;
    float strand_width = 0.0f;  // before the amplitude scale s(t)
};

/// Everything one guide's braid needs from the op's parameters.
struct Context {
    const BraidParams& params;
    const KnotRemap& remap;
    const BraidWeave& weave;
    const Surface* scalp;
    float margin;  // float slack added to every clearance so rounding never lands a point inside
};

/// Automatic frame-mode normal at the root: the scalp normal, else up (+Y) unless the guide starts
/// near vertical, where +Y would be nearly tangent and the frame ill-defined; then +Z (faces forward).
float3 initial_normal(const Context& ctx, const float3& root, const float3& tangent)
{
    if (length_squared(ctx.params.initial_normal) > 0.0f) return ctx.params.initial_normal;
    if (ctx.scalp) return ctx.scalp->normal(root);
    return std::fabs(tangent.y) > 0.906f ? float3(0, 0, 1) : float3(0, 1, 0);  // cos 25 deg
}

/// Amplitude scale s(t): root/tip blend times the taper spline, pinched around a tie.
float amplitude_scale(const BraidParams& p, const GuidePlan& plan, float t)
{
    const float blend = p.root_amplitude + (p.tip_amplitude - p.root_amplitude) * t;
    float s = p.taper.empty() ? blend : blend * sample_uniform_spline(p.taper, t);
    if (p.tie) {
        // A tie gathers the braid: the cross-section narrows to 60% within half a knot of it.
        const double knot = plan.frequency > 0.0 ? plan.woven * plan.length / plan.frequency : plan.length;
        const double d = std::fabs(double(t) - double(*p.tie)) * plan.length / (0.5 * knot);
        if (d < 1.0) s *= float(1.0 - 0.4 * 0.5 * (1.0 + std::cos(std::numbers::pi * d)));
    }
    return s;
}

/// Section lift statistics for one guide.
struct LiftStats {
    int64_t lifted = 0, lowered = 0;
    float max_lift = 0.0f, max_lower = 0.0f;
};

/// Builds the N strands of one guide into `dst` (curves first..first+N-1), their sections into `sec`,
/// and records, for each output point, the guide point nearest in arc length.
LiftStats braid_guide(const Context& ctx, const GuidePlan& plan, std::span<const float3> guide, int64_t guide_point0,
                      CurveSet& dst, int64_t first_curve, StrandSections& sec, std::span<int64_t> src_point)
{
    const BraidParams& p = ctx.params;
    const int N = p.strand_count();
    const int64_t S = plan.samples;
    const double len = plan.length;
    const double F = plan.frequency;
    const double tb = plan.woven;

    // Sample the guide evenly in arc length: t_j = j / (S - 1) (the talk's z = omega = Length / N_cv).
    const std::vector<double> cum = cumulative_lengths(guide);
    std::vector<float3> C(S);
    std::vector<float> t(S);
    for (int64_t j = 0; j < S; ++j) {
        t[j] = float(double(j) / double(S - 1));
        C[j] = j == S - 1 ? guide.back() : point_at_length(guide, cum, len * double(j) / double(S - 1));
        // Nearest guide point in arc length, for carrying the guide's point attributes.
        const size_t best = locate_at_length(cum, len * double(j) / double(S - 1)).nearest;
        for (int i = 0; i < N; ++i) src_point[dst.points_of(first_curve + i).begin + j] = guide_point0 + int64_t(best);
    }

    // Frames. Sec. 2.1: offsets are applied in orthonormal frames along the guide; rotation-minimising
    // ones do not flip at inflections. Cornrows replace the normal with the scalp normal.
    const std::vector<float3> tangents = polyline_tangents(C);
    std::vector<Frame> frames = rotation_minimising_frames(C, initial_normal(ctx, C[0], tangents[0]));
    if (p.orient == BraidOrient::Scalp) {
        for (int64_t j = 0; j < S; ++j) {
            const float3 ns = ctx.scalp->normal(C[j]);
            const float3 tj = frames[j].t;
            const float3 b = cross(tj, ns);
            // A guide running straight into the scalp has no tangent plane direction; keep the RMF frame.
            if (length(b) < 1e-3f) continue;
            frames[j].b = normalize(b);
            frames[j].n = cross(frames[j].b, tj);
        }
    }

    // Where the weave stops (t_b): each strand's offset there, and its place in the loose end's row
    // (strands ordered across by their offset at t_b, so none crosses another while they part).
    const double u_end = F;
    std::vector<WeaveOffset> end_offset(N);
    std::vector<double> row(N);
    if (tb < 1.0) {
        std::vector<int> order(N);
        for (int i = 0; i < N; ++i) {
            end_offset[i] = ctx.weave.at(i, u_end);
            order[i] = i;
        }
        std::sort(order.begin(), order.end(), [&](int a, int b) {
            return end_offset[a].x != end_offset[b].x ? end_offset[a].x < end_offset[b].x : a < b;
        });
        // Row spacing in units of A: the strands' own width, at least the weave's touching width.
        const double spacing = std::max(ctx.weave.touching_width(), plan.A > 0.0f ? double(plan.strand_width) / plan.A : 0.0);
        for (int r = 0; r < N; ++r) row[order[r]] = (double(r) - 0.5 * (N - 1)) * spacing;
    }

    auto P = dst.positions_for_write();
    auto W = dst.find_for_write<float>(Domain::Point, attr::width);
    std::vector<float> section_reach(S);  // how far the hair reaches beyond a centreline, per section
    const float inv_sqrt_m = p.fibers > 0 ? 1.0f / std::sqrt(float(p.fibers)) : 0.0f;
    for (int64_t j = 0; j < S; ++j) {
        const double tj = t[j];
        const bool loose = tj > tb;
        // Knot phase: F alpha(t / t_b) over the woven part, then held.
        const double a = loose ? 1.0 : (tb > 0.0 ? tj / tb : 1.0);
        const double u = F * (ctx.remap.identity() ? a : ctx.remap.alpha(a));
        // q: 0 where the loose end starts, 1 at the tip; e: its smooth ease.
        const double q = loose ? (tj - tb) / (1.0 - tb) : 0.0;
        const double e = q * q * (3.0 - 2.0 * q);
        const double spread = 1.0 + double(p.flare) * q;
        const float s = amplitude_scale(p, plan, t[j]);
        const double A = double(plan.A) * s, B = double(plan.B) * s;
        const float w = plan.strand_width * s;
        // With fibers the strand is an ellipse about w/2 across, filled with fibers of their own width.
        const float fiber_w = p.fibers > 0 ? (p.fiber_width > 0.0f ? p.fiber_width : w * inv_sqrt_m) : 0.0f;
        section_reach[j] = p.fibers > 0 ? float(0.5 * w * (kFiberSpreadAcross + 0.5 * p.flatten) * spread) + 0.5f * fiber_w : 0.5f * w;
        for (int i = 0; i < N; ++i) {
            WeaveOffset o = loose ? end_offset[i] : ctx.weave.at(i, u);
            if (loose) {
                // Unbraided: part from the weave's last section into a row that opens by the flare.
                o.x = ((1.0 - e) * o.x + e * row[i]) * spread;
                o.y *= 1.0 - e;
                o.press *= 1.0 - e;
            }
            const int64_t q_pt = dst.points_of(first_curve + i).begin + j;
            P[q_pt] = C[j] + frames[j].b * float(A * o.x) + frames[j].n * float(B * o.y);
            W[q_pt] = w;
            sec.centre[q_pt] = C[j];
            sec.lateral[q_pt] = frames[j].b;
            sec.up[q_pt] = frames[j].n;
            sec.phase[q_pt] = float(u);
            sec.press[q_pt] = float(o.press);
            sec.spread[q_pt] = float(spread);
            sec.t[q_pt] = t[j];
            sec.half_width[q_pt] = float(A + 0.5 * w);
            sec.half_height[q_pt] = float(B + 0.5 * w);
        }
    }

    LiftStats stats;
    if (!ctx.scalp) return stats;
    // Scalp intersections: each whole cross-section moves along the scalp normal (so the braid keeps its
    // shape) by the least amount that puts every strand's hair `clearance` off the scalp; with `rest`,
    // sections above that are lowered onto it (lift_outside, fields/keep_outside.h).
    const KeepOutside rule{p.clearance, ctx.margin, 32};
    std::vector<float3> section(N);
    for (int64_t j = 0; j < S; ++j) {
        const float3 dir = ctx.scalp->normal(C[j]);
        for (int i = 0; i < N; ++i) section[i] = P[dst.points_of(first_curve + i).begin + j];
        const double lift = lift_outside(section, dir, *ctx.scalp, rule, section_reach[j], p.rest);
        if (lift == 0.0) continue;
        for (int i = 0; i < N; ++i) {
            const int64_t q = dst.points_of(first_curve + i).begin + j;
            P[q] += dir * float(lift);
            sec.centre[q] += dir * float(lift);
        }
        if (lift > 0.0) {
            ++stats.lifted;
            stats.max_lift = std::max(stats.max_lift, float(lift));
        }
        else {
            ++stats.lowered;
            stats.max_lower = std::max(stats.max_lower, float(-lift));
        }
    }
    return stats;
}

/// The tie band of one guide: `turns` wraps of an ellipse around the pinched braid at params.tie,
/// advancing one band width per turn along the guide. Writes `count` points from `out`.
void tie_band(const BraidParams& p, const CurveSet& strands, const StrandSections& sec, int64_t first_strand, int N,
              float band_width, double strand_length, std::span<float3> out)
{
    // The strand sample nearest the tie: every strand of a guide shares the guide's samples.
    const IndexRange r0 = strands.points_of(first_strand);
    const int64_t S = r0.size();
    const int64_t j = std::clamp<int64_t>(int64_t(std::lround(double(*p.tie) * double(S - 1))), 0, S - 1);
    const auto P = strands.positions();
    const auto W = strands.find<float>(Domain::Point, attr::width);
    const int64_t q0 = r0.begin + j;
    const float3 c = sec.centre[q0], b = sec.lateral[q0], n = sec.up[q0];
    const float3 tan = normalize(cross(b, n));
    // Reach of the strands' hair from the centre, across and up, over the stretch the band covers.
    const double len = double(strand_length);
    const double half_span = 0.5 * double(p.tie_turns) * band_width + band_width;
    float rx = 0.0f, ry = 0.0f;
    for (int64_t jj = 0; jj < S; ++jj) {
        if (std::fabs(double(jj - j)) / double(S - 1) * len > half_span) continue;
        const int64_t qc = r0.begin + jj;
        for (int i = 0; i < N; ++i) {
            const int64_t q = strands.points_of(first_strand + i).begin + jj;
            const float3 d = P[q] - sec.centre[qc];
            const float hw = 0.5f * W[q] * (kFiberSpreadAcross + 0.5f * p.flatten);
            rx = std::max(rx, std::fabs(dot(d, b)) + hw);
            ry = std::max(ry, std::fabs(dot(d, n)) + hw);
        }
    }
    rx += 0.5f * band_width;
    ry += 0.5f * band_width;
    const int64_t count = int64_t(out.size());
    const double span = double(p.tie_turns) * band_width;
    for (int64_t k = 0; k < count; ++k) {
        const double f = double(k) / double(count - 1);
        const double ang = 2.0 * std::numbers::pi * p.tie_turns * f;
        out[k] = c + b * float(rx * std::cos(ang)) + n * float(ry * std::sin(ang)) + tan * float((f - 0.5) * span);
    }
}

}  // namespace

BraidResult braid(const CurveSet& guides, const BraidParams& params, const Surface* scalp, Progress* progress)
{
    params.validate();
    if (params.orient == BraidOrient::Scalp && !scalp) {
        throw InvalidParam("braid: --orient scalp needs a scalp (give --scalp SCALP)");
    }
    if (!scalp && (params.rest || params.clearance > 0.0f)) {
        throw InvalidParam(std::string("braid: ") + (params.rest ? "--rest" : "--clearance") + " needs a scalp (give --scalp SCALP)");
    }
    const KnotRemap remap(params);
    const int N = params.strand_count();
    const BraidWeave weave(params.pattern, N, params.pattern == BraidPattern::Lissajous ? BraidHand::Over : params.resolved_hand());
    const auto GP = guides.positions();
    const size_t ng = guides.num_curves();
    const int64_t M = params.fibers;
    // Points per knot where knots are densest: smooth crossings need a few samples per weave step.
    const double per_knot = params.pattern == BraidPattern::Plait || params.pattern == BraidPattern::Fishtail
                                ? std::max(16.0, 4.0 * 2.0 * N)
                            : params.pattern == BraidPattern::Round ? std::max(16.0, 4.0 * N)
                                                                    : 16.0;

    // The closest approach of strands for an amplitude pair and knot length, measured once per distinct
    // triple (guides braided with --knot-length share one).
    const bool helical = params.pattern == BraidPattern::Rope || params.pattern == BraidPattern::Twist ||
                         params.pattern == BraidPattern::Round;
    std::mutex separation_mutex;
    std::map<std::tuple<float, float, double>, double> separation_cache;
    const auto separation = [&](float A, float B, double knot) {
        const auto key = std::make_tuple(A, B, knot);
        {
            const std::lock_guard<std::mutex> lock(separation_mutex);
            const auto it = separation_cache.find(key);
            if (it != separation_cache.end()) return it->second;
        }
        const double d = weave.min_separation(A, B, knot);
        const std::lock_guard<std::mutex> lock(separation_mutex);
        separation_cache.emplace(key, d);
        return d;
    };

    // Plan each guide: length, F, sample count, amplitudes.
    std::vector<GuidePlan> plans(ng);
    parallel_for(int64_t(ng), 256, [&](int64_t begin, int64_t end) {
        for (int64_t g = begin; g < end; ++g) {
            const IndexRange r = guides.points_of(g);
            GuidePlan& plan = plans[g];
            plan.length = cumulative_lengths(GP.subspan(r.begin, r.size())).back();
            if (r.size() < 2 || !(plan.length > 0.0)) continue;  // nothing to braid along: skipped
            plan.frequency = braid_frequency(params, plan.length);
            plan.woven = woven_fraction(params, plan.length);
            const double woven_len = plan.woven * plan.length;
            const double knot = plan.frequency > 0.0 && woven_len > 0.0 ? woven_len / plan.frequency : plan.length;
            plan.A = params.width ? *params.width : float(knot / 3.0);
            plan.B = params.height ? *params.height : float(plan.A * weave.touching_height());
            if (!params.width && params.pattern != BraidPattern::Lissajous && !(params.strand_width > 0.0f) &&
                !(params.fibers > 0 && params.fiber_radius > 0.0f)) {
                // Automatic width: the widest braid whose strands, at the width where neighbours touch,
                // still keep 0.85 widths apart along the knot (a tight braid, neither gapped nor
                // interpenetrating). Shrink A until the touching width fits; a few steps converge.
                for (int iter = 0; iter < 4; ++iter) {
                    const double fit = separation(plan.A, plan.B, knot) / 0.85 / weave.touching_width();
                    if (fit >= 0.999 * plan.A) break;
                    plan.A = float(fit);
                    if (!params.height) plan.B = float(plan.A * weave.touching_height());
                }
            }
            if (params.fibers > 0 && params.fiber_radius > 0.0f) plan.strand_width = 2.0f * params.fiber_radius;
            else if (params.strand_width > 0.0f) plan.strand_width = params.strand_width;
            else if (plan.A > 0.0f && params.pattern == BraidPattern::Lissajous) {
                // The talk's formula as written: strands of an even N pass through each other, so there
                // is no touching width to keep; the width of earlier releases, 2 max(A, B) / N.
                plan.strand_width = 2.0f * std::max(plan.A, plan.B) / float(N);
            }
            else if (plan.A > 0.0f) {
                // Automatic: as thick as the weave lets neighbours touch, but no thicker than keeps every
                // two strands' centrelines 0.85 widths apart (a braid wide for its knot length has
                // steep strands that pass close to the one that went through the same place a step
                // before). A plait's automatic height then puts crossing strands 1.1 widths apart.
                const double sep = separation(plan.A, plan.B, knot);
                double w = std::min(double(plan.A) * weave.touching_width(), sep / 0.85);
                if (!params.height && !helical) {
                    plan.B = float(0.55 * w);
                    w = std::min(w, separation(plan.A, plan.B, knot) / 0.85);
                }
                // A flat braid asked for (--height 0) has no separation to keep: keep a visible strand.
                plan.strand_width = float(std::max(w, 0.1 * double(plan.A) * weave.touching_width()));
            }
            else plan.strand_width = plan.B > 0.0f ? 2.0f * plan.B / float(N) : float(0.01 * plan.length);
            // Automatic: enough points per knot where alpha is steepest, >= the guide's own detail.
            const double cycles = plan.frequency * remap.max_slope() / std::max(plan.woven, 1e-3);
            const double want = params.samples > 0 ? double(params.samples)
                                                   : std::max({std::ceil(per_knot * cycles) + 1.0, double(r.size()), 8.0});
            plan.samples = int64_t(std::min(want, 1e12));
        }
    });

    BraidReport report;
    double total_points = 0.0;
    std::vector<int64_t> strand_counts;
    std::vector<int64_t> first_strand(ng, -1);
    const std::vector<int64_t> guide_ids = guides.curve_ids();
    for (size_t g = 0; g < ng; ++g) {
        if (plans[g].samples == 0) {
            ++report.skipped_guides;
            continue;
        }
        ++report.guides;
        total_points += double(plans[g].samples) * N * double(std::max<int64_t>(M, 1));
        if (total_points > double(kMaxBraidPoints)) {
            throw LimitExceeded("braid: the output would have more than " + std::to_string(kMaxBraidPoints) +
                                " points; lower --samples, --fibers, --strands or --frequency");
        }
        // id = (guide id * N + strand) * M + fiber must not overflow, so ids stay unique.
        const int64_t id = guide_ids[g];
        const int64_t per_guide = int64_t(N) * std::max<int64_t>(M, 1);
        if (id > (std::numeric_limits<int64_t>::max() - per_guide) / per_guide ||
            id < std::numeric_limits<int64_t>::min() / per_guide + 1) {
            throw LimitExceeded("braid: guide id " + std::to_string(id) + " times " + std::to_string(N) + " strands" +
                                (M > 0 ? " times " + std::to_string(M) + " fibers" : std::string()) +
                                " overflows a 64-bit id");
        }
        first_strand[g] = int64_t(strand_counts.size());
        for (int i = 0; i < N; ++i) strand_counts.push_back(plans[g].samples);
    }

    // Count -> scan -> fill: strand centrelines first.
    CurveSet strands = CurveSet::from_counts(strand_counts);
    strands.add<float>(Domain::Point, attr::width);
    auto guide_col = strands.add<int32_t>(Domain::Curve, "guide");
    auto strand_col = strands.add<int32_t>(Domain::Curve, "strand");
    auto id_col = strands.add<int64_t>(Domain::Curve, attr::id);
    std::vector<int64_t> src_curve(strands.num_curves());
    for (size_t g = 0; g < ng; ++g) {
        if (first_strand[g] < 0) continue;
        for (int i = 0; i < N; ++i) {
            const int64_t c = first_strand[g] + i;
            guide_col[c] = int32_t(g);
            strand_col[c] = i;
            id_col[c] = guide_ids[g] * N + i;
            src_curve[c] = int64_t(g);
        }
    }

    // Float slack relative to the scene's size: a few ulps of the largest coordinate.
    const Bounds3 bounds = guides.bounds();
    const float extent = bounds.empty() ? 1.0f
                                        : std::max({std::fabs(bounds.lo.x), std::fabs(bounds.lo.y), std::fabs(bounds.lo.z),
                                                    std::fabs(bounds.hi.x), std::fabs(bounds.hi.y), std::fabs(bounds.hi.z), 1e-3f});
    const Context ctx{params, remap, weave, scalp, 8.0f * extent * std::numeric_limits<float>::epsilon()};

    StrandSections sec;
    sec.resize(strands.num_points());
    std::vector<int64_t> src_point(strands.num_points());
    std::vector<LiftStats> stats(ng);
    {
        const ProgressStep step(progress, "braid", int64_t(ng));
        parallel_for(int64_t(ng), 4, [&](int64_t begin, int64_t end) {
            for (int64_t g = begin; g < end; ++g) {
                if (first_strand[g] >= 0) {
                    const IndexRange r = guides.points_of(g);
                    stats[g] = braid_guide(ctx, plans[g], GP.subspan(r.begin, r.size()), r.begin, strands, first_strand[g],
                                           sec, src_point);
                }
                step.advance(1);
            }
        });
    }
    for (const LiftStats& s : stats) {
        report.lifted_sections += s.lifted;
        report.lowered_sections += s.lowered;
        report.max_lift = std::max(report.max_lift, s.max_lift);
        report.max_lower = std::max(report.max_lower, s.max_lower);
    }
    carry_curve_attributes(guides, strands, src_curve);
    carry_point_attributes(guides, strands, src_point, {attr::P});
    report.strands = int64_t(strands.num_curves());

    // Hair: the strands themselves, or M fibers each.
    CurveSet hair;
    std::vector<float> offset_reach;  // per hair point: how far it lies from its strand point
    std::vector<int64_t> hair_strand_point;
    if (M > 0) {
        std::vector<StrandFiberPlan> fplans(strands.num_curves());
        for (size_t g = 0; g < ng; ++g) {
            if (first_strand[g] < 0) continue;
            const GuidePlan& plan = plans[g];
            const double woven_len = plan.woven * plan.length;
            const double knot = plan.frequency > 0.0 && woven_len > 0.0 ? woven_len / plan.frequency : plan.length;
            for (int i = 0; i < N; ++i) {
                StrandFiberPlan& f = fplans[first_strand[g] + i];
                f.knot_t = float(knot / plan.length);
                f.feed_t = float(std::min((params.feed_length > 0.0f ? double(params.feed_length) : 3.0 * knot) / plan.length, 1.0));
            }
        }
        FiberStats fs;
        hair = braid_fibers(strands, sec, fplans, params, weave, fs, offset_reach, hair_strand_point, progress);
        report.flyaways = fs.flyaways;
        report.fed_in = fs.fed_in;
    }
    else {
        hair = std::move(strands);
    }
    auto kind_hair = hair.add<int32_t>(Domain::Curve, "kind");
    std::fill(kind_hair.begin(), kind_hair.end(), 0);

    // Ties: one band per guide, appended after the hair.
    CurveSet out;
    if (params.tie) {
        const CurveSet& strand_src = M > 0 ? strands : hair;
        constexpr int64_t kTiePointsPerTurn = 24;
        const int64_t tie_points = kTiePointsPerTurn * params.tie_turns + 1;
        std::vector<int64_t> counts(hair.num_curves(), 0);
        const auto hair_offsets = hair.offsets();
        for (size_t c = 0; c < hair.num_curves(); ++c) counts[c] = hair_offsets[c + 1] - hair_offsets[c];
        std::vector<int64_t> tie_guide;
        for (size_t g = 0; g < ng; ++g) {
            if (first_strand[g] < 0) continue;
            counts.push_back(tie_points);
            tie_guide.push_back(int64_t(g));
        }
        out = CurveSet::from_counts(counts);
        const int64_t nh = int64_t(hair.num_curves());
        std::vector<int64_t> tie_src_curve(out.num_curves()), tie_src_point(out.num_points());
        for (int64_t c = 0; c < nh; ++c) tie_src_curve[c] = c;
        for (int64_t p = 0; p < int64_t(hair.num_points()); ++p) tie_src_point[p] = p;
        auto oP = out.positions_for_write();
        const auto hP = hair.positions();
        std::copy(hP.begin(), hP.end(), oP.begin());
        auto ow = out.add<float>(Domain::Point, attr::width);
        const auto hw = hair.find<float>(Domain::Point, attr::width);
        std::copy(hw.begin(), hw.end(), ow.begin());
        auto oid = out.add<int64_t>(Domain::Curve, attr::id);
        auto okind = out.add<int32_t>(Domain::Curve, "kind");
        auto ostrand = out.add<int32_t>(Domain::Curve, "strand");
        const auto hid = hair.find<int64_t>(Domain::Curve, attr::id);
        const auto hstrand = hair.find<int32_t>(Domain::Curve, "strand");
        std::copy(hid.begin(), hid.end(), oid.begin());
        std::copy(hstrand.begin(), hstrand.end(), ostrand.begin());
        std::fill(okind.begin(), okind.begin() + nh, 0);
        std::span<int32_t> ofiber;
        if (M > 0) {
            ofiber = out.add<int32_t>(Domain::Curve, "fiber");
            const auto hf = hair.find<int32_t>(Domain::Curve, "fiber");
            std::copy(hf.begin(), hf.end(), ofiber.begin());
        }
        int64_t tie_id0 = 0;
        for (const int64_t id : hid) tie_id0 = std::max(tie_id0, id + 1);
        if (tie_id0 > std::numeric_limits<int64_t>::max() - int64_t(tie_guide.size())) {
            throw LimitExceeded("braid: tie ids past the largest hair id overflow a 64-bit id; lower the guide ids");
        }
        for (size_t k = 0; k < tie_guide.size(); ++k) {
            const int64_t g = tie_guide[k];
            const int64_t c = nh + int64_t(k);
            const int64_t fs = first_strand[g];
            const IndexRange r = out.points_of(c);
            const float sw = strand_src.find<float>(Domain::Point, attr::width)[strand_src.points_of(fs).begin];
            const float band = params.tie_width > 0.0f ? params.tie_width : 0.35f * std::max(sw, 1e-6f);
            tie_band(params, strand_src, sec, fs, N, band, plans[g].length, oP.subspan(r.begin, r.size()));
            for (int64_t p = r.begin; p < r.end; ++p) ow[p] = band;
            // After every hair id (not negative: tinyusdz, and so some USD readers, refuse negative int64s).
            oid[c] = tie_id0 + int64_t(k);
            okind[c] = 1;
            ostrand[c] = -1;
            if (M > 0) ofiber[c] = -1;
            // Curve attributes from the guide's first hair curve, point attributes from its first point.
            const int64_t first_hair = M > 0 ? fs * M : fs;
            tie_src_curve[c] = first_hair;
            for (int64_t p = r.begin; p < r.end; ++p) tie_src_point[p] = hair.points_of(first_hair).begin;
        }
        carry_curve_attributes(hair, out, tie_src_curve);
        carry_point_attributes(hair, out, tie_src_point, {attr::P, attr::width});
        report.ties = int64_t(tie_guide.size());
        offset_reach.resize(out.num_points(), std::numeric_limits<float>::infinity());
        hair_strand_point.resize(out.num_points(), -1);
    }
    else {
        out = std::move(hair);
    }

    if (scalp) {
        // Which points need no scalp query: a signed distance changes no faster than the point moves,
        // so a hair point within `reach` of its strand point keeps clearance where the strand point
        // keeps clearance + reach + its half width. Saves a query per fiber point.
        std::vector<uint8_t> known_clear;
        if (M > 0) {
            const auto SP = strands.positions();
            std::vector<float> strand_dist(strands.num_points());
            parallel_for(int64_t(strands.num_points()), 1024, [&](int64_t begin, int64_t end) {
                for (int64_t q = begin; q < end; ++q) strand_dist[q] = scalp->distance(SP[q]);
            });
            const auto W = out.find<float>(Domain::Point, attr::width);
            known_clear.assign(out.num_points(), 0);
            parallel_for(int64_t(out.num_points()), 4096, [&](int64_t begin, int64_t end) {
                for (int64_t q = begin; q < end; ++q) {
                    const int64_t sp = hair_strand_point[q];
                    if (sp < 0) continue;
                    known_clear[q] = strand_dist[sp] - offset_reach[q] >= params.clearance + 0.5f * W[q] + ctx.margin;
                }
            });
        }
        // Last resort after the section lifts: a point still closer than clearance + half its width
        // moves out on its own.
        report.pushed_points = keep_outside(out.positions_for_write(), *scalp, KeepOutside{params.clearance, ctx.margin, 8},
                                            out.find<float>(Domain::Point, attr::width), known_clear, progress);
    }
    report.curves = int64_t(out.num_curves());
    report.points = int64_t(out.num_points());
    return {std::move(out), report};
}

}  // namespace groom
