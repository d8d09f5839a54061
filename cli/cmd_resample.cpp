// `groom resample`: re-space curve points evenly in arc length (ops/resample.h).
#include "cli/command.h"
#include "kernel/io/curve_io.h"
#include "ops/resample.h"

namespace groom::cli {
namespace {

struct Args {
    std::string input, output;
    ResampleParams params;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--count", args->params.count, "Points per curve (>= 2)");
    app->add_option("--segment-length", args->params.segment_length, "Target spacing between points, scene units (> 0)");
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {args->input}, common);
        args->params.validate();
        const CurveSet out = resample(read_curve_input(args->input, common), args->params);
        write_curves(out, args->output);
        note(common, "resample: " + std::to_string(out.num_curves()) + " curves, " + std::to_string(out.num_points()) + " points -> " + args->output);
    };
}

const Registrar reg({"resample", "Re-space curve points evenly in arc length", 30, setup});

}  // namespace
}  // namespace groom::cli
