// `groom puff`: Izzy's afro puffs (talk, Sec. 3.2): rows x cols guides from a region of the scalp to a
// perfect sphere, and curls rooted at random in the region that follow them (ops/puff.h).
#include "cli/command.h"
#include "cli/curl_options.h"
#include "cli/scalp_options.h"
#include "cli/scene_scale.h"
#include "fields/scalp_field.h"
#include "kernel/curve_set_edit.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "ops/puff.h"

#include <chrono>
#include <cstdio>

namespace groom::cli {

namespace {

struct Args {
    std::string scalp, output, guides_out, center, sphere_center;
    ScalpBuildParams scalp_params;
    PuffParams params;
    CurlOptions curl;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    PuffParams& p = args->params;
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh (" + mesh_formats() + ")")->required();
    app->add_option("-o,--output", args->output, "Output curves: guides and hairs (only hairs with --guides-out)")->required();
    app->add_option("--guides-out", args->guides_out, "Write the guides to this file instead of with the hairs");
    app->add_option("--center", args->center, "X,Y,Z: the region's centre, projected onto the scalp")->required();
    app->add_option("--radius", p.radius, "Region radius around the projected centre, scene units, > 0")->required();
    app->add_option("--sphere-center", args->sphere_center, "X,Y,Z: centre of the puff's sphere")->required();
    app->add_option("--sphere-radius", p.sphere_radius, "Radius of the puff's sphere, scene units, > 0")->required();
    app->add_option("--rows", p.rows, "Guide rows, 1..256")->capture_default_str();
    app->add_option("--cols", p.cols, "Guide columns, 1..256")->capture_default_str();
    app->add_option("--cap-angle", p.cap_angle, "Half-angle of the sphere cap the guide tips cover, degrees, (0, 180)")->capture_default_str();
    app->add_option("--guide-points", p.guide_points, "Points per guide, [4, 4096]")->capture_default_str();
    app->add_option("--bend", p.bend, "Guide end-tangent length as a fraction of root-to-tip distance, (0, 1]")->capture_default_str();
    app->add_option("--hairs", p.hairs, "Curled hairs to grow in the region, >= 0")->capture_default_str();
    app->add_option("--hair-points", p.hair_points, "Points per hair centreline before curling, >= 4")->capture_default_str();
    app->add_option("--neighbours", p.neighbours, "Guides blended per hair, >= 1")->capture_default_str();
    app->add_option("--power", p.power, "Inverse-distance weight exponent of that blend, > 0")->capture_default_str();
    app->add_option("--first-id", p.first_id, "Curve ids start here (guides first, then hairs), >= 0")->capture_default_str();
    add_scalp_build_options(app, args->scalp_params);
    add_curl_options(app, args->curl);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_outputs({{"-o", args->output}, {"--guides-out", args->guides_out}}, {args->scalp}, common);
        PuffParams params = args->params;
        params.center = parse_float3("--center", args->center);
        params.sphere_center = parse_float3("--sphere-center", args->sphere_center);
        params.curl = curl_params_from(args->curl, "puff");
        params.validate();
        if (!args->guides_out.empty() && params.hairs == 0) {
            throw InvalidParam("puff: --guides-out needs --hairs > 0 (with no hairs, -o holds the guides)");
        }
        const auto start = std::chrono::steady_clock::now();
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        // As generate, curl and sections warn (a trial's puff on the Lee Perry-Smith scan, in other
        // units, said nothing; its curls stood 0.32 off the sphere against 0.056 at the right units).
        if (params.hairs > 0) warn_scene_scale(common, "puff", scalp->bounds(), params.curl.units_per_cm, "the curl's default radius and the widths");
        const PuffResult r = puff(*scalp, scalp_root_sampler(*scalp), params, progress.get());
        // Everything is computed before anything is written.
        if (args->guides_out.empty()) {
            write_curves(params.hairs > 0 ? join(r.guides, r.hairs) : r.guides, args->output);
        }
        else {
            OutputBatch outputs;  // both files land together, or neither
            write_curves(r.hairs, args->output, outputs);
            write_curves(r.guides, args->guides_out, outputs);
            outputs.commit();
        }
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        if (params.hairs > 0) {
            // The silhouette's guarantee: every hair tip lies within the curl reach of the sphere.
            std::snprintf(line, sizeof line, "puff: %zu guides, %zu hairs (%zu points), tips within %.3g of the sphere, %.2f s -> ",
                          r.guides.num_curves(), r.hairs.num_curves(), r.hairs.num_points(), double(curl_reach(params.curl)), secs);
        }
        else {
            std::snprintf(line, sizeof line, "puff: %zu guides, %.2f s -> ", r.guides.num_curves(), secs);
        }
        note(common, line + args->output + (args->guides_out.empty() ? "" : " + " + args->guides_out));
    };
}

const Registrar reg({"puff", "Afro puff: guides ending on a sphere, filled with curls that follow them (talk 3.2)", 410, setup});

}  // namespace
}  // namespace groom::cli
