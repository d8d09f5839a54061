#include "ops/hair_widths.h"

#include "kernel/error.h"
#include "kernel/parallel.h"

#include <cmath>
#include <vector>
#include <string>

namespace groom {

HairWidths HairWidths::resolved(float units_per_cm) const
{
    return {root.value_or(kDefaultRootWidthCm * units_per_cm), tip.value_or(kDefaultTipWidthCm * units_per_cm)};
}

void HairWidths::validate(std::string_view op) const
{
    // Widths beyond this are not hair in any unit anyone models in (1e6 scene units = 10 km in cm).
    constexpr float kMax = 1e6f;
    if (root && !(std::isfinite(*root) && *root > 0.0f && *root <= kMax)) {
        throw InvalidParam(std::string(op) + ": --root-width must be a finite number > 0 and <= 1e+06 (got " + format_number(*root) + ")");
    }
    if (tip && !(std::isfinite(*tip) && *tip >= 0.0f && *tip <= kMax)) {
        throw InvalidParam(std::string(op) + ": --tip-width must be a finite number >= 0 and <= 1e+06 (got " + format_number(*tip) + ")");
    }
}

namespace {

/// |a - b| in double: in float it overflows to inf past 1.8e19 apart (fibers of a guide 1e30 wide,
/// op_populate), and the arc-length fractions then came out inf / inf = NaN widths.
double segment_length(const float3& a, const float3& b)
{
    const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace

void taper_curve_widths(std::span<const float3> P, std::span<float> W, float root, float tip, std::vector<double>& seg)
{
    const int64_t n = int64_t(P.size());
    if (n == 0) return;
    seg.resize(size_t(n));  // each segment's length, measured once (the square roots were half the time)
    double total = 0.0;
    for (int64_t i = 1; i < n; ++i) {
        seg[size_t(i)] = segment_length(P[size_t(i)], P[size_t(i - 1)]);
        total += seg[size_t(i)];
    }
    // Fractions in double: (1 - f) r + f t is then monotone in f to double rounding, and the
    // one rounding to float keeps that order (rounding is monotone).
    const double r = root, t = tip;
    double s = 0.0;
    for (int64_t i = 0; i < n; ++i) {
        if (i > 0) s += seg[size_t(i)];
        double f = total > 0.0 ? s / total : (n > 1 ? double(i) / double(n - 1) : 0.0);
        if (i == n - 1 && n > 1) f = 1.0;  // the sum of the segments need not land on total exactly
        W[size_t(i)] = i == 0 ? root : f == 1.0 ? tip : float((1.0 - f) * r + f * t);
    }
}

void taper_widths(CurveSet& curves, float root, float tip)
{
    AttributeSet& points = curves.attributes(Domain::Point);
    if (const Attribute* a = points.find(attr::width); a && a->type() != AttrType::Float) points.remove(attr::width);
    // A per-curve width (USD's uniform widths) would shadow the per-point one in writers: the taper replaces it.
    curves.attributes(Domain::Curve).remove(attr::width);
    const auto P = curves.positions();
    auto W = curves.add<float>(Domain::Point, attr::width);
    parallel_for(int64_t(curves.num_curves()), 1024, [&](int64_t b, int64_t e) {
        std::vector<double> seg;
        for (int64_t c = b; c < e; ++c) {
            const IndexRange pr = curves.points_of(size_t(c));
            taper_curve_widths(P.subspan(size_t(pr.begin), size_t(pr.size())), W.subspan(size_t(pr.begin), size_t(pr.size())), root, tip,
                               seg);
        }
    });
}

std::optional<HairWidths> hair_widths_taper(const CurveSet& input, const HairWidths& widths, float units_per_cm)
{
    if (!widths.given() && (!input.find<float>(Domain::Point, attr::width).empty() || !input.find<float>(Domain::Curve, attr::width).empty())) {
        return std::nullopt;
    }
    return widths.resolved(units_per_cm);
}

void apply_hair_widths(CurveSet& curves, const HairWidths& widths, float units_per_cm)
{
    if (const std::optional<HairWidths> w = hair_widths_taper(curves, widths, units_per_cm)) {
        taper_widths(curves, *w->root, *w->tip);
        return;
    }
    if (!curves.find<float>(Domain::Point, attr::width).empty()) return;
    // A width per curve (a constant or uniform USD width) is still the input's width: keep it, per point.
    const auto cw = curves.find<float>(Domain::Curve, attr::width);
    const std::vector<float> per_curve(cw.begin(), cw.end());
    curves.attributes(Domain::Curve).remove(attr::width);
    auto W = curves.add<float>(Domain::Point, attr::width);
    for (size_t c = 0; c < curves.num_curves(); ++c) {
        const IndexRange pr = curves.points_of(c);
        for (int64_t i = pr.begin; i < pr.end; ++i) W[i] = per_curve[c];
    }
}

}  // namespace groom
