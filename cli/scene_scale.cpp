#include "cli/scene_scale.h"

#include "kernel/error.h"
#include "kernel/math/polyline.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace groom::cli {

void warn_scene_scale(const CommonOptions& common, const std::string& command, const Bounds3& scalp, float units_per_cm,
                      const std::string& what)
{
    if (scalp.empty() || !(units_per_cm > 0.0f)) return;
    const float3 size = scalp.size();
    const double extent = std::max({size.x, size.y, size.z});
    // A scalp mesh is at least a head (15 cm and more across) and at most a whole body (about 2 m).
    const double lo = 10.0 * units_per_cm, hi = 300.0 * units_per_cm;
    if (extent >= lo && extent <= hi) return;
    warn(common, command + ": warning: the scalp is " + format_number(extent) + " scene units across, but " + what +
                     " are centimetres x --units-per-cm " + format_number(units_per_cm) + ", for a head, bust or body " +
                     format_number(lo) + " to " + format_number(hi) + " units across: if the scene is in other units pass " +
                     "--units-per-cm (0.01 for metres, 10 for millimetres)");
}

void check_units_per_cm(const std::string& command, float units_per_cm)
{
    if (!(units_per_cm > 0.0f) || !std::isfinite(units_per_cm)) {
        throw InvalidParam(command + ": --units-per-cm must be a finite number > 0 (got " + format_number(units_per_cm) + ")");
    }
}

void scale_default_lengths(const CLI::App& app, float units_per_cm, std::initializer_list<std::pair<const char*, float*>> lengths)
{
    for (const auto& [option, value] : lengths) {
        if (app.count(option) == 0) *value *= units_per_cm;
    }
}

double median_curve_length(const CurveSet& curves)
{
    const auto P = curves.positions();
    std::vector<double> lengths(curves.num_curves());
    for (size_t c = 0; c < curves.num_curves(); ++c) {
        const IndexRange r = curves.points_of(c);
        lengths[c] = polyline_length(P.subspan(size_t(r.begin), size_t(r.size())));
    }
    if (lengths.empty()) return 0.0;
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    return lengths[lengths.size() / 2];
}

void warn_curl_scale(const CommonOptions& common, const std::string& command, const CurveSet& hair, float radius, const std::string& how)
{
    const double median = median_curve_length(hair);
    if (!(median > 0.0) || !(radius > 0.0f)) return;
    if (radius <= 0.5 * median && radius >= 1e-3 * median) return;
    warn(common, command + ": warning: the curl radius " + format_number(radius) + " (" + how + ") is " +
                     (radius > 0.5 * median ? "more than half" : "under a thousandth of") + " the hairs' median length " +
                     format_number(median) + ", so the curls will not show: if the scene is not in centimetres pass --units-per-cm " +
                     "(0.01 for metres, 10 for millimetres), or give --amplitude");
}

}  // namespace groom::cli
