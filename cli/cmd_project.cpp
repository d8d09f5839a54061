// `groom project`: move curves onto the scalp (ops/project.h).
#include "cli/command.h"
#include "cli/scalp_options.h"
#include "fields/scalp_field.h"
#include "kernel/io/curve_io.h"
#include "ops/project.h"

#include <cstdio>

namespace groom::cli {
namespace {

struct Args {
    ScalpBuildParams scalp_params;
    std::string input, scalp, output, mode = "root";
    ProjectParams params;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("--scalp", args->scalp, "Scalp: .vdb from `groom scalp`, or a mesh")->required();
    add_scalp_build_options(app, args->scalp_params);
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--mode", args->mode, "root: move each curve rigidly so its root is on the surface; all: every point onto the surface")
        ->check(CLI::IsMember({"root", "all"}))
        ->capture_default_str();
    app->add_option("--offset", args->params.offset, "Distance above the surface along its normal, scene units")->capture_default_str();
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        Args& a = *args;
        check_output(a.output, {a.input, a.scalp}, common);
        a.params.mode = a.mode == "all" ? ProjectMode::All : ProjectMode::Root;
        a.params.validate();
        const CurveSet curves = read_curve_input(a.input, common);
        auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(a.scalp, a.scalp_params, progress.get());
        ProjectStats stats;
        const CurveSet out = project(curves, *scalp, a.params, &stats);
        write_curves(out, a.output);
        char buf[256];
        std::snprintf(buf, sizeof buf, "project (%s): %lld curves, %lld points moved (at most %.4g) -> %s", a.mode.c_str(),
                      static_cast<long long>(stats.curves), static_cast<long long>(stats.points_moved), stats.max_move, a.output.c_str());
        note(common, buf);
        // Curves in other units than the scalp (a trial's guides in cm on a body in metres moved by
        // up to 91 onto a body 0.9 across, without a word): a move larger than half the scalp is
        // no projection.
        const Bounds3 box = scalp->bounds();
        const float size = box.empty() ? 0.0f : length(box.size());
        if (size > 0.0f && stats.max_move > 0.5 * double(size)) {
            warn(common, "project: warning: curves moved by up to " + format_number(float(stats.max_move)) + ", more than half the scalp's size (" +
                             format_number(size) + " across): are the curves and the scalp in the same units and place? (groom transform --units, --translate)");
        }
    };
}

const Registrar reg({"project", "Move curve roots (or whole curves) onto the scalp", 120, setup});

}  // namespace
}  // namespace groom::cli
