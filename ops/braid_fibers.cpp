#include "ops/braid_fibers.h"
#include "ops/braid_plan.h"

#include "kernel/math/polyline.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace groom {

namespace {

/// Rng stream for a fiber's draws; a distinct constant per purpose (kernel/rng.h).
constexpr uint64_t kStreamBraidFiber = 0x62726169646669ull;  // "braidfi"
constexpr double kTwoPi = 2.0 * std::numbers::pi;


/// What one fiber drew: its place in the strand's cross-section, its flyaway loop, where it joins.
struct FiberDraw {
    float rho = 0.0f, phi = 0.0f;  // polar place in the unit disc
    bool flyaway = false;
    float loop_t = 0.0f, loop_half_t = 0.0f, loop_height = 0.0f;  // centre, half-length (t), height scale
    bool feeds = false;
    float join_t = 0.0f;
    float side = 1.0f;  // which side of the braid a feeding fiber comes from
};

FiberDraw draw_fiber(const BraidParams& p, const StrandFiberPlan& plan, uint64_t fiber_id)
{
    Rng rng(p.seed, fiber_id, kStreamBraidFiber);
    FiberDraw d;
    float u = 0.0f, v = 0.0f;
    rng.disc(u, v);
    d.rho = std::sqrt(u * u + v * v);
    d.phi = std::atan2(v, u);
    // Always draw every value, so changing one option never moves another's randomness.
    const float fly = rng.uniform(), loop_pos = rng.uniform(), loop_len = rng.uniform(), loop_h = rng.uniform();
    const float feed = rng.uniform(), join = rng.uniform(), side = rng.uniform();
    d.flyaway = fly < p.flyaways;
    d.loop_half_t = plan.knot_t * (0.25f + 0.35f * loop_len);
    d.loop_t = d.loop_half_t + loop_pos * std::max(1.0f - 2.0f * d.loop_half_t, 0.0f);
    d.loop_height = 0.6f + 0.8f * loop_h;
    d.feeds = feed < p.feed_in;
    d.join_t = plan.feed_t * std::max(join, 1e-3f);
    d.side = side < 0.5f ? -1.0f : 1.0f;
    return d;
}

/// First strand sample a fiber uses (a feeding fiber starts where it joins; at least two points).
int64_t first_sample(const FiberDraw& d, std::span<const float> t)
{
    if (!d.feeds) return 0;
    const int64_t S = int64_t(t.size());
    const int64_t j = std::lower_bound(t.begin(), t.end(), d.join_t) - t.begin();
    return std::clamp<int64_t>(j, 0, std::max<int64_t>(S - 2, 0));
}

}  // namespace

CurveSet braid_fibers(const CurveSet& strands, const StrandSections& sec, std::span<const StrandFiberPlan> plans,
                      const BraidParams& p, const BraidWeave& weave, const Surface* scalp, FiberStats& stats,
                      std::vector<float>& reach, std::vector<int64_t>& strand_point, Progress* progress)
{
    const int64_t M = p.fibers;
    const int64_t nc = int64_t(strands.num_curves());
    const std::vector<int64_t> ids = strands.curve_ids();
    const auto SP = strands.positions();
    const auto SW = strands.find<float>(Domain::Point, attr::width);
    const std::span<const float> T = sec.t;

    // Count -> scan -> fill.
    std::vector<int64_t> counts(nc * M);
    std::vector<uint8_t> fly(nc * M), feeds(nc * M);
    parallel_for(nc, 64, [&](int64_t begin, int64_t end) {
        for (int64_t c = begin; c < end; ++c) {
            const IndexRange r = strands.points_of(c);
            for (int64_t f = 0; f < M; ++f) {
                const FiberDraw d = draw_fiber(p, plans[c], uint64_t(ids[c] * M + f));
                counts[c * M + f] = r.size() - first_sample(d, T.subspan(r.begin, r.size()));
                fly[c * M + f] = d.flyaway;
                feeds[c * M + f] = d.feeds;
            }
        }
    });
    for (size_t k = 0; k < fly.size(); ++k) {
        stats.flyaways += fly[k];
        stats.fed_in += feeds[k];
    }
    CurveSet dst = CurveSet::from_counts(counts);
    auto dP = dst.positions_for_write();
    auto dW = dst.add<float>(Domain::Point, attr::width);
    auto dfiber = dst.add<int32_t>(Domain::Curve, "fiber");
    auto did = dst.add<int64_t>(Domain::Curve, attr::id);
    std::vector<int64_t> src_curve(dst.num_curves());
    reach.assign(dst.num_points(), 0.0f);
    strand_point.assign(dst.num_points(), 0);

    // A rope's or twist's fibers turn against the lay of its plies; a plait's strands twist gently.
    const double twist = double(p.fiber_twist) * (weave.winding() != 0 ? weave.winding() : -1);
    const float inv_sqrt_m = 1.0f / std::sqrt(float(M));
    const bool on_scalp = p.orient == BraidOrient::Scalp;
    // A root on the scalp, at the clearance plus half the fiber's width (the later push then leaves it).
    auto onto_scalp = [&](const float3& x, float width) {
        if (!on_scalp || !scalp) return x;
        float3 n, c;
        scalp->query(x, n, c);
        return c + n * (p.clearance + 0.5f * width);
    };
    const ProgressStep step(progress, "braid fibers", nc);
    parallel_for(nc, 16, [&](int64_t begin, int64_t end) {
        std::vector<float3> e1, e2;
        std::vector<float> cos_twist, sin_twist;
        for (int64_t c = begin; c < end; ++c) {
            const IndexRange r = strands.points_of(c);
            const auto pts = SP.subspan(r.begin, r.size());
            const std::vector<float3> tan = polyline_tangents(pts);
            // The cross-section's axes: across the braid (the binormal, square to the strand) and the
            // strand tangent crossed with it (about the braid normal).
            e1.resize(pts.size());
            e2.resize(pts.size());
            for (int64_t j = 0; j < r.size(); ++j) {
                const float3 b = sec.lateral[r.begin + j];
                float3 a = b - tan[j] * dot(b, tan[j]);
                a = length_squared(a) > 1e-12f ? normalize(a) : any_perpendicular(tan[j]);
                e1[j] = a;
                e2[j] = cross(tan[j], a);
            }
            // The twist angle at each strand point, shared by the strand's M fibers: each fiber adds its
            // own start angle by the sum formula, so a fiber point costs no trigonometry (the profile
            // of the first version spent two thirds of the op in per-point sin and cos).
            cos_twist.resize(pts.size());
            sin_twist.resize(pts.size());
            for (int64_t j = 0; j < r.size(); ++j) {
                const double psi = kTwoPi * twist * double(sec.phase[r.begin + j]);
                cos_twist[j] = float(std::cos(psi));
                sin_twist[j] = float(std::sin(psi));
            }
            const StrandFiberPlan& plan = plans[c];
            for (int64_t f = 0; f < M; ++f) {
                const int64_t oc = c * M + f;
                const FiberDraw d = draw_fiber(p, plan, uint64_t(ids[c] * M + f));
                const int64_t j0 = r.size() - (dst.points_of(oc).size());
                dfiber[oc] = int32_t(f);
                did[oc] = ids[c] * M + f;
                src_curve[oc] = c;
                const IndexRange o = dst.points_of(oc);
                const float blend_t = 0.35f * plan.knot_t;
                const float c0 = std::cos(d.phi), s0 = std::sin(d.phi);
                float3 start_root{};
                // The join starts at the fiber's first point (the strand sample at or after join_t),
                // so that point is the root itself.
                const float join_from = d.feeds ? std::max(d.join_t, T[r.begin + j0]) : 0.0f;
                for (int64_t j = j0; j < r.size(); ++j) {
                    const int64_t q = r.begin + j;
                    const float tj = T[q];
                    // The strand's width already follows the hair fed in so far (feed_scale in its
                    // amplitude scale): its disc holds the fibers present, each of the full width.
                    const float rad = 0.5f * SW[q] * sec.spread[q];
                    const float fed = feed_scale(p.feed_in, plan.feed_t, tj);
                    const float fiber_width = p.fiber_width > 0.0f ? p.fiber_width : SW[q] * inv_sqrt_m / fed;
                    const float fl = p.flatten * sec.press[q];
                    const float cphi = c0 * cos_twist[j] - s0 * sin_twist[j], sphi = s0 * cos_twist[j] + c0 * sin_twist[j];
                    float3 off = (e1[j] * (cphi * rad * (kFiberSpreadAcross + 0.5f * fl)) + e2[j] * (sphi * rad * (1.0f - fl))) * d.rho;
                    if (d.flyaway) {
                        const float dist = std::fabs(tj - d.loop_t) / d.loop_half_t;
                        if (dist < 1.0f) {
                            const float bump = 0.5f * (1.0f + std::cos(float(std::numbers::pi) * dist));
                            const float height = (p.flyaway_height > 0.0f ? p.flyaway_height : SW[q]) * d.loop_height;
                            off += (e1[j] * cphi + e2[j] * sphi) * (bump * height);
                        }
                    }
                    float3 pos = pts[j] + off;
                    // A cornrow lies on the scalp (its normal is the section's up): hair joining it
                    // comes from the scalp, level with the braid's underside. Elsewhere, from below.
                    const float down = on_scalp ? 1.0f : 0.6f;
                    if (d.feeds && tj - join_from < blend_t) {
                        // Joining: from beside the braid and below it, eased into the fiber's place.
                        const float3 root = onto_scalp(sec.centre[q] + sec.lateral[q] * (d.side * 1.1f * sec.half_width[q]) -
                                                           sec.up[q] * (down * sec.half_height[q]),
                                                       fiber_width);
                        const float v = std::clamp((tj - join_from) / blend_t, 0.0f, 1.0f);
                        const float e = v * v * (3.0f - 2.0f * v);
                        pos = root + (pos - root) * e;
                    }
                    else if (on_scalp && j0 == 0 && tj < blend_t) {
                        // A cornrow's first stitch gathers hair growing from the scalp around it: each
                        // fiber rises from the scalp, its root 1.4 times as far out across the braid
                        // as its place in the first section, instead of all starting in one cut
                        // section (a paintbrush, a trial's close-ups of the hairline).
                        const int64_t q0 = r.begin;
                        if (j == 0) {
                            start_root = onto_scalp(sec.centre[q0] + sec.lateral[q0] * (1.4f * dot(pos - sec.centre[q0], sec.lateral[q0])) -
                                                        sec.up[q0] * sec.half_height[q0],
                                                    fiber_width);
                        }
                        const float v = std::clamp(tj / blend_t, 0.0f, 1.0f);
                        const float e = v * v * (3.0f - 2.0f * v);
                        pos = start_root + (pos - start_root) * e;
                    }
                    const int64_t oq = o.begin + (j - j0);
                    dP[oq] = pos;
                    dW[oq] = fiber_width;
                    reach[oq] = length(pos - pts[j]);
                    strand_point[oq] = q;
                }
            }
            step.advance(1);
        }
    });
    carry_curve_attributes(strands, dst, src_curve);
    carry_point_attributes(strands, dst, strand_point, {attr::P, attr::width});
    return dst;
}

}  // namespace groom
