// `groom populate`: fill a disc around each input curve with hair fibers (see ops/populate.h).
#include "cli/command.h"
#include "cli/width_options.h"
#include "kernel/io/curve_io.h"
#include "ops/populate.h"

namespace groom::cli {
namespace {

struct Args {
    std::string input, output;
    PopulateParams params;
    WidthOptions widths;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--count", args->params.count, "Fibers per input curve (M), 1..1000000")->capture_default_str();
    app->add_option("--radius", args->params.radius,
                    "Disc radius around each curve, scene units; 0 = half of each point's `width`")
        ->capture_default_str();
    app->add_option("--width", args->params.width, "Fiber width, scene units; 0 = 2 radius / sqrt(count) (fibers cover the disc)")
        ->capture_default_str();
    app->add_option("--radius-scale", args->params.radius_scale,
                    "Point float attribute of the input that scales the radius per point (e.g. a taper)");
    add_width_options(app, args->widths, "--width (one fiber width, automatic by default)");
    app->add_option("--seed", args->params.seed, "Random seed for the fiber offsets")->capture_default_str();
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {args->input}, common);
        args->params.widths = hair_widths_from(args->widths, "populate");
        args->params.validate();
        const CurveSet in = read_curves(args->input);
        const auto progress = make_progress(common);
        const CurveSet out = populate(in, args->params, progress.get());
        write_curves(out, args->output);
        note(common, "populate: " + std::to_string(in.num_curves()) + " curves x " + std::to_string(args->params.count) +
                         " fibers -> " + std::to_string(out.num_curves()) + " curves, " + std::to_string(out.num_points()) +
                         " points -> " + args->output);
    };
}

const Registrar reg({"populate", "Fill a disc around each curve with hair fibers", 220, setup});

}  // namespace
}  // namespace groom::cli
