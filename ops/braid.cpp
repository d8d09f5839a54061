#include "ops/braid.h"

#include "kernel/error.h"
#include "kernel/math/frames.h"
#include "kernel/math/polyline.h"
#include "kernel/math/spline.h"
#include "kernel/parallel.h"
#include "ops/populate.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
    if (strands < 2) throw InvalidParam("braid: --strands must be >= 2 (got " + std::to_string(strands) + ")");
    if (strands > 4096) throw InvalidParam("braid: --strands must be <= 4096 (got " + std::to_string(strands) + ")");
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
    if (params.knot_length) return guide_length / *params.knot_length;
    return BraidParams::kDefaultFrequency;
}

std::vector<float> braid_knot_parameters(const BraidParams& params, double guide_length)
{
    params.validate();
    const double F = braid_frequency(params, guide_length);
    if (F > 1e8) {
        throw LimitExceeded("braid: " + fmt(F) + " knots on one guide is more than 1e8; raise --knot-length or lower --frequency");
    }
    const KnotRemap remap(params);
    std::vector<float> t;
    for (int64_t k = 0; (double(k) + 0.5) <= F; ++k) t.push_back(float(remap.inverse((double(k) + 0.5) / F)));
    return t;
}

// --- the op ------------------------------------------------------------------------------------------

namespace {

/// Per-guide quantities resolved before any output is allocated.
struct GuidePlan {
    double length = 0.0;
    double frequency = 0.0;
    int64_t samples = 0;  // 0 = skipped
    float A = 0.0f, B = 0.0f;
    float strand_width = 0.0f;  // before the amplitude scale s(t)
};

/// Everything one guide's braid needs from the op's parameters.
struct Context {
    const BraidParams& params;
    const KnotRemap& remap;
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

/// Amplitude scale s(t): root/tip blend times the taper spline.
float amplitude_scale(const BraidParams& p, float t)
{
    const float blend = p.root_amplitude + (p.tip_amplitude - p.root_amplitude) * t;
    return p.taper.empty() ? blend : blend * sample_uniform_spline(p.taper, t);
}

/// Section lift statistics for one guide.
struct LiftStats {
    int64_t lifted = 0, lowered = 0;
    float max_lift = 0.0f, max_lower = 0.0f;
};

/// Builds the N strands of one guide into `dst` (curves first..first+N-1) and records, for each
/// output point, the guide point nearest in arc length.
LiftStats braid_guide(const Context& ctx, const GuidePlan& plan, std::span<const float3> guide, int64_t guide_point0,
                      CurveSet& dst, int64_t first_curve, std::span<int64_t> src_point)
{
    const BraidParams& p = ctx.params;
    const int N = p.strands;
    const int64_t S = plan.samples;
    const double len = plan.length;
    const double F = plan.frequency;

    // Sample the guide evenly in arc length: t_j = j / (S - 1) (the talk's z = omega = Length / N_cv).
    const std::vector<double> cum = cumulative_lengths(guide);
    std::vector<float3> C(S);
    std::vector<float> t(S);
    for (int64_t j = 0; j < S; ++j) {
        t[j] = float(double(j) / double(S - 1));
        C[j] = j == S - 1 ? guide.back() : point_at_length(guide, cum, len * double(j) / double(S - 1));
        // Nearest guide point in arc length, for carrying the guide's point attributes.
        const double s = len * double(j) / double(S - 1);
        const size_t k = std::lower_bound(cum.begin(), cum.end(), s) - cum.begin();
        size_t best = std::min(k, cum.size() - 1);
        if (k > 0 && (k == cum.size() || s - cum[k - 1] < cum[k] - s)) best = k - 1;
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

    auto P = dst.positions();
    auto W = dst.find<float>(Domain::Point, attr::width);
    std::vector<float> section_reach(S);  // how far the hair reaches beyond a centreline, per section
    const float inv_sqrt_m = p.fibers > 0 ? 1.0f / std::sqrt(float(p.fibers)) : 0.0f;
    for (int64_t j = 0; j < S; ++j) {
        const double alpha = ctx.remap.identity() ? double(t[j]) : ctx.remap.alpha(t[j]);
        const float s = amplitude_scale(p, t[j]);
        const double A = double(plan.A) * s, B = double(plan.B) * s;
        const float w = plan.strand_width * s;
        // With fibers the strand is a disc of radius w/2 filled with fibers of their own width.
        const float fiber_w = p.fibers > 0 ? (p.fiber_width > 0.0f ? p.fiber_width : w * inv_sqrt_m) : 0.0f;
        section_reach[j] = p.fibers > 0 ? 0.5f * w + 0.5f * fiber_w : 0.5f * w;
        const double fa = F * alpha;
        for (int i = 0; i < N; ++i) {
            // Sec. 2.1: Lissajous cross-section, beta / alpha = 1/2, delta_i = i / N. Phases are reduced
            // in double so large F keeps full float precision.
            const double delta = double(i) / N;
            double px = fa + delta, py = 0.5 * fa - delta;
            px -= std::floor(px);
            py -= std::floor(py);
            const double x = A * std::sin(2.0 * std::numbers::pi * px);
            const double y = B * std::sin(2.0 * std::numbers::pi * py);
            const int64_t q = dst.points_of(first_curve + i).begin + j;
            P[q] = C[j] + frames[j].b * float(x) + frames[j].n * float(y);
            W[q] = w;
        }
    }

    LiftStats stats;
    if (!ctx.scalp) return stats;
    // Scalp intersections: move each whole cross-section along the scalp normal (so the braid keeps its
    // shape) by the least amount that puts every strand's hair `clearance` off the scalp; with `rest`,
    // sections above that are lowered onto it. Iterated because off-centre strands move by less than
    // the lift where the scalp curves.
    for (int64_t j = 0; j < S; ++j) {
        const float3 dir = ctx.scalp->normal(C[j]);
        const float need = p.clearance + section_reach[j] + ctx.margin;
        double lift = 0.0;
        for (int iter = 0; iter < 32; ++iter) {
            float worst = std::numeric_limits<float>::infinity();
            for (int i = 0; i < N; ++i) {
                const int64_t q = dst.points_of(first_curve + i).begin + j;
                worst = std::min(worst, ctx.scalp->distance(P[q] + dir * float(lift)) - need);
            }
            const double next = p.rest ? lift - worst : std::max(lift - worst, 0.0);
            const bool done = std::fabs(next - lift) <= ctx.margin;
            lift = next;
            if (done) break;
        }
        if (lift == 0.0) continue;
        for (int i = 0; i < N; ++i) P[dst.points_of(first_curve + i).begin + j] += dir * float(lift);
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

/// Last resort after section lifts: any point still closer than clearance + half its width is pushed
/// out along the scalp normal alone. Points flagged in `known_clear` (may be empty) are not queried.
/// Returns how many points moved.
int64_t push_out(CurveSet& cs, const Surface& scalp, float clearance, float margin, std::span<const uint8_t> known_clear,
                 Progress* progress)
{
    auto P = cs.positions();
    const auto W = cs.find<float>(Domain::Point, attr::width);
    const int64_t n = int64_t(cs.num_points());
    std::vector<uint8_t> moved(n, 0);
    const ProgressStep step(progress, "scalp clearance", n);
    parallel_for(n, 4096, [&](int64_t begin, int64_t end) {
        for (int64_t q = begin; q < end; ++q) {
            if (!known_clear.empty() && known_clear[q]) continue;
            const float need = clearance + 0.5f * W[q];
            for (int iter = 0; iter < 8; ++iter) {
                const float d = scalp.distance(P[q]);
                if (d >= need) break;
                P[q] += scalp.normal(P[q]) * (need + margin - d);
                moved[q] = 1;
            }
        }
        step.advance(end - begin);
    });
    int64_t count = 0;
    for (const uint8_t m : moved) count += m;
    return count;
}

/// Which fiber points need no scalp query: a fiber point lies within its strand's disc radius r of the
/// strand point it was offset from, and a signed distance changes no faster than the point moves, so
/// where the strand point keeps clearance + r + fiber width / 2 every fiber point there keeps
/// clearance + fiber width / 2. Saves one distance query per fiber point (M of them per strand point).
std::vector<uint8_t> fibers_known_clear(const CurveSet& strands, const CurveSet& fibers, const Surface& scalp,
                                        const BraidParams& params)
{
    const auto SP = strands.positions();
    const auto SW = strands.find<float>(Domain::Point, attr::width);
    const int64_t M = params.fibers;
    const float inv_sqrt_m = 1.0f / std::sqrt(float(M));
    std::vector<uint8_t> strand_clear(strands.num_points());
    parallel_for(int64_t(strands.num_points()), 1024, [&](int64_t begin, int64_t end) {
        for (int64_t q = begin; q < end; ++q) {
            const float fiber_w = params.fiber_width > 0.0f ? params.fiber_width : SW[q] * inv_sqrt_m;
            strand_clear[q] = scalp.distance(SP[q]) >= params.clearance + 0.5f * SW[q] + 0.5f * fiber_w;
        }
    });
    // populate() lays fiber f of strand c out as curve c * M + f with the strand's point count.
    std::vector<uint8_t> clear(fibers.num_points());
    parallel_for(int64_t(fibers.num_curves()), 256, [&](int64_t begin, int64_t end) {
        for (int64_t fc = begin; fc < end; ++fc) {
            const IndexRange d = fibers.points_of(fc), s = strands.points_of(fc / M);
            for (int64_t j = 0; j < d.size(); ++j) clear[d.begin + j] = strand_clear[s.begin + j];
        }
    });
    return clear;
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
    const auto GP = guides.positions();
    const size_t ng = guides.num_curves();
    const int N = params.strands;
    const int64_t M = params.fibers;

    // Plan each guide: length, F, sample count, amplitudes.
    std::vector<GuidePlan> plans(ng);
    parallel_for(int64_t(ng), 256, [&](int64_t begin, int64_t end) {
        for (int64_t g = begin; g < end; ++g) {
            const IndexRange r = guides.points_of(g);
            GuidePlan& plan = plans[g];
            plan.length = cumulative_lengths(GP.subspan(r.begin, r.size())).back();
            if (r.size() < 2 || !(plan.length > 0.0)) continue;  // nothing to braid along: skipped
            plan.frequency = braid_frequency(params, plan.length);
            const double knot = plan.frequency > 0.0 ? plan.length / plan.frequency : plan.length;
            plan.A = params.width ? *params.width : float(knot / 3.0);
            plan.B = params.height ? *params.height : 0.5f * plan.A;
            plan.strand_width = params.fibers > 0 && params.fiber_radius > 0.0f ? 2.0f * params.fiber_radius
                                : params.strand_width > 0.0f                     ? params.strand_width
                                : std::max(plan.A, plan.B) > 0.0f                ? 2.0f * std::max(plan.A, plan.B) / float(N)
                                                                                 : float(0.01 * plan.length);
            // Automatic: >= 16 points per x cycle where alpha is steepest, >= the guide's own detail.
            const double cycles = plan.frequency * remap.max_slope();
            const double want = params.samples > 0 ? double(params.samples)
                                                   : std::max({std::ceil(16.0 * cycles) + 1.0, double(r.size()), 8.0});
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
        // id = guide id * N + strand must not overflow (populate checks the fiber factor).
        const int64_t id = guide_ids[g];
        if (id > (std::numeric_limits<int64_t>::max() - N) / N || id < std::numeric_limits<int64_t>::min() / N) {
            throw LimitExceeded("braid: guide id " + std::to_string(id) + " times " + std::to_string(N) +
                                " strands overflows a 64-bit id");
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
    const Context ctx{params, remap, scalp, 8.0f * extent * std::numeric_limits<float>::epsilon()};

    std::vector<int64_t> src_point(strands.num_points());
    std::vector<LiftStats> stats(ng);
    {
        const ProgressStep step(progress, "braid", int64_t(ng));
        parallel_for(int64_t(ng), 4, [&](int64_t begin, int64_t end) {
            for (int64_t g = begin; g < end; ++g) {
                if (first_strand[g] >= 0) {
                    const IndexRange r = guides.points_of(g);
                    stats[g] = braid_guide(ctx, plans[g], GP.subspan(r.begin, r.size()), r.begin, strands, first_strand[g],
                                           src_point);
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

    CurveSet out;
    std::vector<uint8_t> known_clear;
    if (M > 0) {
        // Each strand's width is its fiber disc's diameter (see plan.strand_width), so populate takes
        // the radius from it and the taper carries over.
        PopulateParams pop;
        pop.count = int(M);
        pop.radius = 0.0f;
        pop.width = params.fiber_width;
        pop.seed = params.seed;
        out = populate(strands, pop, progress);
        if (scalp) known_clear = fibers_known_clear(strands, out, *scalp, params);
    }
    else {
        out = std::move(strands);
    }
    if (scalp) report.pushed_points = push_out(out, *scalp, params.clearance, ctx.margin, known_clear, progress);
    report.curves = int64_t(out.num_curves());
    report.points = int64_t(out.num_points());
    return {std::move(out), report};
}

}  // namespace groom
