#include "ops/gather.h"

#include "fields/keep_outside.h"
#include "fields/surface_path.h"
#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "ops/puff.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace groom {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Rng streams (kernel/rng.h), per gathered hair: one per purpose so adding a draw never shifts another.
constexpr uint64_t kStreamLift = 11;    // the flat part's height over the scalp
constexpr uint64_t kStreamFollow = 12;  // the point of the base whose guides the hair follows

float smoothstep01(float x)
{
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

/// The point of puff k's base circle toward p, on the scalp: the direction from the base centre to p
/// in the base's tangent plane.
float3 base_point_toward(const Surface& scalp, const GatherPuff& puff, const float3& p)
{
    const float3 n0 = scalp.normal(puff.base);
    const float3 t = (p - puff.base) - n0 * dot(p - puff.base, n0);
    const float3 dir = normalize(t, any_perpendicular(n0));
    return scalp.closest_point(puff.base + dir * puff.base_radius);
}

/// One hair's part on the scalp: points and the normal at each (heights are added later).
struct FlatPart {
    std::vector<float3> points;  ///< on the scalp
    std::vector<float3> normals;
};

}  // namespace

void GatherParams::validate() const
{
    auto positive = [](const char* name, float v) {
        if (!(v > 0.0f) || !std::isfinite(v)) {
            throw InvalidParam("gather: `" + std::string(name) + "` must be a finite number > 0 (got " + format_number(v) + ")");
        }
    };
    if (hairs < 1) throw InvalidParam("gather: `hairs` must be >= 1 (got " + std::to_string(hairs) + ")");
    positive("lift", lift);
    positive("step", step);
    if (hair_points < 4) throw InvalidParam("gather: `hair_points` must be >= 4 (got " + std::to_string(hair_points) + ")");
    if (neighbours < 1) throw InvalidParam("gather: `neighbours` must be >= 1 (got " + std::to_string(neighbours) + ")");
    positive("power", power);
    positive("band_width", band_width);
    positive("band_thickness", band_thickness);
    if (band_strands < 0 || band_strands > 256) {
        throw InvalidParam("gather: `band_strands` must be in [0, 256] (got " + std::to_string(band_strands) + ")");
    }
    if (first_id < 0) throw InvalidParam("gather: `first_id` must be >= 0 (got " + std::to_string(first_id) + ")");
    curl.validate_for("gather");
}

GatherResult gather(const Surface& scalp, const RootSampler& sample, const std::vector<GatherPuff>& puffs, const HairRegion& region,
                    const GatherParams& params, Progress* progress)
{
    params.validate();
    if (puffs.empty()) throw InvalidGeometry("gather: no puff to gather the hair into");
    for (size_t k = 0; k < puffs.size(); ++k) {
        const GatherPuff& p = puffs[k];
        if (p.guides.num_curves() == 0) throw InvalidGeometry("gather: puff " + std::to_string(k) + " has no guides");
        if (!(p.base_radius > 0.0f) || !(p.sphere_radius > 0.0f) || !isfinite(p.base) || !isfinite(p.sphere_center)) {
            throw InvalidGeometry("gather: puff " + std::to_string(k) + " has no valid base or sphere (puff_radius and puff_sphere_radius must be > 0)");
        }
        // A puff made on another head (groom puff puts the base on the scalp, so within the level
        // set's error of it): its hair would run from this scalp to a base elsewhere (a
        // trial gathered Sintel's hair, over her face, into a puff made on ICT's head, exit 0).
        const float off = std::fabs(scalp.distance(p.base));
        if (!(off <= 0.25f * p.base_radius)) {
            throw InvalidGeometry("gather: puff " + std::to_string(k) + "'s base (puff_base " + format_xyz(p.base) + ") is " + format_number(off) +
                                  " from this scalp, more than a quarter of its radius " + format_number(p.base_radius) +
                                  ": was it made on another scalp? Run groom puff on this one");
        }
        if (!(p.cap_angle >= 0.0f && p.cap_angle < 180.0f)) {
            throw InvalidGeometry("gather: puff " + std::to_string(k) + "'s puff_cap_angle must be in (0, 180) degrees, or absent (got " +
                                  format_number(p.cap_angle) + ")");
        }
    }
    const size_t np = puffs.size();
    // Ids first_id .. first_id + hairs + bands - 1 must not pass int64 (they would wrap to negative).
    if (params.first_id > std::numeric_limits<int64_t>::max() - params.hairs - int64_t(params.band_strands) * int64_t(np)) {
        throw InvalidParam("gather: `first_id` " + std::to_string(params.first_id) + " + " + std::to_string(params.hairs) +
                           " hairs and the bands passes the largest id, 2^63 - 1 (ids would wrap to negative)");
    }
    std::vector<uint64_t> puff_section(np);
    for (size_t k = 0; k < np; ++k) puff_section[k] = region.section(puffs[k].base);

    // Before sampling: each hair draws about 3 candidate roots (a position, a normal, a face) and
    // holds its puff part's centreline (`hair_points`) twice, with a normal per point, before the
    // curl (which checks its own output). Its flat path depends on where it lands and is not counted.
    check_memory("gather: " + std::to_string(params.hairs) + " `hairs` x " + std::to_string(params.hair_points) + " `hair_points`",
                 double(params.hairs) * (3.0 * 32.0 + double(params.hair_points) * 3.0 * 12.0 + 128.0), "lower `hairs`");

    // --- Roots: area-uniform rounds, kept where the region is haired and no puff's base is.
    const uint64_t seed = mix64(params.curl.seed ^ 0x67617468ull);
    std::vector<SurfaceSample> roots;
    std::vector<int32_t> owner;
    int64_t orphans = 0;
    for (int round = 0; int64_t(roots.size()) < params.hairs && round < 64; ++round) {
        const int64_t ask = 3 * (params.hairs - int64_t(roots.size())) + 64;
        const std::vector<SurfaceSample> s = sample(puffs[0].base, 0.0f, ask, mix64(seed + uint64_t(round)));
        std::vector<int32_t> pick(s.size(), -1);  // puff index, -1 rejected, -2 no puff in its section
        parallel_for(int64_t(s.size()), 256, [&](int64_t b, int64_t e) {
            for (int64_t i = b; i < e; ++i) {
                const float3& p = s[i].position;
                if (!region.haired(p)) continue;
                bool under_base = false;
                for (const GatherPuff& puff : puffs) under_base = under_base || distance(p, puff.base) < puff.base_radius;
                if (under_base) continue;
                const uint64_t sec = region.section(p);
                float best = std::numeric_limits<float>::infinity();
                int32_t k_best = -2;
                for (size_t k = 0; k < np; ++k) {
                    if (puff_section[k] != sec) continue;
                    const float d = distance(p, puffs[k].base) - puffs[k].base_radius;
                    if (d < best) best = d, k_best = int32_t(k);
                }
                pick[i] = k_best;
            }
        });
        for (size_t i = 0; i < s.size() && int64_t(roots.size()) < params.hairs; ++i) {
            if (pick[i] == -2) ++orphans;
            if (pick[i] < 0) continue;
            roots.push_back(s[i]);
            owner.push_back(pick[i]);
        }
    }
    if (roots.empty()) {
        throw LimitExceeded("gather: found no haired scalp outside the puffs' bases in 64 rounds of sampling (is the hairline around "
                            "this head, and are the puffs inside it?)");
    }
    const int64_t nh = int64_t(roots.size());
    // Before walking: a flat part takes at most 4 |root - base| / step + 16 steps (surface_path),
    // each point held with its normal, twice. On a head 1e4 times larger than `step` expects, 200
    // hairs walked for minutes (op fuzzer): the bound is known here, so both memory and time are.
    double path_points = 0.0;
    for (int64_t i = 0; i < nh; ++i) {
        const GatherPuff& puff = puffs[owner[size_t(i)]];
        path_points += 4.0 * (double(distance(roots[size_t(i)].position, puff.base)) + double(puff.base_radius)) / double(params.step) + 16.0;
    }
    check_memory("gather: the flat parts of " + std::to_string(nh) + " hairs at `step` " + format_number(params.step) + " (up to " +
                     format_number(path_points) + " points)",
                 path_points * 2.0 * 24.0, "use a larger `step` or fewer `hairs`");
    ProgressStep step(progress, "gather", nh);

    // --- Flat parts: on the scalp from each root to its puff's base circle.
    std::vector<FlatPart> flat(static_cast<size_t>(nh));
    std::vector<float> height(static_cast<size_t>(nh));
    parallel_for(nh, 32, [&](int64_t b, int64_t e) {
        std::vector<float3> path;
        for (int64_t i = b; i < e; ++i) {
            const GatherPuff& puff = puffs[owner[i]];
            const float3 target = base_point_toward(scalp, puff, roots[i].position);
            // A walk that runs out of steps still ends at the base: the puff part starts there.
            if (!surface_path(scalp, roots[i].position, target, params.step, 0.0f, path)) path.push_back(target);
            FlatPart& f = flat[i];
            f.points = path;
            f.points.front() = roots[i].position;  // the root exactly where it was drawn
            f.normals.resize(path.size());
            for (size_t j = 0; j < path.size(); ++j) f.normals[j] = scalp.normal(path[j]);
            f.normals.front() = roots[i].normal;
            Rng rng(params.curl.seed, uint64_t(params.first_id + i), kStreamLift);
            height[i] = params.lift * (1.0f + 3.0f * rng.uniform()) * 0.25f;
        }
        step.advance(e - b);
    });

    // --- Puff parts: from each base point up into the puff, blended from its guides, per puff.
    std::vector<CurveSet> puff_part(np);
    std::vector<std::vector<int64_t>> members(np);
    for (int64_t i = 0; i < nh; ++i) members[owner[i]].push_back(i);
    for (size_t k = 0; k < np; ++k) {
        if (members[k].empty()) continue;
        // Each hair enters at its point of the base's rim but follows the puff's guides from a point
        // of the base drawn area-uniformly along the same direction (from the centre out to the
        // rim). Following the rim's guides, as the hair at the rim would alone, sent every gathered
        // hair to the cap's rim along the same few paths: one thin sheet of 24,000 parallel hairs, a
        // smooth cone under the demo's puffs with a sharp edge where their tips all met the ball.
        const GatherPuff& puff = puffs[k];
        std::vector<float3> at, normals, blend_at;
        for (int64_t i : members[k]) {
            const float3 rim = flat[i].points.back();
            at.push_back(rim);
            normals.push_back(flat[i].normals.back());
            Rng rng(params.curl.seed, uint64_t(params.first_id + i), kStreamFollow);
            blend_at.push_back(scalp.closest_point(puff.base + (rim - puff.base) * std::sqrt(rng.uniform())));
        }
        GenerateParams gen;
        gen.neighbours = params.neighbours;
        gen.power = params.power;
        gen.points = params.hair_points;
        CurveSet centres = generate_at_roots(puff.guides, scalp, at, normals, gen, nullptr, blend_at);
        auto ids = centres.find_for_write<int64_t>(Domain::Curve, attr::id);
        for (size_t j = 0; j < members[k].size(); ++j) ids[j] = params.first_id + members[k][j];  // the curl's randomness
        if (puff.cap_angle > 0.0f) {
            // Its tip at the cap's point for the point of the base it follows (PuffCap), as the
            // puff's own hairs end at their roots' points.
            PuffCap::make(scalp, puff.base, puff.base_radius, puff.sphere_center, puff.sphere_radius, puff.cap_angle).warp_onto(centres, blend_at);
        }
        else {
            warp_tips_to_sphere(centres, puff.sphere_center, puff.sphere_radius);
        }
        keep_outside(centres, scalp, KeepOutside{});
        CurlParams curl_params = params.curl;
        curl_params.preserve_length = false;
        puff_part[k] = curl(centres, curl_params, nullptr, nullptr);
        keep_outside(puff_part[k], scalp, KeepOutside{});
    }

    // --- Assemble: flat part (lifted) + puff part (lifted by the same height, fading out).
    std::vector<int64_t> counts(static_cast<size_t>(nh));
    std::vector<std::pair<int32_t, int64_t>> where(static_cast<size_t>(nh));  // puff, curve in its part
    for (size_t k = 0; k < np; ++k) {
        for (size_t j = 0; j < members[k].size(); ++j) {
            const int64_t i = members[k][j];
            where[i] = {int32_t(k), int64_t(j)};
            counts[i] = int64_t(flat[i].points.size()) - 1 + puff_part[k].points_in(size_t(j));
        }
    }
    GatherResult result;
    result.roots_without_puff = orphans;
    CurveSet& out = result.hairs;
    out = CurveSet::from_counts(counts);
    auto P = out.positions_for_write();
    auto flat_attr = out.add<int32_t>(Domain::Point, "flat");
    auto ids = out.add<int64_t>(Domain::Curve, attr::id);
    auto kind = out.add<int32_t>(Domain::Curve, "kind");
    auto puff_of = out.add<int32_t>(Domain::Curve, "puff");
    KeepOutside settle;
    settle.margin = 0.05f * params.lift;
    settle.max_steps = 4;
    parallel_for(nh, 64, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            const IndexRange r = out.points_of(size_t(i));
            const FlatPart& f = flat[i];
            const float h = height[i];
            // Heights ease in from the root over one step of arc length.
            double s = 0.0;
            int64_t o = r.begin;
            for (size_t j = 0; j + 1 < f.points.size(); ++j) {
                if (j > 0) s += double(distance(f.points[j], f.points[j - 1]));
                const float want = j == 0 ? 0.0f : h * smoothstep01(float(s / params.step));
                float3 q = f.points[j] + f.normals[j] * want;
                // Settle onto the level set at that height: one projection from the field is accurate
                // to a fraction of a voxel, less in creases (behind an ear); two Newton steps along the
                // normal fix it. The root stays where it was drawn.
                for (int it = 0; j > 0 && it < 2; ++it) {
                    float3 n, c;
                    const float d = scalp.query(q, n, c);
                    q += n * (want - d);
                }
                // In a crease the field's normal turns under a step; the one rule keeps the point out.
                if (j > 0) keep_outside(q, scalp, settle);
                P[o] = q;
                flat_attr[o++] = 1;
            }
            const auto [k, c] = where[i];
            const CurveSet& part = puff_part[k];
            const IndexRange pr = part.points_of(size_t(c));
            const auto src = part.positions().subspan(pr.begin, pr.size());
            const auto cum = cumulative_lengths(src);
            const float3 lift_dir = f.normals.back();
            for (size_t j = 0; j < src.size(); ++j) {
                const float fade = cum.back() > 0.0 ? 1.0f - smoothstep01(float(3.0 * cum[j] / cum.back())) : 1.0f;
                P[o] = src[j] + lift_dir * (h * fade);
                flat_attr[o++] = 0;
            }
            ids[i] = params.first_id + i;
            kind[i] = 1;
            puff_of[i] = k;
        }
    });
    // The whole hair, flat part and puff part, tapers over its own length.
    const HairWidths widths = params.curl.widths.resolved(params.curl.units_per_cm);
    taper_widths(out, *widths.root, *widths.tip);

    // --- Bands: rings around each base, outside the bunch of hair going up, on top of the flat hair.
    if (params.band_strands > 0) {
        const int ring = 96;
        const int64_t nb = int64_t(np) * params.band_strands;
        result.bands = CurveSet::from_counts(std::vector<int64_t>(static_cast<size_t>(nb), ring + 1));
        auto BP = result.bands.positions_for_write();
        auto bw = result.bands.add<float>(Domain::Point, attr::width);
        auto bid = result.bands.add<int64_t>(Domain::Curve, attr::id);
        auto bkind = result.bands.add<int32_t>(Domain::Curve, "kind");
        auto bpuff = result.bands.add<int32_t>(Domain::Curve, "puff");
        for (size_t k = 0; k < np; ++k) {
            const GatherPuff& puff = puffs[k];
            const float3 n0 = scalp.normal(puff.base);
            const float3 u = any_perpendicular(n0), v = cross(n0, u);
            const float radius = puff.base_radius + params.band_thickness;
            for (int j = 0; j < params.band_strands; ++j) {
                const int64_t c = int64_t(k) * params.band_strands + j;
                const float h = params.lift + params.band_thickness * 0.5f + params.band_width * (float(j) + 0.5f) / float(params.band_strands);
                const IndexRange r = result.bands.points_of(size_t(c));
                for (int m = 0; m <= ring; ++m) {
                    const double a = 2.0 * kPi * (m % ring) / ring;
                    float3 nq, q;
                    scalp.query(puff.base + (u * float(std::cos(a)) + v * float(std::sin(a))) * radius, nq, q);
                    BP[r.begin + m] = q + nq * h;
                    bw[r.begin + m] = params.band_thickness;
                }
                bid[c] = params.first_id + nh + c;
                bkind[c] = 2;
                bpuff[c] = int32_t(k);
            }
        }
    }
    return result;
}

}  // namespace groom
