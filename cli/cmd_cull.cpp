// `groom cull`: keep curves out of the head (ops/cull.h).
#include "cli/command.h"
#include "cli/scalp_options.h"
#include "fields/scalp_field.h"
#include "kernel/io/curve_io.h"
#include "ops/cull.h"

namespace groom::cli {
namespace {

struct Args {
    ScalpBuildParams scalp_params;
    std::string input, scalp, output, mode = "push";
    CullParams params;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("--scalp", args->scalp, "Scalp: .vdb from `groom scalp`, or a mesh")->required();
    add_scalp_build_options(app, args->scalp_params);
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--mode", args->mode, "push: move offending points out along the normal; trim: cut each curve at its first entry; delete: drop the curve")
        ->check(CLI::IsMember({"push", "trim", "delete"}))
        ->capture_default_str();
    app->add_option("--clearance", args->params.clearance, "Minimum distance outside the surface, scene units (>= 0)")->capture_default_str();
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        Args& a = *args;
        check_output(a.output, {a.input, a.scalp}, common);
        a.params.mode = a.mode == "trim" ? CullMode::Trim : (a.mode == "delete" ? CullMode::Delete : CullMode::Push);
        a.params.validate();
        const CurveSet curves = read_curve_input(a.input, common);
        auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(a.scalp, a.scalp_params, progress.get());
        CullStats stats;
        const CurveSet out = cull(curves, *scalp, a.params, &stats);
        write_curves(out, a.output);
        std::string msg = "cull (" + a.mode + "): " + std::to_string(stats.curves_affected) + " of " + std::to_string(curves.num_curves()) +
                          " curves affected";
        if (a.params.mode == CullMode::Push) msg += ", " + std::to_string(stats.points_pushed) + " points pushed out";
        if (stats.curves_trimmed) msg += ", " + std::to_string(stats.curves_trimmed) + " trimmed";
        if (stats.curves_deleted) msg += ", " + std::to_string(stats.curves_deleted) + " deleted";
        if (stats.points_removed) msg += ", " + std::to_string(stats.points_removed) + " points removed";
        note(common, msg + " -> " + a.output);
    };
}

const Registrar reg({"cull", "Push out, trim or delete curves that enter the head", 130, setup});

}  // namespace
}  // namespace groom::cli
