#include "ops/braid_plan.h"

#include "kernel/math/polyline.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

namespace groom {

std::vector<GuidePlan> plan_guides(const CurveSet& guides, const BraidParams& params, const KnotRemap& remap,
                                   const BraidWeave& weave)
{
    const int N = params.strand_count();
    const auto GP = guides.positions();
    const size_t ng = guides.num_curves();
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
            if (r.size() < 2) continue;  // nothing to braid along (a file may hold empty curves): skipped
            plan.length = cumulative_lengths(GP.subspan(r.begin, r.size())).back();
            if (!(plan.length > 0.0)) continue;
            plan.frequency = braid_frequency(params, plan.length);
            plan.woven = braid_woven_fraction(params, plan.length);
            const double knot = plan.knot_length();
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
    return plans;
}

}  // namespace groom
