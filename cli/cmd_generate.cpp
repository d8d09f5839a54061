// `groom generate`: a full groom from a few guides (ops/generate.h): roots scattered area-uniformly
// on the scalp, shapes interpolated from the nearest guides.
#include "cli/command.h"
#include "cli/frame_options.h"
#include "cli/region_options.h"
#include "cli/scalp_options.h"
#include "cli/scene_scale.h"
#include "cli/width_options.h"
#include "fields/scalp_field.h"
#include "kernel/curve_blocks.h"
#include "kernel/io/curve_io.h"
#include "ops/generate.h"

#include <chrono>
#include <cstdio>

namespace groom::cli {

namespace {

struct Args {
    std::string input, scalp, output, region;
    ScalpBuildParams scalp_params;
    GenerateParams params;
    RegionOptions hair_region;
    WidthOptions widths;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    GenerateParams& p = args->params;
    app->add_option("GUIDES", args->input, "Guide curves, root to tip (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh (" + mesh_formats() + ")")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--count", p.count, "Curves to generate, >= 1")->required();
    app->add_option("--region", args->region,
                    "X,Y,Z,R: root only inside this ball (scene units); default: the guides' footprint");
    app->add_option("--footprint-scale", p.footprint_scale,
                    "Without --region: roots lie within this many times the coarsest guide spacing of a guide root, > 0")
        ->capture_default_str();
    app->add_option("--max-angle", p.max_angle,
                    "Skip roots whose scalp normal is more than this many degrees from their nearest guide's, (0, 180]")
        ->capture_default_str();
    app->add_option("--neighbours", p.neighbours, "Guides blended per curve, >= 1")->capture_default_str();
    app->add_option("--power", p.power, "Inverse-distance weight exponent, > 0")->capture_default_str();
    app->add_option("--points", p.points, "Points per curve, >= 2 (default: the guides' own count)");
    app->add_option("--clearance", p.clearance, "Points inside the scalp are pushed out to this distance, scene units, >= 0")
        ->capture_default_str();
    app->add_option("--first-id", p.first_id, "Curve ids start here, >= 0")->capture_default_str();
    app->add_option("--seed", p.seed, "Random seed for the roots")->capture_default_str();
    add_scalp_build_options(app, args->scalp_params);
    add_region_options(app, args->hair_region);
    add_width_options(app, args->widths, "the guides' widths, else the defaults x --units-per-cm");
    app->add_option("--units-per-cm", p.units_per_cm, "Scene units per centimetre, for the default widths (0.01 for metres)")
        ->capture_default_str();
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {args->input, args->scalp, args->hair_region.hairline, args->hair_region.parting}, common);
        if (!args->region.empty()) {
            const std::vector<float> v = parse_floats("--region", args->region, 4, 4);
            args->params.region_center = {v[0], v[1], v[2]};
            args->params.region_radius = v[3];
            if (!(v[3] > 0.0f)) throw InvalidParam("generate: --region radius must be > 0 (got " + std::to_string(v[3]) + ")");
        }
        args->params.widths = hair_widths_from(args->widths, "generate");
        args->params.validate();
        const auto start = std::chrono::steady_clock::now();
        const CurveSet guides = read_curve_input(args->input, common);
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        const std::unique_ptr<HairRegion> region = make_region(args->hair_region, *scalp);
        // The default widths are used when neither end is given and the guides carry none.
        if (!args->params.widths.given() && guides.find<float>(Domain::Point, attr::width).empty()) {
            warn_scene_scale(common, "generate", scalp->bounds(), args->params.units_per_cm, "the default widths");
        }
        GenerateParams params = args->params;
        params.region = region.get();
        // A farm shard grows only its part of the roots (they are all scattered: that is cheap).
        ShardRequest& shard = current_shard();
        if (shard.shards > 1) {
            params.range_begin = shard.shard * params.count / shard.shards;
            params.range_end = (shard.shard + 1) * params.count / shard.shards;
            shard.claimed = true;
        }
        size_t curves = 0, points = 0;
        if (writes_curve_blocks(args->output)) {
            // Written as it is grown: the output is never whole in memory (kernel/curve_blocks.h).
            const CurveBlockCounts n = write_curve_blocks(args->output, [&](const CurveBlockStart& start, const CurveBlockEmit& emit) {
                generate_blocks(guides, *scalp, scalp_root_sampler(*scalp), params, progress.get(), kCurveBlockPoints, start, emit);
            });
            curves = n.curves, points = n.points;
        }
        else {
            const CurveSet out = generate(guides, *scalp, scalp_root_sampler(*scalp), params, progress.get());
            write_curves(out, args->output);
            curves = out.num_curves(), points = out.num_points();
        }
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "generate: %zu curves from %zu guides, %zu points, %.2f s -> ", curves, guides.num_curves(), points,
                      secs);
        note(common, line + args->output);
    };
}

const Registrar reg({"generate", "Grow a full groom from guides: area-uniform roots, shapes from the nearest guides", 400, setup});

}  // namespace
}  // namespace groom::cli
