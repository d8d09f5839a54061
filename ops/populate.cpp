#include "ops/populate.h"

#include "kernel/error.h"
#include "kernel/math/frames.h"
#include "kernel/math/polyline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"
#include "kernel/rng.h"

#include <cmath>
#include <limits>
#include <string>

namespace groom {

namespace {
/// Rng stream for the disc offsets; a distinct constant per purpose (kernel/rng.h).
constexpr uint64_t kStreamFiberDisc = 0x706f70756c617465ull;  // "populate"

std::string fmt(float v) { return format_number(v); }
}  // namespace

void PopulateParams::validate() const
{
    if (count < 1 || count > kMaxFibersPerCurve) {
        throw InvalidParam("populate: `count` must be in [1, " + std::to_string(kMaxFibersPerCurve) + "] (got " +
                           std::to_string(count) + ")");
    }
    if (!std::isfinite(radius) || radius < 0.0f) {
        throw InvalidParam("populate: `radius` must be a finite number >= 0 (got " + fmt(radius) + ")");
    }
    if (!std::isfinite(width) || width < 0.0f) {
        throw InvalidParam("populate: `width` must be a finite number >= 0 (got " + fmt(width) + ")");
    }
    widths.validate("populate");
    if (width > 0.0f && widths.given()) {
        throw InvalidParam("populate: `width` " + fmt(width) + " and --root-width/--tip-width are exclusive (one width, or a taper)");
    }
}

CurveSet populate(const CurveSet& src, const PopulateParams& params, Progress* progress)
{
    params.validate();
    const auto P = src.positions();
    const size_t nc = src.num_curves();
    const int64_t M = params.count;

    const auto src_width = src.find<float>(Domain::Point, attr::width);
    if (params.radius == 0.0f && src_width.empty() && src.num_points() > 0) {
        throw InvalidParam("populate: `radius` 0 takes the radius from point attribute 'width', which the input lacks "
                           "(give `radius` r > 0)");
    }
    std::span<const float> scale;
    if (!params.radius_scale.empty()) {
        scale = src.find<float>(Domain::Point, params.radius_scale);
        if (scale.empty() && src.num_points() > 0) {
            throw InvalidParam("populate: radius scale attribute '" + params.radius_scale +
                               "' is not a point float attribute of the input");
        }
    }

    if (double(src.num_points()) * double(M) > double(kMaxPopulatePoints)) {
        throw LimitExceeded("populate: " + std::to_string(src.num_points()) + " points x " + std::to_string(M) +
                            " fibers would make more than " + std::to_string(kMaxPopulatePoints) +
                            " points; lower `count` or resample the curves");
    }
    // What the output holds (every source column carried, plus position, width, fiber, id) and this
    // op's own arrays (the source point and curve of each output element, the counts).
    const double out_points = double(src.num_points()) * double(M), out_curves = double(nc) * double(M);
    check_memory("populate: " + std::to_string(src.num_curves()) + " curves x " + std::to_string(M) + " fibers (`count`) = " +
                     format_number(out_points) + " points",
                 out_points * (double(sizeof(float3) + sizeof(float) + sizeof(int64_t)) + bytes_per_point(src)) +
                     out_curves * (double(3 * sizeof(int64_t) + sizeof(int32_t) + sizeof(int64_t)) + bytes_per_curve(src)),
                 "lower `count`");
    const std::vector<int64_t> ids = src.curve_ids();
    for (const int64_t id : ids) {
        // id * M + f must not overflow, so ids stay unique and deterministic.
        if (id > (std::numeric_limits<int64_t>::max() - M) / M || id < std::numeric_limits<int64_t>::min() / M) {
            throw LimitExceeded("populate: curve id " + std::to_string(id) + " times " + std::to_string(M) +
                                " fibers overflows a 64-bit id");
        }
    }

    // Count -> scan -> fill: fiber f of curve c is output curve c*M + f with c's point count.
    std::vector<int64_t> counts(nc * M);
    std::vector<int64_t> src_curve(nc * M);
    for (size_t c = 0; c < nc; ++c) {
        for (int64_t f = 0; f < M; ++f) {
            counts[c * M + f] = src.points_in(c);
            src_curve[c * M + f] = int64_t(c);
        }
    }
    CurveSet dst = CurveSet::from_counts(counts);
    auto dP = dst.positions_for_write();
    auto dwidth = dst.add<float>(Domain::Point, attr::width);
    auto dfiber = dst.add<int32_t>(Domain::Curve, "fiber");
    auto did = dst.add<int64_t>(Domain::Curve, attr::id);
    std::vector<int64_t> src_point(dst.num_points());

    const ProgressStep step(progress, "populate", int64_t(nc));
    const float inv_sqrt_m = 1.0f / std::sqrt(float(M));
    parallel_for(int64_t(nc), 64, [&](int64_t begin, int64_t end) {
        std::vector<float> radius;
        for (int64_t c = begin; c < end; ++c) {
            const IndexRange r = src.points_of(c);
            const auto pts = P.subspan(r.begin, r.size());
            const auto tan = polyline_tangents(pts);
            // The disc is drawn rotation-invariantly, so any start normal is as good; a fixed rule keeps
            // the output deterministic.
            const auto frames = rotation_minimising_frames(pts, pts.empty() ? float3(1, 0, 0) : any_perpendicular(tan[0]));
            radius.resize(pts.size());
            for (int64_t j = 0; j < r.size(); ++j) {
                float rj = params.radius > 0.0f ? params.radius : 0.5f * src_width[r.begin + j];
                if (!scale.empty()) rj *= scale[r.begin + j];
                radius[j] = rj;
            }
            Rng rng(params.seed, uint64_t(ids[c]), kStreamFiberDisc);
            for (int64_t f = 0; f < M; ++f) {
                float u = 0.0f, v = 0.0f;
                rng.disc(u, v);
                const int64_t out_curve = c * M + f;
                const IndexRange d = dst.points_of(out_curve);
                dfiber[out_curve] = int32_t(f);
                did[out_curve] = ids[c] * M + f;
                for (int64_t j = 0; j < r.size(); ++j) {
                    const Frame& fr = frames[j];
                    dP[d.begin + j] = pts[j] + (fr.n * u + fr.b * v) * radius[j];
                    dwidth[d.begin + j] = params.width > 0.0f ? params.width : 2.0f * radius[j] * inv_sqrt_m;
                    src_point[d.begin + j] = r.begin + j;
                }
            }
            step.advance(1);
        }
    });
    carry_curve_attributes(src, dst, src_curve);
    carry_point_attributes(src, dst, src_point, {attr::P});
    if (params.widths.given()) apply_hair_widths(dst, params.widths);
    return dst;
}

}  // namespace groom
