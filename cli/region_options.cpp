#include "cli/region_options.h"

#include "cli/command.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"

namespace groom::cli {

void add_region_options(CLI::App* app, RegionOptions& o)
{
    app->add_option("--hairline", o.hairline, "Hairline: one closed curve around the head (`groom hairline`); roots only inside it");
    app->add_option("--parting", o.parting, "Partings: curves on the scalp (`groom parting`); bare lines no hair crosses");
    app->add_option("--parting-gap", o.params.parting_gap, "Bare width along each parting, scene units, >= 0")->capture_default_str();
    app->add_option("--up", o.up, "X,Y,Z: the head's up direction (reading the hairline)")->capture_default_str();
}

CurveSet read_hairline(const std::string& path, const CommonOptions* common)
{
    CurveReadOptions ro;
    ro.closed_loops = true;
    if (common) ro.warn = [common](const std::string& w) { warn(*common, "warning: " + w); };
    return read_curves(path, ro);
}

CurveSet reported_hairline(const std::string& command, const Surface& scalp, const Bounds3& bounds, const HairlineParams& params,
                           const CommonOptions& common)
{
    HairlineReport report;
    CurveSet hairline = make_hairline(scalp, bounds, params, &report);
    for (const auto& [is_warning, m] : report.messages(command, params.forward)) is_warning ? warn(common, m) : note(common, m);
    return hairline;
}

std::unique_ptr<HairRegion> make_region(const RegionOptions& o, const Surface& scalp, const CurveSet* hairline_if_none)
{
    HairRegionParams params = o.params;
    params.up = parse_float3("--up", o.up);
    params.validate();
    if (!o.given() && !hairline_if_none) return nullptr;
    // Readers name the file in their own errors.
    const CurveSet hairline = !o.hairline.empty() ? read_hairline(o.hairline) : hairline_if_none ? *hairline_if_none : CurveSet();
    const CurveSet partings = o.parting.empty() ? CurveSet() : read_curves(o.parting);
    try {
        return std::make_unique<HairRegion>(scalp, hairline, partings, params);
    }
    catch (const InvalidGeometry& e) {
        // The region names `hairline` or `parting`; the user typed a file.
        const std::string what = e.what();
        const std::string file = what.rfind("hairline", 0) == 0 ? (o.hairline.empty() ? std::string("the default hairline") : o.hairline) : o.parting;
        throw InvalidGeometry(file + ": " + what);
    }
}

}  // namespace groom::cli
