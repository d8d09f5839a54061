#include "cli/width_options.h"

#include "kernel/error.h"

namespace groom::cli {

void add_width_options(CLI::App* app, WidthOptions& o, const std::string& unset)
{
    const std::string root = format_number(kDefaultRootWidthCm), tip = format_number(kDefaultTipWidthCm);
    const std::string when_unset = unset.empty() ? "" : "; neither given: " + unset;
    o.root_opt = app->add_option("--root-width", o.root,
                                 "Hair diameter at the root, scene units, > 0 (default " + root +
                                     ": a human hair in cm), tapering linearly in arc length to --tip-width" + when_unset);
    o.tip_opt = app->add_option("--tip-width", o.tip, "Hair diameter at the tip, scene units, >= 0 (default " + tip + ")");
}

HairWidths hair_widths_from(const WidthOptions& o, std::string_view command)
{
    HairWidths w;
    if (o.root_opt && o.root_opt->count()) w.root = o.root;
    if (o.tip_opt && o.tip_opt->count()) w.tip = o.tip;
    w.validate(command);
    return w;
}

}  // namespace groom::cli
