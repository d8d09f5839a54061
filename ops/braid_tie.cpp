#include "ops/braid_tie.h"

#include "kernel/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace groom {

namespace {

/// The tie band of one guide: `turns` wraps of an ellipse around the pinched braid at params.tie,
/// advancing one band width per turn along the guide. Writes `count` points from `out`.
void tie_band(const BraidParams& p, const CurveSet& strands, const StrandSections& sec, int64_t first_strand, int N,
              float band_width, double strand_length, std::span<float3> out)
{
    // The strand sample nearest the tie: every strand of a guide shares the guide's samples.
    const IndexRange r0 = strands.points_of(first_strand);
    const int64_t S = r0.size();
    const int64_t j = std::clamp<int64_t>(int64_t(std::lround(double(*p.tie) * double(S - 1))), 0, S - 1);
    const auto P = strands.positions();
    const auto W = strands.find<float>(Domain::Point, attr::width);
    const int64_t q0 = r0.begin + j;
    const float3 c = sec.centre[q0], b = sec.lateral[q0], n = sec.up[q0];
    const float3 tan = normalize(cross(b, n));
    // Reach of the strands' hair from the centre, across and up, over the stretch the band covers.
    const double len = double(strand_length);
    const double half_span = 0.5 * double(p.tie_turns) * band_width + band_width;
    float rx = 0.0f, ry = 0.0f;
    for (int64_t jj = 0; jj < S; ++jj) {
        if (std::fabs(double(jj - j)) / double(S - 1) * len > half_span) continue;
        const int64_t qc = r0.begin + jj;
        for (int i = 0; i < N; ++i) {
            const int64_t q = strands.points_of(first_strand + i).begin + jj;
            const float3 d = P[q] - sec.centre[qc];
            const float hw = 0.5f * W[q] * (kFiberSpreadAcross + 0.5f * p.flatten);
            rx = std::max(rx, std::fabs(dot(d, b)) + hw);
            ry = std::max(ry, std::fabs(dot(d, n)) + hw);
        }
    }
    rx += 0.5f * band_width;
    ry += 0.5f * band_width;
    const int64_t count = int64_t(out.size());
    const double span = double(p.tie_turns) * band_width;
    for (int64_t k = 0; k < count; ++k) {
        const double f = double(k) / double(count - 1);
        const double ang = 2.0 * std::numbers::pi * p.tie_turns * f;
        out[k] = c + b * float(rx * std::cos(ang)) + n * float(ry * std::sin(ang)) + tan * float((f - 0.5) * span);
    }
}

}  // namespace

CurveSet append_ties(const CurveSet& hair, const CurveSet& strands, const StrandSections& sec, const BraidParams& params,
                     std::span<const GuidePlan> plans, std::span<const int64_t> first_strand)
{
    const int N = params.strand_count();
    const int64_t M = params.fibers;
    const size_t ng = first_strand.size();
    constexpr int64_t kTiePointsPerTurn = 24;
    const int64_t tie_points = kTiePointsPerTurn * params.tie_turns + 1;
    std::vector<int64_t> counts(hair.num_curves(), 0);
    const auto hair_offsets = hair.offsets();
    for (size_t c = 0; c < hair.num_curves(); ++c) counts[c] = hair_offsets[c + 1] - hair_offsets[c];
    std::vector<int64_t> tie_guide;
    for (size_t g = 0; g < ng; ++g) {
        if (first_strand[g] < 0) continue;
        counts.push_back(tie_points);
        tie_guide.push_back(int64_t(g));
    }
    CurveSet out = CurveSet::from_counts(counts);
    const int64_t nh = int64_t(hair.num_curves());
    std::vector<int64_t> tie_src_curve(out.num_curves()), tie_src_point(out.num_points());
    for (int64_t c = 0; c < nh; ++c) tie_src_curve[c] = c;
    for (int64_t p = 0; p < int64_t(hair.num_points()); ++p) tie_src_point[p] = p;
    auto oP = out.positions_for_write();
    const auto hP = hair.positions();
    std::copy(hP.begin(), hP.end(), oP.begin());
    auto ow = out.add<float>(Domain::Point, attr::width);
    const auto hw = hair.find<float>(Domain::Point, attr::width);
    std::copy(hw.begin(), hw.end(), ow.begin());
    auto oid = out.add<int64_t>(Domain::Curve, attr::id);
    auto okind = out.add<int32_t>(Domain::Curve, "kind");
    auto ostrand = out.add<int32_t>(Domain::Curve, "strand");
    const auto hid = hair.find<int64_t>(Domain::Curve, attr::id);
    const auto hstrand = hair.find<int32_t>(Domain::Curve, "strand");
    std::copy(hid.begin(), hid.end(), oid.begin());
    std::copy(hstrand.begin(), hstrand.end(), ostrand.begin());
    std::fill(okind.begin(), okind.begin() + nh, 0);
    std::span<int32_t> ofiber;
    if (M > 0) {
        ofiber = out.add<int32_t>(Domain::Curve, "fiber");
        const auto hf = hair.find<int32_t>(Domain::Curve, "fiber");
        std::copy(hf.begin(), hf.end(), ofiber.begin());
    }
    int64_t tie_id0 = 0;
    for (const int64_t id : hid) tie_id0 = std::max(tie_id0, id + 1);
    if (tie_id0 > std::numeric_limits<int64_t>::max() - int64_t(tie_guide.size())) {
        throw LimitExceeded("braid: tie ids past the largest hair id overflow a 64-bit id; lower the guide ids");
    }
    for (size_t k = 0; k < tie_guide.size(); ++k) {
        const int64_t g = tie_guide[k];
        const int64_t c = nh + int64_t(k);
        const int64_t fs = first_strand[g];
        const IndexRange r = out.points_of(c);
        const float sw = strands.find<float>(Domain::Point, attr::width)[strands.points_of(fs).begin];
        const float band = params.tie_width > 0.0f ? params.tie_width : 0.35f * std::max(sw, 1e-6f);
        tie_band(params, strands, sec, fs, N, band, plans[g].length, oP.subspan(r.begin, r.size()));
        for (int64_t p = r.begin; p < r.end; ++p) ow[p] = band;
        // After every hair id (not negative: tinyusdz, and so some USD readers, refuse negative int64s).
        oid[c] = tie_id0 + int64_t(k);
        okind[c] = 1;
        ostrand[c] = -1;
        if (M > 0) ofiber[c] = -1;
        // Curve attributes from the guide's first hair curve, point attributes from its first point.
        const int64_t first_hair = M > 0 ? fs * M : fs;
        tie_src_curve[c] = first_hair;
        for (int64_t p = r.begin; p < r.end; ++p) tie_src_point[p] = hair.points_of(first_hair).begin;
    }
    carry_curve_attributes(hair, out, tie_src_curve);
    carry_point_attributes(hair, out, tie_src_point, {attr::P, attr::width});
    return out;
}

}  // namespace groom
