#include "ops/resample.h"

#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/memory_budget.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace groom {

void ResampleParams::validate() const
{
    if (count != 0 && segment_length != 0) {
        throw InvalidParam("resample: `count` and `segment_length` are exclusive (got both)");
    }
    if (count == 0 && !(segment_length > 0)) {
        throw InvalidParam("resample: give `count` N (>= 2) or `segment_length` L (> 0)");
    }
    if (count != 0 && count < 2) throw InvalidParam("resample: `count` must be >= 2 (got " + std::to_string(count) + ")");
    if (count == 0 && !std::isfinite(segment_length)) throw InvalidParam("resample: `segment_length` must be finite");
}

CurveSet resample(const CurveSet& src, const ResampleParams& params)
{
    params.validate();
    const auto P = src.positions();
    const size_t nc = src.num_curves();
    // A loop's points include its first again at the end: 3 are a line there and back, 2 one point
    // twice (a trial's `--count 2` wrote a periodic curve of length 0). At least a triangle.
    const bool loops = is_closed(src);
    if (loops && params.count != 0 && params.count < 4) {
        throw InvalidParam("resample: these curves are closed loops (detail `closed`), whose last point is their first again: `count` must be >= 4 "
                           "for a loop of 3 points (got " + std::to_string(params.count) + ")");
    }

    // Count -> scan -> fill: each curve's new point count first, then offsets, then points. The counts
    // are taken in double and summed before anything is allocated: a 1e30-long curve asked llround
    // for a count past int64 (2 points came out), and a short file can ask for billions of points.
    std::vector<double> wanted(nc);
    parallel_for(int64_t(nc), 256, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = src.points_of(c);
            const double length = double(polyline_length(P.subspan(r.begin, r.size())));
            if (r.empty()) wanted[c] = 0.0;
            else if (!std::isfinite(length)) wanted[c] = length;
            else if (params.count) wanted[c] = params.count;
            else wanted[c] = std::max(loops ? 4.0 : 2.0, std::round(length / double(params.segment_length)) + 1.0);
        }
    });
    double total = 0.0;
    size_t longest = 0;
    for (size_t c = 0; c < nc; ++c) {
        if (!std::isfinite(wanted[c])) {
            throw InvalidGeometry("resample: curve " + std::to_string(c) +
                                  " is too long for float to measure (its length overflows): scale the curves down");
        }
        total += wanted[c];
        if (wanted[c] > wanted[longest]) longest = c;
    }
    // Each output point costs its position, its source index and every other point column carried.
    const double per_point = double(sizeof(float3) + sizeof(int64_t)) + bytes_per_point(src);
    const std::string what = "resample: " + format_number(total) + " points" +
                             (params.count ? " (`count` " + std::to_string(params.count) + " per curve)"
                                           : " at `segment_length` " + format_number(params.segment_length) + " (curve " +
                                                 std::to_string(longest) + " alone needs " + format_number(nc ? wanted[longest] : 0.0) + ")");
    check_memory(what, total * per_point + double(nc) * bytes_per_curve(src),
                 params.count ? "use a smaller `count`" : "use a larger `segment_length` or `count`");
    std::vector<int64_t> counts(nc);
    for (size_t c = 0; c < nc; ++c) counts[c] = int64_t(wanted[c]);

    CurveSet dst = CurveSet::from_counts(counts);
    auto dP = dst.positions_for_write();
    std::vector<int64_t> src_point(dst.num_points());
    parallel_for(int64_t(nc), 256, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = src.points_of(c), d = dst.points_of(c);
            if (d.empty()) continue;
            const auto in = P.subspan(r.begin, r.size());
            const auto out = resample_by_count(in, int(d.size()));
            std::copy(out.begin(), out.end(), dP.begin() + d.begin);
            // Nearest source point by arc length, for carrying other point attributes.
            const auto cum = cumulative_lengths(in);
            for (int64_t i = 0; i < d.size(); ++i) {
                const double s = d.size() > 1 ? cum.back() * double(i) / double(d.size() - 1) : 0.0;
                src_point[d.begin + i] = r.begin + int64_t(locate_at_length(cum, s).nearest);
            }
        }
    });
    std::vector<int64_t> identity(nc);
    for (size_t c = 0; c < nc; ++c) identity[c] = int64_t(c);
    carry_curve_attributes(src, dst, identity);
    carry_point_attributes(src, dst, src_point, {attr::P});
    set_closed(dst, is_closed(src));  // each curve keeps its ends: a loop stays one
    return dst;
}

}  // namespace groom
