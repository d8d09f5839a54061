#include "ops/sections.h"
#include "ops/root_uv.h"

#include "fields/keep_outside.h"
#include "fields/point_index.h"
#include "fields/surface_path.h"
#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "ops/hair_region.h"
#include "ops/section_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace groom {

namespace {

constexpr double kPi = 3.14159265358979323846;

const char* layout_name(SectionLayout l) { return l == SectionLayout::Grid ? "grid" : l == SectionLayout::Rows ? "rows" : "radial"; }

void require(bool ok, const std::string& what)
{
    if (!ok) throw InvalidParam("sections: " + what);
}

void count_in(const char* name, int v, int hi)
{
    require(v >= 0 && v <= hi, "`" + std::string(name) + "` must be 0 (unset) or in [1, " + std::to_string(hi) + "] (got " + std::to_string(v) + ")");
}

void finite_at_least(const char* name, float v, float lo, bool strict)
{
    const bool ok = std::isfinite(v) && (strict ? v > lo : v >= lo);
    require(ok, "`" + std::string(name) + "` must be a finite number " + (strict ? "> " : ">= ") + format_number(lo) + " (got " + format_number(v) + ")");
}

/// d turned toward `target` (unit) by at most `max_angle` radians; `fallback` picks the plane of
/// the turn when the two are opposite.
float3 turn_toward(const float3& d, const float3& target, float max_angle, const float3& fallback)
{
    const float c = std::clamp(dot(d, target), -1.0f, 1.0f);
    const float angle = std::acos(c);
    if (angle <= max_angle) return target;
    float3 axis = cross(d, target);
    if (length(axis) < 1e-6f) axis = cross(d, fallback);
    axis = normalize(axis, any_perpendicular(d));
    return normalize(d * std::cos(max_angle) + cross(axis, d) * std::sin(max_angle), target);
}

/// How a free guide moves: see SectionsParams (hang, sweep, bend, clearance, layer).
struct Fall {
    float3 gravity;     ///< unit
    float3 face;        ///< a point in front of the face: on the scalp, guides are combed away from it
    float3 up, forward;
    float sweep = 0.0f;
    float rate = 0.0f;  ///< radians of turn per unit length
    float reach = 0.0f; ///< within this distance of its clearance a guide is still steered by the scalp
    float clearance = 0.0f;
    float layer = 0.0f; ///< extra clearance, reached over `ramp` of arc length from the root
    float ramp = 1.0f;
    float margin = 0.0f;
};

/// Marches `length` from p leaving along d, `h` per step: near the scalp (within fall.reach of its
/// clearance, so while it rises from the root) toward gravity plus the sweep away from the face, both
/// along the scalp; farther out toward gravity; turning at most fall.rate per unit length; each point
/// kept its clearance outside the scalp (clearance + layer, the layer eased in from the root).
/// `walked` is the arc length from the root at p. Appends the points after p.
void march(const Surface& scalp, float3 p, float3 d, double length, double h, double walked, const Fall& fall, std::vector<float3>& out)
{
    const int steps = std::max(1, int(std::ceil(length / h)));
    const float hs = float(length / steps);
    for (int k = 0; k < steps; ++k) {
        float3 away = p - fall.face;
        away = normalize(away - fall.up * dot(away, fall.up), -fall.up);
        const float ramp = std::min(1.0f, float(walked / fall.ramp));
        const float clear = fall.clearance + fall.layer * ramp * ramp * (3.0f - 2.0f * ramp);
        // Only a guide within reach of the scalp needs its normal: farther out a bound of the
        // distance answers (no closest-point search on the mesh, which each step far from a level
        // set's band took: 32 s for 48 guides of 100,000 points hanging 30 units, a fuzz input).
        const float near = clear + fall.reach;
        float3 n, c;
        const bool steered = scalp.distance_within(p, near) < near && scalp.query(p, n, c) < near;
        float3 target = fall.gravity;
        if (steered && dot(fall.gravity, n) < 0.0f) {
            // On scalp that bears it (gravity presses the guide onto it; under a chin or the cut of a
            // neck it falls free): down the scalp's fall line, combed back only where that line runs
            // toward the face.
            const float3 tg = fall.gravity - n * dot(fall.gravity, n), ta = away - n * dot(away, n);
            const float toward_face = std::max(0.0f, dot(normalize(tg), fall.forward));
            target = normalize(tg + ta * (fall.sweep * toward_face), fall.gravity);
        }
        d = turn_toward(d, target, fall.rate * hs, away);
        float3 q = p + d * hs;
        keep_outside(q, scalp, KeepOutside{clear, fall.margin, 4});
        d = normalize(q - p, d);
        walked += distance(q, p);
        p = q;
        out.push_back(p);
    }
}

/// Distance from p to the nearest parting (their points indexed in `index`, each point's curve
/// neighbours known through `next` / `prev` (-1 at an end)).
float parting_distance(const float3& p, const PointIndex& index, std::span<const float3> pts, std::span<const int64_t> prev,
                       std::span<const int64_t> next, std::vector<PointIndex::Neighbour>& scratch)
{
    index.nearest(p, 4, scratch);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& nb : scratch) {
        const int64_t i = nb.index;
        best = std::min(best, nb.distance * nb.distance);
        for (int64_t j : {prev[i], next[i]}) {
            if (j >= 0) best = std::min(best, segment_distance_sq(p, p, pts[i], pts[j]));
        }
    }
    return float(std::sqrt(best));
}

}  // namespace

SectionLayout parse_section_layout(const std::string& name)
{
    if (name == "grid") return SectionLayout::Grid;
    if (name == "rows") return SectionLayout::Rows;
    if (name == "radial") return SectionLayout::Radial;
    throw InvalidParam("sections: `layout` must be grid, rows or radial (got '" + name + "')");
}

SectionGuide parse_section_guide(const std::string& name)
{
    if (name == "auto") return SectionGuide::Auto;
    if (name == "hang") return SectionGuide::Hang;
    if (name == "along") return SectionGuide::Along;
    throw InvalidParam("sections: `guide` must be auto, hang or along (got '" + name + "')");
}

void SectionsParams::validate() const
{
    require(isfinite(up) && groom::length(up) > 0.0f, "`up` must be a finite non-zero direction");
    require(isfinite(forward) && groom::length(cross(normalize(up), forward)) > 1e-3f * groom::length(forward), "`forward` must be a finite direction not parallel to `up`");
    count_in("cols", cols, 256);
    count_in("rows", rows, 256);
    count_in("rings", rings, 64);
    count_in("wedges", wedges, 256);
    const std::string with = " with `layout` " + std::string(layout_name(layout)) + ")";
    require(cols == 0 || layout == SectionLayout::Grid, "`cols` applies to the grid layout only (got " + std::to_string(cols) + with);
    require(rows == 0 || layout != SectionLayout::Radial, "`rows` applies to the grid and rows layouts only (got " + std::to_string(rows) + with);
    require(rings == 0 || layout == SectionLayout::Radial, "`rings` applies to the radial layout only (got " + std::to_string(rings) + with);
    require(wedges == 0 || layout == SectionLayout::Radial, "`wedges` applies to the radial layout only (got " + std::to_string(wedges) + with);
    require(!has_crown || layout == SectionLayout::Radial, "`crown` applies to the radial layout only (got it" + with);
    require(!has_crown || isfinite(crown), "`crown` must be finite");
    require(guide != SectionGuide::Along || layout != SectionLayout::Radial, "`guide` along runs front to back: grid and rows layouts only (got it" + with);
    finite_at_least("size", size, 0.0f, false);
    finite_at_least("parting_gap", parting_gap, 0.0f, true);
    finite_at_least("step", step, 0.0f, true);
    finite_at_least("length", length, 0.0f, true);
    require(points >= 4 && points <= 100000, "`points` must be in [4, 100000] (got " + std::to_string(points) + ")");
    finite_at_least("bend", bend, 0.0f, true);
    require(isfinite(hang), "`hang` must be a finite direction (0,0,0 = down)");
    finite_at_least("sweep", sweep, 0.0f, false);
    finite_at_least("clearance", clearance, 0.0f, false);
    finite_at_least("layer", layer, 0.0f, false);
    require(std::isfinite(jitter) && jitter >= 0.0f && jitter <= 45.0f, "`jitter` must be in [0, 45] degrees (got " + format_number(jitter) + ")");
    require(roots >= 0 && roots <= 100000000, "`roots` must be in [0, 1e8] (got " + std::to_string(roots) + ")");
    require(root_points >= 2 && root_points <= 64, "`root_points` must be in [2, 64] (got " + std::to_string(root_points) + ")");
    require(first_id >= 0, "`first_id` must be >= 0 (got " + std::to_string(first_id) + ")");
}

SectionsResult sections(const Surface& scalp, const CurveSet& hairline, const RootSampler* sample, const SectionsParams& params,
                        Progress* progress)
{
    params.validate();
    if (params.roots > 0 && !sample) throw InvalidParam("sections: `roots` needs a scalp sampler");
    if (hairline.num_curves() != 1) {
        throw InvalidGeometry("sections: expected a hairline (one closed curve around the head), found " + std::to_string(hairline.num_curves()) + " curves");
    }
    // Lengths against the head's size, the hairline's: a guide 65536 long on a head 34 across ran
    // for 240 s and partings a million wide for minutes, with nothing said (a trial's typos).
    {
        const Bounds3 b = hairline.bounds();
        const float across = b.empty() ? 0.0f : length(b.hi - b.lo);
        if (across > 0.0f && params.length > 50.0f * across) {
            throw InvalidParam("sections: `length` " + format_number(params.length) + " is over 50 times the hairline's size (" + format_number(across) +
                               " across): give the hair's length in scene units");
        }
        if (across > 0.0f && params.parting_gap > across) {
            throw InvalidParam("sections: `parting_gap` " + format_number(params.parting_gap) + " is wider than the hairline (" + format_number(across) +
                               " across): give the bare width along each parting in scene units");
        }
    }
    HairRegionParams region_params;
    region_params.up = params.up;
    region_params.parting_gap = params.parting_gap;
    const HairRegion region(scalp, hairline, CurveSet(), region_params);
    const SectionMap map(scalp, hairline, region, params, progress);

    SectionsResult result;
    result.sections = map.sections();
    std::vector<SectionInfo>& secs = result.sections;
    const size_t ns = secs.size();
    SectionsReport& rep = result.report;
    rep.bands = map.num_bands();
    rep.rays = map.rays();
    rep.min_area = std::numeric_limits<double>::infinity();
    for (const SectionInfo& s : secs) {
        rep.haired_area += s.area;
        rep.min_area = std::min(rep.min_area, s.area);
        rep.max_area = std::max(rep.max_area, s.area);
    }
    const float side = float(std::sqrt(rep.haired_area / double(ns)));
    const float tiny = 1e-5f * map.mean_radius();

    // --- Partings: each border line's waypoints joined on the scalp.
    // Before drawing them: a border (at most one per section and band) is shorter than the scalp's
    // circumference, and its path holds a point per `step`, twice (waypoints, path). On a head 1e4
    // times larger than the default `step` expects, the defaults walked for minutes (op fuzzer).
    const double parting_points = double(ns + map.num_bands() + 1) * 2.0 * std::numbers::pi * double(map.mean_radius()) / double(params.step);
    check_memory("sections: partings of up to " + format_number(parting_points) + " points at `step` " + format_number(params.step) +
                     " on a scalp of mean radius " + format_number(map.mean_radius()),
                 parting_points * 24.0, "use a larger `step`");
    const std::vector<SectionMap::Border> borders = map.borders(4.0f * params.step, 0.5f * params.parting_gap);
    std::vector<std::vector<float3>> paths(borders.size());
    parallel_for(int64_t(borders.size()), 1, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            if (!surface_path_through(scalp, borders[i].points, params.step, 0.0f, paths[i])) {
                throw InvalidGeometry("sections: a parting could not be drawn on the scalp (a hole or a fold near " +
                                      format_xyz(borders[i].points.front()) + "?)");
            }
        }
    });
    {
        std::vector<int64_t> counts;
        for (const auto& p : paths) counts.push_back(int64_t(p.size()));
        CurveSet& out = result.partings;
        out = CurveSet::from_counts(counts);
        auto P = out.positions_for_write();
        auto id = out.add<int64_t>(Domain::Curve, attr::id);
        auto kind = out.add<int32_t>(Domain::Curve, "kind");
        auto band = out.add<int32_t>(Domain::Curve, "band");
        for (size_t i = 0; i < paths.size(); ++i) {
            std::copy(paths[i].begin(), paths[i].end(), P.begin() + out.points_of(i).begin);
            id[i] = int64_t(i);
            kind[i] = borders[i].kind;
            band[i] = borders[i].band;
        }
    }

    // --- Guides.
    const float3 up = normalize(params.up);
    const float3 fwd = normalize(params.forward - up * dot(params.forward, up));
    const float3 gravity = length(params.hang) > 0.0f ? normalize(params.hang) : -up;
    const bool along = params.guide == SectionGuide::Along || (params.guide == SectionGuide::Auto && params.layout == SectionLayout::Rows);
    const double h_out = double(params.length) / (params.points - 1);
    const double h = std::min(0.5 * h_out, params.bend / 8.0);
    std::vector<std::vector<float3>> guides(ns);
    std::vector<float> scalp_length(ns, 0.0f), feed_length(ns, 0.0f);
    {
        ProgressStep step(progress, "sections: guides", int64_t(ns));
        parallel_for(int64_t(ns), 1, [&](int64_t b, int64_t e) {
            for (int64_t s = b; s < e; ++s) {
                SectionInfo& info = secs[s];
                Fall fall;
                fall.face = region.centroid() + fwd * (1.5f * map.mean_radius());
                fall.up = up;
                fall.forward = fwd;
                fall.sweep = params.sweep;
                fall.rate = float(0.5 * kPi / params.bend);
                fall.reach = 0.5f * params.bend;
                fall.margin = tiny;
                // Hanging braids rooted higher lie over the ones below them: one `layer` per section
                // side between the root and the hairline, eased in over the first section side. Along
                // guides lie beside each other, not over.
                const float above = std::max(0.0f, region.hairline_margin(info.root) * distance(info.root, region.centroid()));
                fall.clearance = params.clearance;
                fall.layer = along ? 0.0f : params.layer * above / side;
                fall.ramp = side;
                Rng rng(params.seed, uint64_t(params.first_id + s), 1);
                const float3 e1 = any_perpendicular(gravity), e2 = cross(gravity, e1);
                const float a = float(2 * kPi) * rng.uniform(), tilt = std::tan(params.jitter * float(kPi / 180.0)) * rng.uniform();
                fall.gravity = normalize(gravity + (e1 * std::cos(a) + e2 * std::sin(a)) * tilt, gravity);

                std::vector<float3> pts;
                std::vector<float3> mid = along ? map.midline(int(s), std::max(params.parting_gap, params.clearance), float(h)) : std::vector<float3>{};
                float3 d;
                if (mid.size() >= 2) {
                    // Along the section on the scalp at the clearance (the root on the scalp), then free.
                    info.root = mid.front();
                    pts.push_back(mid.front());
                    for (size_t i = 1; i < mid.size(); ++i) {
                        float3 q = mid[i] + scalp.normal(mid[i]) * fall.clearance;
                        keep_outside(q, scalp, KeepOutside{fall.clearance, tiny, 4});
                        pts.push_back(q);
                    }
                    scalp_length[s] = polyline_length(pts);
                    d = normalize(pts.back() - pts[pts.size() - 2], gravity);
                }
                else {
                    pts.push_back(info.root);
                    d = scalp.normal(info.root);
                }
                march(scalp, pts.back(), d, params.length, h, polyline_length(pts), fall, pts);
                const double total = polyline_length(pts);
                const int count = mid.size() >= 2 ? std::max(params.points, int(std::lround(total / h_out)) + 1) : params.points;
                std::vector<float3> even = resample_by_count(pts, count);
                // Resampled points lie on chords, which dip toward a convex scalp: out again.
                for (size_t i = 1; i < even.size(); ++i) keep_outside(even[i], scalp, KeepOutside{fall.clearance, tiny, 4});
                // Roots join a hanging guide at its base (within its clearance of the root), an along
                // guide beside them.
                feed_length[s] = scalp_length[s] > 0.0f ? scalp_length[s] : fall.clearance;
                guides[s] = std::move(even);
            }
            step.advance(e - b);
        });
    }
    {
        std::vector<int64_t> counts;
        for (const auto& g : guides) counts.push_back(int64_t(g.size()));
        CurveSet& out = result.guides;
        out = CurveSet::from_counts(counts);
        auto P = out.positions_for_write();
        auto id = out.add<int64_t>(Domain::Curve, attr::id);
        auto section = out.add<int32_t>(Domain::Curve, "section");
        auto band = out.add<int32_t>(Domain::Curve, "band");
        auto cell = out.add<int32_t>(Domain::Curve, "cell");
        auto area = out.add<float>(Domain::Curve, "area");
        auto on_scalp = out.add<float>(Domain::Curve, "scalp_length");
        for (size_t s = 0; s < ns; ++s) {
            std::copy(guides[s].begin(), guides[s].end(), P.begin() + out.points_of(s).begin);
            id[s] = params.first_id + int64_t(s);
            section[s] = int32_t(s);
            band[s] = secs[s].band;
            cell[s] = secs[s].cell;
            area[s] = float(secs[s].area);
            on_scalp[s] = scalp_length[s];
        }
    }
    if (params.roots == 0) return result;

    // --- Roots: area-uniform, kept on haired scalp (inside the hairline, off the partings' gaps).
    const auto ppts = result.partings.positions();
    std::vector<int64_t> prev(ppts.size(), -1), next(ppts.size(), -1);
    for (size_t c = 0; c < result.partings.num_curves(); ++c) {
        const IndexRange r = result.partings.points_of(c);
        for (int64_t i = r.begin; i < r.end; ++i) {
            if (i > r.begin) prev[i] = i - 1;
            if (i + 1 < r.end) next[i] = i + 1;
        }
    }
    const PointIndex index(ppts);
    const uint64_t seed = mix64(params.seed ^ 0x73656374ull);
    std::vector<float3> roots;
    std::vector<int32_t> owner;
    for (int round = 0; int64_t(roots.size()) < params.roots && round < 64; ++round) {
        const int64_t ask = 3 * (params.roots - int64_t(roots.size())) + 64;
        const std::vector<SurfaceSample> smp = (*sample)(region.centroid(), 0.0f, ask, mix64(seed + uint64_t(round)));
        std::vector<int32_t> pick(smp.size(), -1);  // section, -1 outside, -2 bare
        parallel_for(int64_t(smp.size()), 256, [&](int64_t b, int64_t e) {
            std::vector<PointIndex::Neighbour> scratch;
            for (int64_t i = b; i < e; ++i) {
                const int s = map.section_of(smp[i].position);
                if (s < 0) continue;
                const bool bare = !ppts.empty() && parting_distance(smp[i].position, index, ppts, prev, next, scratch) <= 0.5f * params.parting_gap;
                pick[i] = bare ? -2 : s;
            }
        });
        for (size_t i = 0; i < smp.size() && int64_t(roots.size()) < params.roots; ++i) {
            if (pick[i] == -2) ++rep.roots_bare;
            if (pick[i] < 0) continue;
            roots.push_back(smp[i].position);
            owner.push_back(pick[i]);
        }
    }
    if (int64_t(roots.size()) < params.roots) {
        throw LimitExceeded("sections: found " + std::to_string(roots.size()) + " of " + std::to_string(params.roots) +
                            " roots on the haired scalp in 64 rounds of sampling (is the sampler's scalp the one the hairline is on?)");
    }
    const int64_t nr = int64_t(roots.size());
    CurveSet& out = result.roots;
    out = CurveSet::from_counts(std::vector<int64_t>(size_t(nr), params.root_points));
    auto P = out.positions_for_write();
    auto id = out.add<int64_t>(Domain::Curve, attr::id);
    auto section = out.add<int32_t>(Domain::Curve, "section");
    ProgressStep step(progress, "sections: roots", nr);
    parallel_for(nr, 256, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            const int s = owner[i];
            // The nearest point of the guide's part near the scalp: where this root's hair joins the braid.
            const std::vector<float3>& g = guides[s];
            float3 target = g.front();
            double best = std::numeric_limits<double>::infinity(), walked = 0.0;
            for (size_t k = 0; k + 1 < g.size() && walked <= feed_length[s]; ++k) {
                const float3 ab = g[k + 1] - g[k];
                const float l2 = dot(ab, ab);
                const float t = l2 > 0.0f ? std::clamp(dot(roots[i] - g[k], ab) / l2, 0.0f, 1.0f) : 0.0f;
                const float3 q = g[k] + ab * t;
                const double d = distance(roots[i], q);
                if (d < best) best = d, target = q;
                walked += std::sqrt(l2);
            }
            const IndexRange r = out.points_of(size_t(i));
            for (int k = 0; k < params.root_points; ++k) {
                float3 q = lerp(roots[i], target, float(k) / float(params.root_points - 1));
                // A chord between two points of a convex scalp runs inside it: each point but the root onto it.
                if (k > 0) keep_outside(q, scalp, KeepOutside{0.0f, tiny, 4});
                P[r.begin + k] = q;
            }
            id[i] = params.first_id + int64_t(ns) + i;
            section[i] = s;
        }
        step.advance(e - b);
    });
    add_root_uvs(result.guides, scalp);
    return result;
}

}  // namespace groom
