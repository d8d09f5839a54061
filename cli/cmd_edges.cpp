// `groom edges`: baby hairs laid flat in swirls along the hairline (ops/edges.h). With no --hairline
// the default hairline (`groom hairline` with its defaults and this command's --up/--forward) is used,
// so `groom edges --scalp head.vdb -o edges.usda` works on `groom head`'s head alone.
#include "cli/command.h"
#include "cli/region_options.h"
#include "cli/scalp_options.h"
#include "cli/scene_scale.h"
#include "cli/width_options.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "ops/edges.h"
#include "ops/hairline.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

namespace groom::cli {
namespace {

struct Args {
    std::string scalp, output, hairline, parting, up = "0,1,0", forward = "0,0,1", direction = "face";
    ScalpBuildParams scalp_params;
    EdgesParams params;
    HairRegionParams region;
    float units_per_cm = 1.0f;
    float width = 0.0f;
    WidthOptions widths;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    EdgesParams& p = args->params;
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh (" + mesh_formats() + ")")->required();
    app->add_option("-o,--output", args->output, "Output curves: the edge hairs (" + curve_formats() + ")")->required();
    app->add_option("--hairline", args->hairline, "Hairline: one closed curve around the head (`groom hairline`); default: `groom hairline`'s, computed");
    app->add_option("--parting", args->parting, "Partings (`groom parting`): no root on their bare gap, no hair across them");
    app->add_option("--parting-gap", args->region.parting_gap, "Bare width along each parting, scene units, >= 0")->capture_default_str();
    app->add_option("--up", args->up, "X,Y,Z: the head's up direction")->capture_default_str();
    app->add_option("--forward", args->forward, "X,Y,Z: the direction the face looks (azimuth 0)")->capture_default_str();
    app->add_option("--from", p.from, "Edges along the hairline from this azimuth, degrees around --up from --forward, + toward the head's left")
        ->capture_default_str();
    app->add_option("--to", p.to, "... to this azimuth (> --from, at most 360 past it); forehead 0, temples +-55, sideburns +-80, nape 180")
        ->capture_default_str();
    app->add_option("--depth", p.depth, "Roots in a band this deep inside the hairline, scene units, >= 0 (0: on it)")->capture_default_str();
    app->add_option("--density", p.density, "Hairs per scene unit of hairline, > 0")->capture_default_str();
    app->add_option("--count", p.count, "Exact number of hairs (0: from --density)")->capture_default_str();
    app->add_option("--length", p.length, "Arc length of a hair, scene units, > 0")->capture_default_str();
    app->add_option("--radius", p.radius, "Swirl radius: the tightest radius of curvature of a hair, scene units, > 0")->capture_default_str();
    app->add_option("--bends", p.bends, "Arcs per hair bending alternately: 1 a C, 2 an S, 3+ a wave; [1, 16]")->capture_default_str();
    app->add_option("--direction", args->direction,
                    "face (out of the hairline), along (along it, toward the ears), alternate (swoops leaning left, right, ...), random")
        ->capture_default_str();
    app->add_option("--swoop", p.swoop, "Hairline length a group of hairs laid together shares, scene units, > 0")->capture_default_str();
    app->add_option("--variation", p.variation, "Per-hair random variation of length, radius and heading, [0, 0.9]")->capture_default_str();
    app->add_option("--height", p.height, "Height of the hairs above the skin (each in [h/2, h]), scene units, >= 0")->capture_default_str();
    add_width_options(app, args->widths, "the defaults x --units-per-cm");
    app->add_option("--width", args->width, "One hair diameter root to tip (--root-width W --tip-width W), scene units, > 0")
        ->excludes(args->widths.root_opt)
        ->excludes(args->widths.tip_opt);
    app->add_option("--points", p.points, "Points per hair, [4, 4096]")->capture_default_str();
    app->add_option("--seed", p.seed, "Seed for every random choice")->capture_default_str();
    app->add_option("--first-id", p.first_id, "Curve ids start here, >= 0")->capture_default_str();
    app->add_option("--kind", p.kind, "Curve `kind` written on every hair, >= 0")->capture_default_str();
    app->add_option("--units-per-cm", args->units_per_cm,
                    "Scene units per centimetre (> 0): the defaults above are centimetres, scaled by this unless given")
        ->capture_default_str();
    add_scalp_build_options(app, args->scalp_params);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common, app] {
        for (const std::string& in : {args->scalp, args->hairline, args->parting}) {
            if (!in.empty() && in == args->output && !common.force) throw InvalidParam("edges: output " + in + " is also an input (use --force to overwrite it)");
        }
        check_output(args->output, {args->scalp}, common);
        EdgesParams params = args->params;
        const float u = args->units_per_cm;
        check_units_per_cm("edges", u);
        // The defaults are a head in centimetres; a scene in other units gets them scaled, while
        // every length the user typed is taken as given (scene units).
        scale_default_lengths(*app, u,
                              {{"--depth", &params.depth}, {"--length", &params.length}, {"--radius", &params.radius},
                               {"--swoop", &params.swoop}, {"--height", &params.height}});
        params.widths = hair_widths_from(args->widths, "edges");
        if (app->count("--width")) {
            if (!(std::isfinite(args->width) && args->width > 0.0f)) {
                throw InvalidParam("edges: --width must be > 0 scene units (got " + format_number(args->width) + ")");
            }
            params.widths.root = params.widths.tip = args->width;
        }
        params.widths = params.widths.resolved(u);
        if (app->count("--density") == 0) params.density /= u;
        params.up = parse_float3("--up", args->up);
        params.forward = parse_float3("--forward", args->forward);
        params.direction = parse_edge_direction(args->direction);
        params.validate();
        HairRegionParams region_params = args->region;
        scale_default_lengths(*app, u, {{"--parting-gap", &region_params.parting_gap}});
        region_params.up = params.up;
        region_params.validate();

        const auto start = std::chrono::steady_clock::now();
        CurveSet hairline = args->hairline.empty() ? CurveSet() : read_hairline(args->hairline, &common);
        if (!args->hairline.empty()) warn_if_hairline_faces_away("edges", args->hairline, hairline, params.up, params.forward, common);
        const CurveSet partings = args->parting.empty() ? CurveSet() : read_curve_input(args->parting, common, false);
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        warn_scene_scale(common, "edges", scalp->bounds(), u, "the defaults (lengths, radii, widths, the hairline's)");
        if (!args->hairline.empty()) check_hairline_on_scalp(args->hairline, hairline, *scalp);
        if (args->hairline.empty()) {
            HairlineParams hp;
            hp.up = params.up;
            hp.forward = params.forward;
            hairline = reported_hairline("edges", *scalp, scalp->bounds(), hp, common);
        }
        std::optional<HairRegion> region;
        if (partings.num_curves() > 0) region.emplace(*scalp, hairline, partings, region_params);
        const CurveSet hairs = edges(*scalp, hairline, params, region ? &*region : nullptr);
        write_curves(hairs, args->output);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "edges: %zu hairs (%zu points) along the hairline from %g to %g degrees, %.2f s -> ", hairs.num_curves(),
                      hairs.num_points(), double(params.from), double(params.to), secs);
        note(common, line + args->output);
    };
}

const Registrar reg({"edges", "Baby hairs (edges) laid flat in swirls along the hairline", 430, setup});

}  // namespace
}  // namespace groom::cli
