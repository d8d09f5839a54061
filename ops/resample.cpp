#include "ops/resample.h"

#include "kernel/error.h"
#include "kernel/math/polyline.h"
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

    // Count -> scan -> fill: each curve's new point count first, then offsets, then points.
    std::vector<int64_t> counts(nc);
    std::vector<float> lengths(nc);
    parallel_for(int64_t(nc), 256, [&](int64_t b, int64_t e) {
        for (int64_t c = b; c < e; ++c) {
            const IndexRange r = src.points_of(c);
            lengths[c] = polyline_length(P.subspan(r.begin, r.size()));
            if (params.count) counts[c] = params.count;
            else counts[c] = std::max<int64_t>(2, int64_t(std::llround(lengths[c] / params.segment_length)) + 1);
            if (r.empty()) counts[c] = 0;
        }
    });

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
    return dst;
}

}  // namespace groom
