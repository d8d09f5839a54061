// `groom gather`: the rest of the scalp's hair pulled into puffs (ops/gather.h): run after `groom puff`,
// give it the puffs' files, the scalp, and optionally a hairline and partings.
#include "cli/command.h"
#include "cli/curl_options.h"
#include "cli/region_options.h"
#include "cli/scalp_options.h"
#include "cli/scene_scale.h"
#include "fields/scalp_field.h"
#include "kernel/curve_set_edit.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "ops/gather.h"
#include "ops/hairline.h"

#include <chrono>
#include <cstdio>
#include <optional>

namespace groom::cli {
namespace {

struct Args {
    std::vector<std::string> puffs;
    std::string scalp, output, bands_out;
    ScalpBuildParams scalp_params;
    GatherParams params;
    RegionOptions region;
    std::string forward = "0,0,1";
    CurlOptions curl;
};

/// A puff's guides and base from a file `groom puff` wrote (the guides are its curves with kind 0).
GatherPuff read_puff(const std::string& path)
{
    const CurveSet all = read_curves(path);
    GatherPuff puff;
    const auto base = all.find<float3>(Domain::Detail, "puff_base");
    const auto radius = all.find<float>(Domain::Detail, "puff_radius");
    const auto sc = all.find<float3>(Domain::Detail, "puff_sphere_center");
    const auto sr = all.find<float>(Domain::Detail, "puff_sphere_radius");
    if (base.empty() || radius.empty() || sc.empty() || sr.empty()) {
        throw InvalidParam(path + ": expected a puff written by `groom puff` as .usda, .ply or .obj (detail attributes puff_base, puff_radius, "
                                  "puff_sphere_center, puff_sphere_radius; .hair cannot hold them); found none (re-run groom puff with -o FILE.usda)");
    }
    puff.base = base[0];
    puff.base_radius = radius[0];
    puff.sphere_center = sc[0];
    puff.sphere_radius = sr[0];
    const auto cap = all.find<float>(Domain::Detail, "puff_cap_angle");  // absent from puffs written before it was kept
    if (!cap.empty()) puff.cap_angle = cap[0];
    const auto kind = all.find<int32_t>(Domain::Curve, "kind");
    if (kind.empty()) {
        puff.guides = all;
    }
    else {
        std::vector<char> remove(kind.size());
        for (size_t c = 0; c < kind.size(); ++c) remove[c] = kind[c] != 0;
        puff.guides = remove_curves(all, remove);
    }
    if (puff.guides.num_curves() == 0) throw InvalidParam(path + ": expected the puff's guides (curves with kind 0); found none");
    return puff;
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    GatherParams& p = args->params;
    app->add_option("puffs", args->puffs, "Puffs from `groom puff` (.usda), one file each")->required();
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh (" + mesh_formats() + ")")->required();
    app->add_option("-o,--output", args->output, "Output curves: the gathered hairs (kind 1) and the bands (kind 2)")->required();
    app->add_option("--bands-out", args->bands_out, "Write the bands to this file instead of with the hairs");
    add_region_options(app, args->region);
    app->add_option("--forward", args->forward, "X,Y,Z: the direction the face looks (for the default hairline, without --hairline)")
        ->capture_default_str();
    app->add_option("--hairs", p.hairs, "Gathered hairs over the haired scalp outside the puffs' bases, >= 1")->capture_default_str();
    app->add_option("--lift", p.lift, "Greatest height of the gathered hair above the scalp, scene units, > 0")->capture_default_str();
    app->add_option("--step", p.step, "Spacing of a hair's points along the scalp, scene units, > 0")->capture_default_str();
    app->add_option("--hair-points", p.hair_points, "Points of a hair's part inside the puff before curling, >= 4")->capture_default_str();
    app->add_option("--neighbours", p.neighbours, "Puff guides blended for that part, >= 1")->capture_default_str();
    app->add_option("--power", p.power, "Inverse-distance weight exponent of that blend, > 0")->capture_default_str();
    app->add_option("--band-width", p.band_width, "Height of each puff's band (hair tie) at its base, scene units, > 0")->capture_default_str();
    app->add_option("--band-strands", p.band_strands, "Curves per band, [0, 256]; 0 = no band")->capture_default_str();
    app->add_option("--band-thickness", p.band_thickness, "Width of each band curve, scene units, > 0")->capture_default_str();
    app->add_option("--first-id", p.first_id, "Curve ids start here (hairs, then bands), >= 0")->capture_default_str();
    add_scalp_build_options(app, args->scalp_params);
    add_curl_options(app, args->curl);
    if (CLI::Option* units = app->get_option("--units-per-cm")) {
        units->description("Scene units per centimetre, for every centimetre default: the curl's radius, the widths, --lift, --step, "
                           "--band-width, --band-thickness and --parting-gap (a value typed is scene units)");
    }
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common, app] {
        std::vector<std::string> inputs = args->puffs;
        inputs.push_back(args->scalp);
        for (const std::string& f : args->region.inputs()) inputs.push_back(f);
        for (const std::string& out : {args->output, args->bands_out}) {
            if (out.empty()) continue;
            for (const std::string& in : inputs) {
                if (!in.empty() && in == out && !common.force) throw InvalidParam("gather: output " + out + " is also an input (use --force to overwrite it)");
            }
        }
        check_outputs({{"-o", args->output}, {"--bands-out", args->bands_out}}, {args->scalp}, common);
        GatherParams params = args->params;
        params.curl = curl_params_from(args->curl, "gather");
        // --units-per-cm scales every centimetre default, as edges does, not only the curl's radius
        // and the widths (a trial on a scan at 5.7 cm a unit got bands 4.6 cm thick, cone-shaped);
        // a length the user typed is taken as given.
        const float u = params.curl.units_per_cm;
        RegionOptions region_options = args->region;  // a copy: a command run once per frame scales it once
        scale_default_lengths(*app, u,
                              {{"--lift", &params.lift}, {"--step", &params.step}, {"--band-width", &params.band_width},
                               {"--band-thickness", &params.band_thickness}, {"--parting-gap", &region_options.params.parting_gap}});
        params.validate();

        const auto start = std::chrono::steady_clock::now();
        std::vector<GatherPuff> puffs;
        for (const std::string& f : args->puffs) puffs.push_back(read_puff(f));
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        warn_scene_scale(common, "gather", scalp->bounds(), u, "the defaults (the curl's radius, the widths, --lift, --step, the band)");
        // Without --hairline, the head's default one (as edges and sections take it): the whole
        // scalp laid hair over Sintel's face, neck and chest into the puff without a word (a trial,
        // on the command line and from Blender, whose panel says "none: groom's default hairline").
        std::optional<CurveSet> default_hairline;
        if (region_options.hairline.empty()) {
            HairlineParams hp;
            hp.up = parse_float3("--up", region_options.up);
            hp.forward = parse_float3("--forward", args->forward);
            if (!(length(cross(hp.up, hp.forward)) > 1e-3f * length(hp.up) * length(hp.forward))) {
                // A Z-up scene with the default forward (+Z): said as gather's, not as the hairline's.
                throw InvalidParam("gather: without --hairline, hair grows inside the head's default hairline, which needs --forward (the " +
                                   std::string("direction the face looks) not parallel to --up; got --up ") + region_options.up + " and --forward " +
                                   args->forward + ": pass --forward, or --hairline");
            }
            try {
                default_hairline = reported_hairline("gather", *scalp, scalp->bounds(), hp, common);
                note(common, "gather: no --hairline: hair grows inside the head's default hairline (`groom hairline`); pass --hairline to draw your own");
            }
            catch (const InvalidGeometry& e) {
                warn(common, "gather: warning: no --hairline, and no default hairline could be made (" + std::string(e.what()) +
                                 "): hair grows over the whole scalp, face included; pass --hairline");
            }
        }
        std::unique_ptr<HairRegion> region = make_region(region_options, *scalp, default_hairline ? &*default_hairline : nullptr);
        if (!region) region = std::make_unique<HairRegion>(*scalp, CurveSet(), CurveSet(), HairRegionParams{});  // the whole scalp
        const GatherResult r = gather(*scalp, scalp_root_sampler(*scalp), puffs, *region, params, progress.get());
        if (args->bands_out.empty()) {
            write_curves(r.bands.num_curves() ? join(r.hairs, r.bands) : r.hairs, args->output);
        }
        else {
            OutputBatch outputs;  // both files land together, or neither
            write_curves(r.hairs, args->output, outputs);
            write_curves(r.bands, args->bands_out, outputs);
            outputs.commit();
        }
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "gather: %zu hairs (%zu points) into %zu puffs, %zu band curves, %.2f s -> ", r.hairs.num_curves(),
                      r.hairs.num_points(), puffs.size(), r.bands.num_curves(), secs);
        if (r.roots_without_puff > 0) {
            note(common, "gather: " + std::to_string(r.roots_without_puff) + " roots lay in sections with no puff and grew no hair " +
                             "(a puff serves the section its base's centre lies in: a base on a parting serves one side of it; move the puff " +
                             "or the parting to give each section its puff)");
        }
        note(common, line + args->output + (args->bands_out.empty() ? "" : " + " + args->bands_out));
    };
}

const Registrar reg({"gather", "Pull the rest of the scalp's hair into puffs: flat on the scalp to each puff's band, then up into it", 420, setup});

}  // namespace
}  // namespace groom::cli
