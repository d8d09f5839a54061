#include "ops/generate.h"
#include "ops/scene_length.h"
#include "ops/root_uv.h"

#include "fields/keep_outside.h"
#include "fields/point_index.h"
#include "kernel/curve_blocks.h"
#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace groom {

namespace {

std::string str(float v) { return format_number(v); }

std::vector<float3> guide_roots(const CurveSet& guides)
{
    const auto P = guides.positions();
    std::vector<float3> roots(guides.num_curves());
    for (size_t g = 0; g < guides.num_curves(); ++g) {
        const IndexRange r = guides.points_of(g);
        if (r.size() < 2) {
            throw InvalidGeometry("generate: guide " + std::to_string(g) + " has " + std::to_string(r.size()) +
                                  " point(s); guides need >= 2");
        }
        roots[g] = P[r.begin];
    }
    return roots;
}

/// Minimal rotation taking unit a onto unit b, applied to v (Rodrigues, in the form that needs no
/// trigonometry). Opposite normals take a half turn about an axis perpendicular to a.
float3 rotate_onto(const float3& a, const float3& b, const float3& v)
{
    const float c = dot(a, b);
    if (c > 1.0f - 1e-7f) return v;
    if (c < -1.0f + 1e-6f) {
        const float3 k = any_perpendicular(a);
        return k * (2.0f * dot(k, v)) - v;
    }
    const float3 w = cross(a, b);
    return v * c + cross(w, v) + w * (dot(w, v) / (1.0f + c));
}

struct PreparedGuides {
    int points = 0;                     // common point count
    std::vector<float3> roots;          // #guides
    std::vector<float3> normals;        // scalp normal at each root
    std::vector<float3> offsets;        // #guides * points: point - root
    std::vector<float3> positions;      // #guides * points: the resampled guide
    std::vector<int64_t> source_point;  // #guides * points: nearest original point (attribute carry)
};

PreparedGuides prepare(const CurveSet& guides, const Surface& scalp, int points_param)
{
    PreparedGuides pg;
    pg.roots = guide_roots(guides);
    const size_t ng = guides.num_curves();
    bool same = true;
    int64_t most = 0;
    for (size_t g = 0; g < ng; ++g) {
        most = std::max(most, guides.points_in(g));
        same = same && guides.points_in(g) == guides.points_in(0);
    }
    const bool keep = points_param == 0 && same;
    pg.points = points_param > 0 ? points_param : int(most);
    const int np = pg.points;
    pg.normals.resize(ng);
    pg.offsets.resize(ng * np);
    pg.positions.resize(ng * np);
    pg.source_point.resize(ng * np);
    const auto P = guides.positions();
    parallel_for(int64_t(ng), 64, [&](int64_t b, int64_t e) {
        for (int64_t g = b; g < e; ++g) {
            const IndexRange r = guides.points_of(g);
            const auto in = P.subspan(r.begin, r.size());
            const auto cum = cumulative_lengths(in);
            if (!(cum.back() > 0.0)) {
                throw InvalidGeometry("generate: guide " + std::to_string(g) + " has zero length");
            }
            float3* out = pg.positions.data() + g * np;
            int64_t* src = pg.source_point.data() + g * np;
            if (keep) {
                std::copy(in.begin(), in.end(), out);
                for (int i = 0; i < np; ++i) src[i] = r.begin + i;
            }
            else {
                const auto res = resample_by_count(in, np);
                std::copy(res.begin(), res.end(), out);
                for (int i = 0; i < np; ++i) {
                    src[i] = r.begin + int64_t(locate_at_length(cum, cum.back() * double(i) / double(np - 1)).nearest);
                }
            }
            pg.normals[g] = scalp.normal(pg.roots[g]);
            for (int i = 0; i < np; ++i) pg.offsets[g * np + i] = out[i] - pg.roots[g];
        }
    });
    return pg;
}

/// Refuses, before anything is allocated, `count` curves of the points `prepare` will give them
/// (`points`, else the most any guide has) when they would pass the memory budget. Each output point
/// holds a position, its source point and the guides' other point columns; each curve its id,
/// nearest guide, source curve, root, normal and sample, and the guides' curve columns.
void check_generate_memory(const CurveSet& guides, int64_t count, int points_param)
{
    int64_t np = points_param;
    if (np == 0)
        for (size_t g = 0; g < guides.num_curves(); ++g) np = std::max(np, guides.points_in(g));
    const double points = double(count) * double(np);
    const double per_curve = double(sizeof(int64_t) + sizeof(int32_t) + sizeof(int64_t) + 2 * sizeof(float3) + sizeof(SurfaceSample)) +
                             bytes_per_curve(guides);
    check_memory("generate: " + std::to_string(count) + " curves (`count`) x " + std::to_string(np) + " points (`points`) = " +
                     format_number(points) + " points",
                 points * (double(sizeof(float3) + sizeof(int64_t)) + bytes_per_point(guides)) + double(count) * per_curve,
                 "ask for fewer curves or points");
}

}  // namespace

void GenerateParams::validate() const
{
    if (count < 1) throw InvalidParam("generate: `count` must be >= 1 (got " + std::to_string(count) + ")");
    if (neighbours < 1) {
        throw InvalidParam("generate: `neighbours` must be >= 1 (got " + std::to_string(neighbours) + ")");
    }
    if (!(power > 0.0f) || !std::isfinite(power)) {
        throw InvalidParam("generate: `power` must be a finite number > 0 (got " + str(power) + ")");
    }
    if (points != 0 && points < 2) {
        throw InvalidParam("generate: `points` must be >= 2, or 0 for the guides' own count (got " +
                           std::to_string(points) + ")");
    }
    if (!(region_radius >= 0.0f) || !std::isfinite(region_radius) || !isfinite(region_center)) {
        throw InvalidParam("generate: `region` radius must be finite and > 0 (got " + str(region_radius) + ")");
    }
    if (!(footprint_scale > 0.0f) || !std::isfinite(footprint_scale)) {
        throw InvalidParam("generate: `footprint_scale` must be a finite number > 0 (got " + str(footprint_scale) + ")");
    }
    if (!(max_angle > 0.0f && max_angle <= 180.0f)) {
        throw InvalidParam("generate: `max_angle` must be in (0, 180] degrees (got " + str(max_angle) + ")");
    }
    if (!(clearance >= 0.0f && clearance <= kMaxSceneLength)) {
        throw InvalidParam("generate: `clearance` must be in [0, 1e15] scene units (got " + str(clearance) + ")");
    }
    if (first_id < 0) throw InvalidParam("generate: `first_id` must be >= 0 (got " + std::to_string(first_id) + ")");
    if (first_id > std::numeric_limits<int64_t>::max() - count) {
        throw InvalidParam("generate: `first_id` " + std::to_string(first_id) + " + " + std::to_string(count) +
                           " curves passes the largest id, 2^63 - 1 (ids would wrap to negative)");
    }
    widths.validate("generate");
    if (!(units_per_cm > 0.0f) || !std::isfinite(units_per_cm)) {
        throw InvalidParam("generate: `units_per_cm` must be a finite number > 0 (got " + format_number(units_per_cm) + ")");
    }
}

std::vector<SurfaceSample> scatter_roots(const CurveSet& guides, const Surface& scalp, const RootSampler& sample,
                                         const GenerateParams& params)
{
    params.validate();
    if (guides.num_curves() == 0) throw InvalidParam("generate: no guide curves in the input");
    check_generate_memory(guides, params.count, params.points);
    const std::vector<float3> roots = guide_roots(guides);
    const PointIndex index(roots);
    std::vector<float3> guide_normals(roots.size());
    for (size_t g = 0; g < roots.size(); ++g) guide_normals[g] = scalp.normal(roots[g]);
    const float min_cos = params.max_angle >= 180.0f ? -2.0f : float(std::cos(double(params.max_angle) * 3.14159265358979 / 180.0));

    // The ball handed to the sampler, and the exact test each sample must pass.
    float3 center = params.region_center;
    float radius = params.region_radius;
    double footprint = 0.0;
    const bool use_footprint = !(params.region_radius > 0.0f);
    if (use_footprint) {
        if (roots.size() < 2) {
            throw InvalidParam("generate: one guide has no footprint; give `region` X,Y,Z,R for where roots go");
        }
        std::vector<PointIndex::Neighbour> hits;
        Bounds3 box;
        for (const float3& r : roots) {
            box.extend(r);
            index.nearest(r, 2, hits);
            footprint = std::max(footprint, hits.back().distance);
        }
        footprint *= params.footprint_scale;
        if (!(footprint > 0.0)) throw InvalidParam("generate: every guide root is at the same point; give `region`");
        center = box.center();
        radius = 0.5f * length(box.size()) + float(footprint);
    }
    auto accept = [&](const SurfaceSample& s, std::vector<PointIndex::Neighbour>& hits) {
        if (!use_footprint && !(double(distance(s.position, center)) <= double(radius))) return false;
        index.nearest(s.position, 1, hits);
        if (use_footprint && !(hits.front().distance <= footprint)) return false;
        if (params.region && !params.region->haired(s.position)) return false;
        return min_cos < -1.0f || dot(normalize(s.normal), guide_normals[hits.front().index]) >= min_cos;
    };

    // Rejection from an area-uniform superset stays area-uniform; batches use fresh seeds so the
    // result depends only on params.seed.
    std::vector<SurfaceSample> out;
    out.reserve(size_t(params.count));
    std::vector<PointIndex::Neighbour> hits;
    double rate = 1.0;
    for (uint64_t batch = 0; int64_t(out.size()) < params.count; ++batch) {
        if (batch == 64) {
            // Guides in other units or another place than the scalp leave no root within reach: say
            // so rather than point at `max_angle` (a trial's guides in cm on a body in metres).
            std::vector<float> off(roots.size());
            for (size_t g = 0; g < roots.size(); ++g) off[g] = std::fabs(scalp.distance(roots[g]));
            std::nth_element(off.begin(), off.begin() + std::ptrdiff_t(off.size() / 2), off.end());
            const float median = off[off.size() / 2];
            const double reach = use_footprint ? footprint : double(radius);
            if (double(median) > reach) {
                throw LimitExceeded("generate: found only " + std::to_string(out.size()) + " of " + std::to_string(params.count) +
                                    " roots: the guides' roots lie a median " + format_number(median) + " from the scalp, farther than roots are " +
                                    "looked for around them (" + format_number(float(reach)) + "): are the guides and the scalp in the same " +
                                    "units and place? (groom transform --units, --translate)");
            }
            throw LimitExceeded("generate: found only " + std::to_string(out.size()) + " of " +
                                std::to_string(params.count) + " roots on the scalp inside the " +
                                (use_footprint ? std::string("guides' footprint") : std::string("`region` ball")) +
                                " after 64 rounds of sampling" + (params.region ? std::string(" (and inside the hairline, off the partings)") : std::string()) +
                                "; is the region on the scalp, facing the way the guides' roots do (`max_angle`)?");
        }
        const int64_t want = params.count - int64_t(out.size());
        const int64_t ask = std::min<int64_t>(int64_t(std::ceil(double(want) * 1.1 / std::max(rate, 0.02))) + 16,
                                              std::max<int64_t>(4 * params.count, 1 << 16));
        const std::vector<SurfaceSample> got = sample(center, radius, ask, mix64(params.seed ^ mix64(batch + 0x5bd1e995ull)));
        int64_t kept = 0;
        for (const SurfaceSample& p : got) {
            if (int64_t(out.size()) == params.count) break;
            if (accept(p, hits)) {
                out.push_back(p);
                ++kept;
            }
        }
        rate = got.empty() ? 0.0 : double(kept) / double(got.size());
    }
    return out;
}

namespace {

/// What every part of one run shares: the guides prepared, their roots indexed, and the margin
/// the scalp rule starts from (made once; a run written a block at a time grows many parts).
struct GrowRun {
    PreparedGuides pg;
    PointIndex index;
    float margin = 0.0f;
};

GrowRun prepare_run(const CurveSet& guides, const Surface& scalp, std::span<const float3> roots, std::span<const float3> normals,
                    const GenerateParams& params)
{
    params.validate();
    if (!normals.empty() && normals.size() != roots.size()) {
        throw InvalidParam("generate: " + std::to_string(normals.size()) + " root normals for " + std::to_string(roots.size()) + " roots");
    }
    if (guides.num_curves() == 0) throw InvalidParam("generate: no guide curves in the input");
    if (params.first_id > std::numeric_limits<int64_t>::max() - int64_t(roots.size())) {
        throw InvalidParam("generate: `first_id` " + std::to_string(params.first_id) + " + " + std::to_string(roots.size()) +
                           " curves passes the largest id, 2^63 - 1 (ids would wrap to negative)");
    }
    PreparedGuides pg = prepare(guides, scalp, params.points);
    PointIndex index(pg.roots);
    // The margin (scene_margin) is of the groom's extent: every root and every guide, so a shard's
    // or a block's part gets the whole run's margin.
    Bounds3 box;
    for (const float3& p : roots) box.extend(p);
    for (const float3& p : guides.positions()) box.extend(p);
    return GrowRun{std::move(pg), std::move(index), scene_margin(box)};
}

/// Hairs [r0, r1) of the roots, grown (generate_at_roots' body for one part of the run).
CurveSet grow(const GrowRun& run, const CurveSet& guides, const Surface& scalp, std::span<const float3> roots,
              std::span<const float3> normals, std::span<const float3> blend_at, const GenerateParams& params, int64_t r0, int64_t r1,
              Progress* progress)
{
    const PreparedGuides& pg = run.pg;
    const PointIndex& index = run.index;
    const int np = pg.points;
    const int64_t ng = int64_t(guides.num_curves());
    const int64_t nc = r1 - r0;
    check_generate_memory(guides, nc, params.points);  // the curves made here: a shard's or a block's part
    const int k = int(std::min<int64_t>(params.neighbours, ng));
    const int query = int(std::min<int64_t>(int64_t(k) + 1, ng));

    CurveSet dst = CurveSet::from_counts(std::vector<int64_t>(size_t(nc), np));
    auto P = dst.positions_for_write();
    auto ids = dst.add<int64_t>(Domain::Curve, attr::id);
    auto nearest_guide = dst.add<int32_t>(Domain::Curve, "guide");
    std::vector<int64_t> src_curve(static_cast<size_t>(nc));
    std::vector<int64_t> src_point(dst.num_points());

    ProgressStep step(progress, "generate", nc);
    parallel_for(nc, 256, [&](int64_t b, int64_t e) {
        std::vector<PointIndex::Neighbour> hits;
        std::vector<double> w;
        for (int64_t c = b; c < e; ++c) {
            const int64_t r = r0 + c;  // the hair's index among all roots
            const float3 x = roots[r];
            const float3 q = blend_at.empty() ? x : blend_at[r];  // where the hair takes its guides from
            float3* out = P.data() + c * np;
            index.nearest(q, query, hits);
            const int64_t g0 = hits.front().index;
            ids[c] = params.first_id + r;
            nearest_guide[c] = int32_t(g0);
            src_curve[c] = g0;
            std::copy_n(pg.source_point.data() + g0 * np, np, src_point.data() + c * np);

            if (hits.front().distance == 0.0 && blend_at.empty()) {
                // A root on a guide's root is that guide: weight 1, copied exactly.
                std::copy_n(pg.positions.data() + g0 * np, np, out);
                continue;
            }
            // Franke-Little weights vanish at the (K+1)-th guide, so a guide entering or leaving the
            // K nearest changes nothing abruptly; with no guide beyond the K, plain inverse distance.
            // Each base is divided by the largest before the power is taken: the normalised weights
            // are the same, but (base / max)^power lies in [0, 1] for any power, where base^power
            // overflowed to inf (and inf / inf to NaN positions) at `power` 1000.
            w.assign(size_t(k), 0.0);
            auto weigh = [&] {
                double top = 0.0;
                for (int j = 0; j < k; ++j) top = std::max(top, w[j]);
                if (!(top > 0.0) || !std::isfinite(top)) return 0.0;
                double sum = 0.0;
                for (int j = 0; j < k; ++j) sum += (w[j] = std::pow(w[j] / top, double(params.power)));
                return sum;
            };
            double total = 0.0;
            if (int(hits.size()) > k) {
                const double far = hits[k].distance;
                for (int j = 0; j < k; ++j) w[j] = std::max(0.0, far - hits[j].distance) / (far * hits[j].distance);
                total = weigh();
            }
            if (!(total > 0.0)) {  // no guide beyond the K, or all K tie with the next one
                for (int j = 0; j < k; ++j) w[j] = 1.0 / hits[j].distance;
                total = weigh();
            }
            if (!(total > 0.0)) {  // a blend point on a guide's root (blend_at): that guide alone
                w.assign(size_t(k), 0.0);
                w[0] = total = 1.0;
            }
            const float3 n = normals.empty() ? scalp.normal(x) : normalize(normals[r], scalp.normal(x));
            for (int i = 0; i < np; ++i) out[i] = float3();
            for (int j = 0; j < k; ++j) {
                const int64_t g = hits[j].index;
                const float wj = float(w[j] / total);
                if (wj == 0.0f) continue;
                const float3& ng_ = pg.normals[g];
                const float3* off = pg.offsets.data() + g * np;
                // The guide's root frame carried to x by the minimal rotation between the normals.
                for (int i = 1; i < np; ++i) out[i] += rotate_onto(ng_, n, off[i]) * wj;
            }
            out[0] = x;
            for (int i = 1; i < np; ++i) out[i] += x;
        }
        step.advance(e - b);
    });

    carry_curve_attributes(guides, dst, src_curve);
    carry_point_attributes(guides, dst, src_point, {attr::P});
    // Moved points are checked again and moved again with a doubled margin (up to 16 times): one
    // step along a level set's interpolated normal lands within about a tenth of a voxel of the
    // surface, either side, and on Sintel left 5,500 of 640,000 points reading up to 0.2 inside. In
    // a crease the band's gradient is about half a unit long, so each step gains half of what is
    // missing: 8 steps left 191 of 100,000 hairs' points at Sintel's ear up to 0.05 inside. A run
    // pushed out of an ear flap that folds back is laid over it (fields/drape_runs.h).
    keep_outside(dst, scalp, KeepOutside{params.clearance, run.margin, 16});
    apply_hair_widths(dst, params.widths, params.units_per_cm);
    add_root_uvs(dst, scalp);
    return dst;
}

/// The part of the roots a run grows: all of them, or [range_begin, range_end) of a shard.
std::pair<int64_t, int64_t> run_range(const GenerateParams& params, int64_t all)
{
    const int64_t r0 = std::clamp<int64_t>(params.range_begin, 0, all);
    return {r0, std::clamp<int64_t>(params.range_end < 0 ? all : params.range_end, r0, all)};
}

}  // namespace

CurveSet generate_at_roots(const CurveSet& guides, const Surface& scalp, std::span<const float3> roots,
                           std::span<const float3> normals, const GenerateParams& params, Progress* progress,
                           std::span<const float3> blend_at)
{
    if (!blend_at.empty() && blend_at.size() != roots.size()) {
        throw InvalidParam("generate: " + std::to_string(blend_at.size()) + " blend points for " + std::to_string(roots.size()) + " roots");
    }
    const GrowRun run = prepare_run(guides, scalp, roots, normals, params);
    const auto [r0, r1] = run_range(params, int64_t(roots.size()));
    return grow(run, guides, scalp, roots, normals, blend_at, params, r0, r1, progress);
}

namespace {

struct Roots {
    std::vector<float3> positions, normals;
};

Roots roots_of(const CurveSet& guides, const Surface& scalp, const RootSampler& sample, const GenerateParams& params)
{
    const std::vector<SurfaceSample> samples = scatter_roots(guides, scalp, sample, params);
    Roots r;
    r.positions.resize(samples.size());
    r.normals.resize(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
        r.positions[i] = samples[i].position;
        r.normals[i] = samples[i].normal;
    }
    return r;
}

}  // namespace

CurveSet generate(const CurveSet& guides, const Surface& scalp, const RootSampler& sample, const GenerateParams& params,
                  Progress* progress)
{
    const Roots roots = roots_of(guides, scalp, sample, params);
    return generate_at_roots(guides, scalp, roots.positions, roots.normals, params, progress);
}

void generate_blocks(const CurveSet& guides, const Surface& scalp, const RootSampler& sample, const GenerateParams& params,
                     Progress* progress, int64_t block_points, const std::function<void(std::span<const int64_t> counts)>& start,
                     const std::function<void(const CurveSet& block)>& emit)
{
    const Roots roots = roots_of(guides, scalp, sample, params);
    const GrowRun run = prepare_run(guides, scalp, roots.positions, roots.normals, params);
    // Plain variables, not a structured binding: clang 14 (the sanitizer build) cannot capture one.
    const std::pair<int64_t, int64_t> range = run_range(params, int64_t(roots.positions.size()));
    const int64_t r0 = range.first, r1 = range.second;
    const std::vector<int64_t> counts(size_t(r1 - r0), run.pg.points);
    const std::vector<int64_t> ends = curve_block_ends(counts, block_points);
    // Refused before the caller opens its output (each block checks its own part again).
    if (!ends.empty()) check_generate_memory(guides, largest_curve_block(counts, ends) / std::max(run.pg.points, 1), params.points);
    start(counts);
    const ProgressStep step(progress, "generate", r1 - r0);
    hand_over_curve_blocks(
        ends,
        [&](int64_t c0, int64_t c1) {
            CurveSet block = grow(run, guides, scalp, roots.positions, roots.normals, {}, params, r0 + c0, r0 + c1, nullptr);
            step.advance(c1 - c0);
            return block;
        },
        emit);
}

}  // namespace groom
