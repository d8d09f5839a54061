#include "ops/puff.h"
#include "ops/root_uv.h"

#include "fields/keep_outside.h"
#include "kernel/error.h"
#include "kernel/memory_budget.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"
#include "ops/hair_types.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

namespace groom {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string str(float v) { return format_number(v); }

std::string str(const float3& v) { return str(v.x) + "," + str(v.y) + "," + str(v.z); }

/// Shirley & Chiu's concentric map from [-1,1]^2 to the unit disc: equal-area, continuous, and it
/// keeps a grid's neighbourhoods, so cells of a square grid become equal-area cells of the disc.
void concentric_disc(double sx, double sy, double& dx, double& dy)
{
    if (sx == 0.0 && sy == 0.0) {
        dx = dy = 0.0;
        return;
    }
    double r, phi;
    if (std::fabs(sx) > std::fabs(sy)) {
        r = sx;
        phi = (kPi / 4.0) * (sy / sx);
    }
    else {
        r = sy;
        phi = kPi / 2.0 - (kPi / 4.0) * (sx / sy);
    }
    dx = r * std::cos(phi);
    dy = r * std::sin(phi);
}

float3 bezier(const float3& p0, const float3& p1, const float3& p2, const float3& p3, float t)
{
    const float s = 1.0f - t;
    return p0 * (s * s * s) + p1 * (3.0f * s * s * t) + p2 * (3.0f * s * t * t) + p3 * (t * t * t);
}

}  // namespace

void PuffParams::validate() const
{
    if (!(radius > 0.0f) || !std::isfinite(radius)) {
        throw InvalidParam("puff: `radius` must be a finite number > 0 (got " + str(radius) + ")");
    }
    if (!(sphere_radius > 0.0f) || !std::isfinite(sphere_radius)) {
        throw InvalidParam("puff: `sphere_radius` must be a finite number > 0 (got " + str(sphere_radius) + ")");
    }
    if (!isfinite(center)) throw InvalidParam("puff: `center` must be finite (got " + str(center) + ")");
    if (!isfinite(sphere_center)) {
        throw InvalidParam("puff: `sphere_center` must be finite (got " + str(sphere_center) + ")");
    }
    if (rows < 1 || rows > 256) throw InvalidParam("puff: `rows` must be in 1..256 (got " + std::to_string(rows) + ")");
    if (cols < 1 || cols > 256) throw InvalidParam("puff: `cols` must be in 1..256 (got " + std::to_string(cols) + ")");
    if (!(cap_angle > 0.0f && cap_angle < 180.0f)) {
        throw InvalidParam("puff: `cap_angle` must be in (0, 180) degrees (got " + str(cap_angle) + ")");
    }
    // At most 4096: a guide's points are what every hair blends, and 10^6 of them ran past 100 s,
    // 10^8 past the memory, before anything said no (a trial). 16 already follow a puff's curve.
    if (guide_points < 4 || guide_points > 4096) {
        throw InvalidParam("puff: `guide_points` must be in [4, 4096] (got " + std::to_string(guide_points) + ")");
    }
    if (!(bend > 0.0f && bend <= 1.0f)) throw InvalidParam("puff: `bend` must be in (0, 1] (got " + str(bend) + ")");
    if (first_id < 0) throw InvalidParam("puff: `first_id` must be >= 0 (got " + std::to_string(first_id) + ")");
    if (hairs < 0) throw InvalidParam("puff: `hairs` must be >= 0 (got " + std::to_string(hairs) + ")");
    // Ids first_id .. first_id + rows * cols + hairs - 1 must not pass int64 (they would wrap to negative).
    if (first_id > std::numeric_limits<int64_t>::max() - int64_t(rows) * cols - hairs) {
        throw InvalidParam("puff: `first_id` " + std::to_string(first_id) + " + " + std::to_string(int64_t(rows) * cols) + " guides + " +
                           std::to_string(hairs) + " `hairs` passes the largest id, 2^63 - 1 (ids would wrap to negative)");
    }
    if (hair_points < 4) throw InvalidParam("puff: `hair_points` must be >= 4 (got " + std::to_string(hair_points) + ")");
    if (neighbours < 1) throw InvalidParam("puff: `neighbours` must be >= 1 (got " + std::to_string(neighbours) + ")");
    if (!(power > 0.0f) || !std::isfinite(power)) {
        throw InvalidParam("puff: `power` must be a finite number > 0 (got " + str(power) + ")");
    }
    if (hairs > 0) curl.validate_for("puff");
}

float curl_reach(const CurlParams& params)
{
    float amplitude = params.amplitude.hi;
    if (params.amplitude.lo == 0.0f && params.amplitude.hi == 0.0f) {
        const HairTypePreset* type = find_hair_type(params.hair_type);
        amplitude = type ? type->radius_cm * params.units_per_cm * 1.2f : 0.0f;
    }
    const float n = params.shape.lame_exponent;
    const float shape = n > 2.0f ? std::pow(2.0f, 0.5f - 1.0f / n) : 1.0f;  // a squircle's corner
    return amplitude * shape + std::max(0.0f, params.offset.hi);
}

CurveSet puff_guides(const Surface& scalp, const PuffParams& params, Progress* progress)
{
    params.validate();
    const int ng = params.rows * params.cols, np = params.guide_points;
    ProgressStep step(progress, "puff guides", ng);

    // The region: a disc in the tangent plane at c0; the cap: around the axis from c0 to the centre.
    const float3 c0 = scalp.closest_point(params.center);
    const float3 n0 = scalp.normal(c0);
    // The region is centred where `center` lands on the scalp. Far off the scalp that is anywhere (a
    // centre 125 units off Sintel's head landed on her chest and the guides were refused as "two
    // guides touch", a trial): say what is wrong with it instead.
    const float off = std::fabs(scalp.distance(params.center));
    if (off > 2.0f * params.radius) {
        throw InvalidParam("puff: `center` " + str(params.center) + " is " + str(off) + " from the scalp, more than twice the region's `radius` " +
                           str(params.radius) + ": the puff's base would be where it lands on the scalp, " + str(c0) +
                           "; give a centre on the scalp where the puff should sit");
    }
    if (!(dot(params.sphere_center - c0, n0) > 0.0f)) {
        throw InvalidParam("puff: `sphere_center` " + str(params.sphere_center) + " must lie above the region, on the outer side of the scalp at " +
                           str(c0) + " (normal " + str(n0) + ")");
    }
    const PuffCap cap = PuffCap::make(scalp, c0, params.radius, params.sphere_center, params.sphere_radius, params.cap_angle);
    const float3 u = cap.u, v = cap.v, axis = cap.axis;

    // Cell centres of the rows x cols grid, mapped to the disc.
    std::vector<double> disc_x(ng), disc_y(ng);
    for (int i = 0; i < params.rows; ++i) {
        for (int j = 0; j < params.cols; ++j) {
            const double sx = 2.0 * (i + 0.5) / params.rows - 1.0, sy = 2.0 * (j + 0.5) / params.cols - 1.0;
            concentric_disc(sx, sy, disc_x[i * params.cols + j], disc_y[i * params.cols + j]);
        }
    }

    // Roots: the disc projected onto the scalp. On a convex scalp projection only pulls points in;
    // where the scalp is concave a root can land beyond the radius, so the disc shrinks until all fit.
    std::vector<float3> roots(ng);
    double shrink = 1.0;
    for (int attempt = 0;; ++attempt) {
        bool fits = true;
        for (int g = 0; g < ng; ++g) {
            const float3 q = c0 + (u * float(disc_x[g]) + v * float(disc_y[g])) * float(params.radius * shrink);
            roots[g] = scalp.closest_point(q);
            fits = fits && distance(roots[g], c0) <= params.radius;
        }
        if (fits) break;
        if (attempt == 30) {
            throw InvalidGeometry("puff: the scalp within `radius` " + str(params.radius) + " of " + str(c0) +
                                  " (the point of the scalp nearest `center`) is too folded to root a grid of guides");
        }
        shrink *= 0.9;
    }

    CurveSet dst = CurveSet::from_counts(std::vector<int64_t>(size_t(ng), np));
    auto P = dst.positions_for_write();
    auto ids = dst.add<int64_t>(Domain::Curve, attr::id);
    auto kind = dst.add<int32_t>(Domain::Curve, "kind");
    auto guide = dst.add<int32_t>(Domain::Curve, "guide");
    parallel_for(ng, 16, [&](int64_t b, int64_t e) {
        for (int64_t g = b; g < e; ++g) {
            const float3 tip = cap.tip_at(disc_x[g], disc_y[g]);
            const float3 d = normalize(tip - params.sphere_center);
            if (scalp.distance(tip) < 0.0f) {
                throw InvalidParam("puff: guide tip " + str(tip) + " on the sphere lies inside the scalp; lower `cap_angle` (got " +
                                   str(params.cap_angle) + ") or move `sphere_center` away from the head");
            }
            const float3 root = roots[g];
            const float3 nr = scalp.normal(root);
            // The tip's handle shrinks with the tip's height on the cap (d . axis): at the top the guide
            // arrives along the sphere's normal, the clean silhouette; toward the cap's rim, arriving
            // along the normal meant coming down from inside the ball, so the hair rose as a column
            // from the base and overhung it at the rim: a stalk under a ledge, a "cupcake" (a trial's
            // pictures). There it arrives from the base instead, fanning out.
            const float span = distance(tip, root);
            const float tip_handle = kPuffTipHandle * std::clamp(dot(d, axis), 0.0f, 1.0f);
            const float3 p1 = root + nr * (params.bend * span), p2 = tip - d * (tip_handle * span);
            // Dense samples, then even arc-length spacing; resampling keeps root and tip exactly.
            std::vector<float3> dense(size_t(np) * 8);
            for (size_t k = 0; k < dense.size(); ++k) dense[k] = bezier(root, p1, p2, tip, float(k) / float(dense.size() - 1));
            dense.front() = root;
            dense.back() = tip;
            const std::vector<float3> pts = resample_by_count(dense, np);
            std::copy(pts.begin(), pts.end(), P.begin() + g * np);
            ids[g] = params.first_id + g;
            kind[g] = 0;
            guide[g] = int32_t(g);
        }
        step.advance(e - b);
    });

    // Interior points only: roots stay on the scalp and tips on the sphere.
    for (int g = 0; g < ng && np > 2; ++g) {
        keep_outside(P.subspan(size_t(g) * np + 1, size_t(np - 2)), scalp, KeepOutside{});
    }

    const double sep = min_curve_separation(dst);
    if (ng > 1 && !(sep > 1e-5 * params.sphere_radius)) {
        throw InvalidGeometry("puff: two guides touch (closest " + std::to_string(sep) +
                              " apart); the region and the sphere cap fold onto each other: lower `cap_angle` or "
                              "`bend`, or move `sphere_center` over the region");
    }
    // What `groom gather` needs to pull the rest of the scalp's hair into this puff.
    dst.add<float3>(Domain::Detail, "puff_base")[0] = c0;
    dst.add<float>(Domain::Detail, "puff_radius")[0] = params.radius;
    dst.add<float3>(Domain::Detail, "puff_sphere_center")[0] = params.sphere_center;
    dst.add<float>(Domain::Detail, "puff_sphere_radius")[0] = params.sphere_radius;
    dst.add<float>(Domain::Detail, "puff_cap_angle")[0] = params.cap_angle;
    apply_hair_widths(dst, params.curl.widths, params.curl.units_per_cm);
    add_root_uvs(dst, scalp);
    return dst;
}

PuffResult puff(const Surface& scalp, const RootSampler& sample, const PuffParams& params, Progress* progress)
{
    params.validate();
    // The hairs' centrelines, before curling: a position and a source point each, and the roots.
    check_memory("puff: " + std::to_string(params.hairs) + " `hairs` x " + std::to_string(params.hair_points) + " `hair_points`",
                 double(params.hairs) * (double(params.hair_points) * 32.0 + 128.0), "ask for fewer `hairs`");
    PuffResult result;
    result.guides = puff_guides(scalp, params, progress);
    if (params.hairs == 0) return result;

    // Centrelines: roots area-uniform in the region, shapes blended from the nearest guides.
    GenerateParams gen;
    gen.count = params.hairs;
    gen.neighbours = params.neighbours;
    gen.power = params.power;
    gen.points = params.hair_points;
    gen.region_center = scalp.closest_point(params.center);
    gen.region_radius = params.radius;
    gen.seed = mix64(params.curl.seed ^ 0x70756666ull);  // roots and curls draw from different streams
    gen.first_id = params.first_id + int64_t(result.guides.num_curves());
    CurveSet centres = generate(result.guides, scalp, sample, gen, progress);

    PuffCap::make(scalp, gen.region_center, params.radius, params.sphere_center, params.sphere_radius, params.cap_angle).warp_onto(centres);
    keep_outside(centres, scalp, KeepOutside{});

    CurlParams curl_params = params.curl;
    curl_params.preserve_length = false;
    // The curl op can keep points out of the scalp itself, but it asks the scalp about every
    // point, and far from a ScalpField's narrow band each answer is an exact mesh search (two
    // thirds of the time of a two-puff groom). Only points near the root can end up inside, so
    // curl freely and keep the result outside afterwards, which skips the points provably outside.
    result.hairs = curl(centres, curl_params, nullptr, progress);
    keep_outside(result.hairs, scalp, KeepOutside{});
    // Hairs taper over their own final length, not the guides' (whose widths the centrelines carry).
    apply_hair_widths(result.hairs, params.curl.widths.resolved(params.curl.units_per_cm));
    for (int32_t& k : result.hairs.add<int32_t>(Domain::Curve, "kind")) k = 1;
    return result;
}

PuffCap PuffCap::make(const Surface& scalp, const float3& base, float radius, const float3& sphere_center, float sphere_radius,
                      float cap_angle_degrees)
{
    PuffCap cap;
    cap.base = base;
    const float3 n0 = scalp.normal(base);
    cap.u = any_perpendicular(n0);
    cap.v = cross(n0, cap.u);
    cap.axis = normalize(sphere_center - base, n0);
    cap.ut = cap.u - cap.axis * dot(cap.u, cap.axis);
    cap.ut = length(cap.ut) > 1e-3f ? normalize(cap.ut) : any_perpendicular(cap.axis);
    cap.vt = cross(cap.axis, cap.ut);
    cap.radius = radius;
    cap.cos_cap = std::cos(double(cap_angle_degrees) * kPi / 180.0);
    cap.sphere_center = sphere_center;
    cap.sphere_radius = sphere_radius;
    return cap;
}

float3 PuffCap::at(double rho, const float3& side) const
{
    const double cos_t = 1.0 - rho * rho * (1.0 - cos_cap);
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    return sphere_center + normalize(axis * float(cos_t) + side * float(sin_t)) * sphere_radius;
}

float3 PuffCap::tip_at(double dx, double dy) const
{
    const double rho = std::hypot(dx, dy);
    const double ax = rho > 0.0 ? dx / rho : 0.0, ay = rho > 0.0 ? dy / rho : 0.0;
    return at(rho, ut * float(ax) + vt * float(ay));
}

float3 PuffCap::tip_for(const float3& x, const float3& blended) const
{
    double dx = double(dot(x - base, u)) / double(radius), dy = double(dot(x - base, v)) / double(radius);
    const double len = std::hypot(dx, dy);
    if (len > 1.0) dx /= len, dy /= len;
    const float3 b = blended - sphere_center;
    const float3 side = b - axis * dot(b, axis);
    if (!(length(side) > 1e-6f * sphere_radius)) return tip_at(dx, dy);
    return at(std::min(len, 1.0), normalize(side));
}

void PuffCap::warp_onto(CurveSet& centres, std::span<const float3> follows) const
{
    const auto P = centres.positions();
    std::vector<float3> tips(centres.num_curves());
    for (size_t c = 0; c < tips.size(); ++c) {
        const IndexRange r = centres.points_of(c);
        if (r.size() < 2) continue;
        tips[c] = tip_for(follows.empty() ? P[size_t(r.begin)] : follows[c], P[size_t(r.end - 1)]);
    }
    warp_tips_to(centres, tips);
}

void warp_tips_to(CurveSet& centres, std::span<const float3> targets)
{
    // A warp that vanishes with its derivative at the root: the root and its direction stay.
    auto P = centres.positions_for_write();
    parallel_for(int64_t(centres.num_curves()), 256, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = centres.points_of(c);
            if (r.size() < 2) continue;
            const auto pts = P.subspan(r.begin, r.size());
            const auto cum = cumulative_lengths(pts);
            const float3 shift = targets[size_t(c)] - pts.back();
            for (size_t i = 1; i < pts.size(); ++i) {
                const float s = cum.back() > 0.0 ? float(cum[i] / cum.back()) : 1.0f;
                pts[i] += shift * (s * s);
            }
            pts.back() = targets[size_t(c)];  // exact, not up to rounding
        }
    });
}

void warp_tips_to_sphere(CurveSet& centres, const float3& C, float R)
{
    const auto P = centres.positions();
    std::vector<float3> targets(centres.num_curves());
    for (size_t c = 0; c < targets.size(); ++c) {
        const IndexRange r = centres.points_of(c);
        if (r.size() < 2) continue;
        const float3 tip = P[size_t(r.end - 1)];
        targets[c] = C + normalize(tip - C, normalize(tip - P[size_t(r.begin)])) * R;
    }
    warp_tips_to(centres, targets);
}

double min_curve_separation(const CurveSet& curves)
{
    const auto P = curves.positions();
    const int64_t nc = int64_t(curves.num_curves());
    std::vector<Bounds3> boxes(static_cast<size_t>(nc));
    for (int64_t c = 0; c < nc; ++c) {
        const IndexRange r = curves.points_of(c);
        for (int64_t p = r.begin; p < r.end; ++p) boxes[c].extend(P[p]);
    }
    // Per first curve, the closest of all later curves; then the minimum over first curves.
    std::vector<double> best(static_cast<size_t>(nc), std::numeric_limits<double>::infinity());
    parallel_for(nc, 4, [&](int64_t b, int64_t e) {
        for (int64_t a = b; a < e; ++a) {
            const IndexRange ra = curves.points_of(a);
            double m = std::numeric_limits<double>::infinity();
            for (int64_t c = a + 1; c < nc; ++c) {
                // Boxes apart by more than the best so far cannot improve it.
                const float3 gap = max(max(boxes[a].lo - boxes[c].hi, boxes[c].lo - boxes[a].hi), float3());
                if (double(length_squared(gap)) > m) continue;
                const IndexRange rc = curves.points_of(c);
                for (int64_t i = ra.begin; i + 1 < ra.end; ++i) {
                    for (int64_t j = rc.begin; j + 1 < rc.end; ++j) {
                        m = std::min(m, segment_distance_sq(P[i], P[i + 1], P[j], P[j + 1]));
                    }
                }
            }
            best[a] = m;
        }
    });
    double m = std::numeric_limits<double>::infinity();
    for (double d : best) m = std::min(m, d);
    return std::sqrt(m);
}

}  // namespace groom
