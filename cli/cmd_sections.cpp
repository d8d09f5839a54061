// `groom sections`: the haired scalp parted into sections (ops/sections.h), one guide per section for
// `groom braid` / `groom curl`, the partings, and optionally every root joined to its section's guide.
// Without --hairline the default hairline of `groom hairline` is used.
#include "cli/command.h"
#include "cli/region_options.h"
#include "cli/scalp_options.h"
#include "cli/scene_scale.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "ops/hairline.h"
#include "ops/sections.h"

#include <chrono>
#include <cstdio>

namespace groom::cli {
namespace {

struct Args {
    std::string scalp, output, partings_out, roots_out, hairline, layout = "grid", guide = "auto";
    std::string up = "0,1,0", forward = "0,0,1", crown, hang = "0,0,0";
    ScalpBuildParams scalp_params;
    SectionsParams params;
    float units_per_cm = 1.0f;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    SectionsParams& p = args->params;
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh (" + mesh_formats() + ")")->required();
    app->add_option("-o,--output", args->output, "Output guides, one per section (" + curve_formats() + ")")->required();
    app->add_option("--partings-out", args->partings_out, "Write the parting curves (on the scalp, between sections) to this file");
    app->add_option("--roots-out", args->roots_out, "Write every root of each section, joined to its guide, to this file");
    app->add_option("--hairline", args->hairline, "Hairline: one closed curve around the head (`groom hairline`); default: groom hairline's");
    app->add_option("--layout", args->layout, "grid (box braids, twists, bantu knots), rows (fulani: front to back, centre row) or radial (wedges around the crown)")
        ->capture_default_str();
    app->add_option("--cols", p.cols, "grid: bands across the head, [1, 256]; default 8 (or from --size)");
    app->add_option("--rows", p.rows, "grid: cells along the middle band front to back (default: square cells); rows: rows across the head (default 7)");
    app->add_option("--rings", p.rings, "radial: rings from the crown to the hairline, [1, 64]; default 1");
    app->add_option("--wedges", p.wedges, "radial: wedges in the outermost ring, [1, 256]; default 12");
    app->add_option("--size", p.size, "Side of a section, scene units: sets the counts not given; 0 = unset")->capture_default_str();
    app->add_option("--crown", args->crown, "radial: X,Y,Z, the point the wedges turn around (default: straight up from the hairline's centroid)");
    app->add_option("--parting-gap", p.parting_gap, "Bare width along each parting, scene units, > 0")->capture_default_str();
    app->add_option("--step", p.step, "Spacing of the partings' points, scene units, > 0")->capture_default_str();
    app->add_option("--guide", args->guide, "auto, hang (from the section's middle, then down) or along (front to back on the scalp, then down)")
        ->capture_default_str();
    app->add_option("--length", p.length, "Length of a guide's free part, scene units, > 0")->capture_default_str();
    app->add_option("--points", p.points, "Points over that length, [4, 100000]")->capture_default_str();
    app->add_option("--bend", p.bend, "Arc length over which a guide turns 90 degrees, scene units, > 0")->capture_default_str();
    app->add_option("--hang", args->hang, "X,Y,Z: the direction free guides fall; 0,0,0 = down (-up)")->capture_default_str();
    app->add_option("--sweep", p.sweep, "How strongly guides on the scalp are combed away from the face, >= 0")->capture_default_str();
    app->add_option("--clearance", p.clearance, "Least distance of a guide from the scalp, scene units, >= 0")->capture_default_str();
    app->add_option("--layer", p.layer, "Extra height per section between a root and the hairline, scene units, >= 0")->capture_default_str();
    app->add_option("--jitter", p.jitter, "Random tilt of each guide's fall, degrees, [0, 45]")->capture_default_str();
    app->add_option("--roots", p.roots, "Roots over the haired sections (with --roots-out), >= 1; default 20000");
    app->add_option("--root-points", p.root_points, "Points of each root's curve to its guide, [2, 64]")->capture_default_str();
    app->add_option("--first-id", p.first_id, "Guide ids start here (root ids follow), >= 0")->capture_default_str();
    app->add_option("--seed", p.seed, "Seeds the guides' jitter and the roots")->capture_default_str();
    app->add_option("--up", args->up, "X,Y,Z: the head's up direction")->capture_default_str();
    app->add_option("--forward", args->forward, "X,Y,Z: the direction the face looks")->capture_default_str();
    app->add_option("--units-per-cm", args->units_per_cm,
                    "Scene units per centimetre: scales every default length (--parting-gap, --step, --length, --bend, --clearance, "
                    "--layer), which are centimetres; lengths typed are scene units")
        ->capture_default_str();
    add_scalp_build_options(app, args->scalp_params);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, app, &common] {
        check_outputs({{"-o", args->output}, {"--partings-out", args->partings_out}, {"--roots-out", args->roots_out}},
                      {args->scalp, args->hairline}, common);
        SectionsParams params = args->params;  // a copy: a command run once per frame scales it once
        const float u = args->units_per_cm;
        check_units_per_cm("sections", u);
        scale_default_lengths(*app, u,
                              {{"--parting-gap", &params.parting_gap}, {"--step", &params.step}, {"--length", &params.length},
                               {"--bend", &params.bend}, {"--clearance", &params.clearance}, {"--layer", &params.layer}});
        params.layout = parse_section_layout(args->layout);
        params.guide = parse_section_guide(args->guide);
        params.up = parse_float3("--up", args->up);
        params.forward = parse_float3("--forward", args->forward);
        params.hang = parse_float3("--hang", args->hang);
        if (!args->crown.empty()) {
            params.crown = parse_float3("--crown", args->crown);
            params.has_crown = true;
        }
        if (params.roots != 0 && args->roots_out.empty()) throw InvalidParam("sections: --roots needs --roots-out FILE to write them to");
        if (!args->roots_out.empty() && params.roots == 0) params.roots = 20000;
        params.validate();

        const auto start = std::chrono::steady_clock::now();
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        warn_scene_scale(common, "sections", scalp->bounds(), u, "the default lengths (parting gap, guide length, clearance)");
        CurveSet hairline;
        if (args->hairline.empty()) {
            HairlineParams hp;
            hp.up = params.up;
            hp.forward = params.forward;
            hairline = reported_hairline("sections", *scalp, scalp->bounds(), hp, common);
        }
        else {
            hairline = read_hairline(args->hairline, &common);
            warn_if_hairline_faces_away("sections", args->hairline, hairline, params.up, params.forward, common);
        }
        const RootSampler sampler = scalp_root_sampler(*scalp);
        const SectionsResult r = [&] {
            try {
                return sections(*scalp, hairline, &sampler, params, progress.get());
            }
            catch (const InvalidGeometry& e) {
                // What is wrong with the hairline is said of "hairline"; the user typed a file.
                const std::string what = e.what();
                if (args->hairline.empty() || (what.rfind("hairline", 0) != 0 && what.rfind("sections: the hairline", 0) != 0)) throw;
                throw InvalidGeometry(args->hairline + ": " + what);
            }
        }();
        OutputBatch outputs;  // every file lands together, or none
        write_curves(r.guides, args->output, outputs);
        if (!args->partings_out.empty()) write_curves(r.partings, args->partings_out, outputs);
        if (!args->roots_out.empty()) write_curves(r.roots, args->roots_out, outputs);
        outputs.commit();
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[320];
        std::snprintf(line, sizeof line,
                      "sections: %zu sections in %d bands (%s), areas %.3g to %.3g (haired area %.4g), %zu parting curves, %zu roots, %.2f s -> ",
                      r.sections.size(), r.report.bands, args->layout.c_str(), r.report.min_area, r.report.max_area, r.report.haired_area,
                      r.partings.num_curves(), r.roots.num_curves(), secs);
        std::string files = args->output;
        if (!args->partings_out.empty()) files += " + " + args->partings_out;
        if (!args->roots_out.empty()) files += " + " + args->roots_out;
        note(common, line + files);
        for (int b = 0; b < r.report.bands; ++b) {
            std::string cells;
            for (const SectionInfo& info : r.sections) {
                if (info.band != b) continue;
                char a[32];
                std::snprintf(a, sizeof a, "%s%.3g", cells.empty() ? "" : " ", info.area);
                cells += a;
            }
            detail(common, "sections: band " + std::to_string(b) + ": areas " + cells);
        }
        detail(common, "sections: " + std::to_string(r.report.rays) + " rays charted the scalp; " + std::to_string(r.report.roots_bare) +
                           " sampled roots fell on partings");
    };
}

const Registrar reg({"sections", "Part the scalp into sections (grid, rows, radial) with one guide each, for box braids, twists, knots", 430, setup});

}  // namespace
}  // namespace groom::cli
