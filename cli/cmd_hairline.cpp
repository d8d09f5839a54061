// `groom hairline`: a default hairline on a scalp (ops/hairline.h), as a closed curve that --hairline
// options of other commands read. Artists may draw their own in a DCC instead: any curve going once
// around the head is accepted.
#include "cli/command.h"
#include "cli/region_options.h"
#include "cli/scalp_options.h"
#include "fields/scalp_field.h"
#include "kernel/io/curve_io.h"
#include "ops/hairline.h"

#include <chrono>
#include <cstdio>

namespace groom::cli {
namespace {

struct Args {
    std::string scalp, output, up = "0,1,0", forward = "0,0,1", center;
    ScalpBuildParams scalp_params;
    HairlineParams params;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    HairlineParams& p = args->params;
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh (" + mesh_formats() + ")")->required();
    app->add_option("-o,--output", args->output, "Output curve file: one closed curve (" + curve_formats() + ")")->required();
    app->add_option("--up", args->up, "X,Y,Z: the head's up direction")->capture_default_str();
    app->add_option("--forward", args->forward, "X,Y,Z: the direction the face looks")->capture_default_str();
    app->add_option("--center", args->center, "X,Y,Z: a point inside the head below its crown (default: the middle of the scalp's bounds)");
    app->add_option("--head-length", p.head_length, "Front-to-back length of the head, scene units; 0 = measured")->capture_default_str();
    app->add_option("--forehead", p.forehead, "Hairline height below the top of the head at the forehead, in head lengths")->capture_default_str();
    app->add_option("--temple", p.temple, "... at the temples (55 degrees from the front)")->capture_default_str();
    app->add_option("--sideburn", p.sideburn, "... at the sideburns (80 degrees)")->capture_default_str();
    app->add_option("--ear", p.ear, "... over the ears (105 degrees)")->capture_default_str();
    app->add_option("--nape", p.nape, "... at the nape (180 degrees)")->capture_default_str();
    app->add_option("--points", p.points, "Points on the curve, [16, 100000]")->capture_default_str();
    add_scalp_build_options(app, args->scalp_params);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {args->scalp}, common);
        HairlineParams params = args->params;
        params.up = parse_float3("--up", args->up);
        params.forward = parse_float3("--forward", args->forward);
        if (!args->center.empty()) {
            params.center = parse_float3("--center", args->center);
            params.has_center = true;
        }
        params.validate();
        const auto start = std::chrono::steady_clock::now();
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        const CurveSet hairline = reported_hairline("hairline", *scalp, scalp->bounds(), params, common);
        // Written closed (.usda wrap "periodic", .obj's record back to its first vertex): written
        // open, a DCC showed the hairline with a gap between its last point and its first.
        CurveWriteOptions closed;
        closed.closed = true;
        write_curves(hairline, args->output, closed);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "hairline: 1 closed curve, %zu points, %.2f s -> ", hairline.num_points(), secs);
        note(common, line + args->output);
    };
}

const Registrar reg({"hairline", "A default hairline around a head (forehead, temples, sideburns, over the ears, nape)", 140, setup});

}  // namespace
}  // namespace groom::cli
