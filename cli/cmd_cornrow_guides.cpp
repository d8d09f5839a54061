// `groom cornrow-guides`: procedural front-to-back cornrow guides over a scalp (ops/cornrow_guides.h).
#include "cli/command.h"
#include "cli/region_options.h"
#include "cli/scalp_options.h"
#include "cli/scene_scale.h"
#include "fields/scalp_field.h"
#include "kernel/io/curve_io.h"
#include "kernel/math/polyline.h"
#include "ops/cornrow_guides.h"
#include "ops/cranium.h"
#include "ops/scene_length.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace groom::cli {
namespace {

struct Args {
    ScalpBuildParams scalp_params;
    std::string scalp, output, tails_out, center, hairline, up = "0,1,0", forward = "0,0,1";
    CornrowGuidesParams params;
    bool fit_cranium = false;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh")->required();
    add_scalp_build_options(app, args->scalp_params);
    app->add_option("-o,--output", args->output, "Output guides (" + curve_formats() + ")")->required();
    auto* tails = app->add_option("--tails-out", args->tails_out, "Also write a free tail per guide past the nape here");
    CornrowGuidesParams& p = args->params;
    app->add_option("--count", p.count, "Guides (rows), [1, 256]")->capture_default_str();
    auto* center = app->add_option("--center", args->center,
                                   "Centre X,Y,Z of the sphere the rows are laid on (default: the default head's cranium, 0,3,-1; on a "
                                   "head it does not fit, with --hairline, fitted to the scalp inside it)");
    auto* radius = app->add_option("--radius", p.radius, "Radius of that sphere, scene units")->capture_default_str();
    app->add_option("--up", args->up, "X,Y,Z: the head's up direction")->capture_default_str();
    app->add_option("--forward", args->forward, "X,Y,Z: the direction the face looks (rows run from the front to the nape)")
        ->capture_default_str();
    app->add_option("--pivot", p.pivot,
                    "Depth of the rows' fan axis below the centre, scene units, >= 0 (from --radius on the rows never meet: nearly "
                    "parallel rows; pivot x sin(spread) must stay below the radius); default twice --radius (20)");
    app->add_option("--spread", p.spread, "How far the outermost rows lean from vertical, degrees, [0, 90)")->capture_default_str();
    app->add_option("--front-angle", p.front_angle, "Where the middle row starts above the front horizontal, degrees")->capture_default_str();
    app->add_option("--hairline-curve", p.hairline_curve, "How much further back the outermost rows start, degrees")->capture_default_str();
    app->add_option("--back-angle", p.back_angle, "Where rows end at the nape (negative = below the horizontal), degrees")
        ->capture_default_str();
    auto* hairline = app->add_option("--hairline", args->hairline,
                                     "Hairline: one closed curve around the head (`groom hairline`); rows then run from it at the front "
                                     "to it at the nape, in place of --front-angle, --hairline-curve and --back-angle");
    app->add_flag("--fit-cranium", args->fit_cranium,
                  "Fit --center and --radius to the scalp inside --hairline even where the default head's sphere would fit (a "
                  "head not in centimetres +Y up, or one near the default head's place by chance)")
        ->needs(hairline)
        ->excludes(center)
        ->excludes(radius);
    app->add_option("--min-spacing", p.min_spacing,
                    "With --hairline: a row ends where its neighbours come within this fraction of their spacing over the crown, "
                    "(0, 1]")
        ->capture_default_str();
    app->add_option("--samples", p.samples, "Points per guide, >= 2")->capture_default_str();
    app->add_option("--offset", p.offset, "Height of the guides above the scalp, scene units")->capture_default_str();
    app->add_option("--tail-length", p.tail_length, "Length of each tail past the nape, scene units (needs --tails-out; default 1.2 x --radius: 12)")
        ->needs(tails);
    app->add_option("--tail-samples", p.tail_samples, "Points per tail, >= 2")->capture_default_str();
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common, app] {
        Args& a = *args;
        check_outputs({{"-o", a.output}, {"--tails-out", a.tails_out}}, {a.scalp, a.hairline}, common);
        // The default pivot is twice the default radius: on another head (its own --radius) the
        // rows keep the default's shape. A fixed 7.5 was reported back to a user who had given only
        // --radius 1.8 ("pivot ... got 7.5": a trial on a scan in other units).
        if (app->count("--radius") > 0 && app->count("--pivot") == 0) a.params.pivot = 2.0f * a.params.radius;
        if (!a.center.empty()) {
            const std::vector<float> c = parse_floats("--center", a.center, 3, 3);
            a.params.center = {c[0], c[1], c[2]};
        }
        a.params.up = parse_float3("--up", a.up);
        a.params.forward = parse_float3("--forward", a.forward);
        {
            // Where the cranium may be fitted, its radius is not known yet: the checks that weigh
            // --pivot and --spread against it wait for it (they had refused --pivot 30 against the
            // default radius 10 on a head whose fitted radius was 29.1: a hostile trial).
            CornrowGuidesParams early = a.params;
            if (!a.hairline.empty() && app->count("--center") == 0 && app->count("--radius") == 0) early.radius = kMaxSceneLength;
            early.validate(!a.hairline.empty());
        }
        if (!a.tails_out.empty() && app->count("--tail-length") > 0 && !(a.params.tail_length > 0.0f)) {
            throw InvalidParam("cornrow-guides: --tail-length " + format_number(a.params.tail_length) +
                               " with --tails-out would write tails of no length (0 had given the default length): give a length > 0, or "
                               "drop --tails-out");
        }
        const auto start = std::chrono::steady_clock::now();
        auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(a.scalp, a.scalp_params, progress.get());
        // The hairline is read around the same up direction the rows are laid with.
        RegionOptions region_options;
        region_options.hairline = a.hairline;
        region_options.up = a.up;
        // Read once: checked, then made the region.
        const CurveSet hairline = a.hairline.empty() ? CurveSet() : read_hairline(a.hairline);
        if (!a.hairline.empty()) {
            check_hairline_on_scalp(a.hairline, hairline, *scalp);
            warn_if_hairline_faces_away("cornrow-guides", a.hairline, hairline, a.params.up, a.params.forward, common);
        }
        const std::unique_ptr<HairRegion> region = make_region(region_options, *scalp, a.hairline.empty() ? nullptr : &hairline);
        // The default sphere is the default head's cranium (`groom head`: centimetres, +Y up, its top
        // at y = 13). On another head it lays rows somewhere else without a word (a trial on a scan
        // in other units ran them onto the shoulders): unless the scalp lies about on that sphere,
        // the cranium is fitted to the scalp inside the hairline, or without one the command
        // refuses. The top's height alone let MakeHuman's body through (decimetres, its head's top
        // at y 8.5, 4.5 from 13 by chance: rows over the chest), so the scalp's distance is asked at
        // 17 points of the sphere's upper half too: within 0.22 R on the default head, 0.25 R on
        // ICT's face and Sintel's (cm), 0.44-0.88 R on MakeHuman's body.
        const Bounds3 box = scalp->bounds();
        if (app->count("--center") == 0 && app->count("--radius") == 0 && !box.empty()) {
            const float3 c = a.params.center;
            const float r = a.params.radius, top = c.y + r;
            std::vector<float> off{std::fabs(scalp->distance(c + float3(0, r, 0)))};
            for (int az = 0; az < 360; az += 45) {
                for (const float el : {60.0f, 35.0f}) {
                    const float e = el * 3.14159265f / 180.0f, t = float(az) * 3.14159265f / 180.0f;
                    const float3 d(std::cos(e) * std::sin(t), std::sin(e), std::cos(e) * std::cos(t));
                    off.push_back(std::fabs(scalp->distance(c + d * r)));
                }
            }
            std::nth_element(off.begin(), off.begin() + off.size() / 2, off.end());
            const float median = off[off.size() / 2];
            const bool top_off = std::fabs(box.hi.y - top) > 0.5f * r;
            if ((a.fit_cranium || top_off || median > 0.4f * r) && region != nullptr && region->has_hairline()) {
                // A user with a scan and its hairline had to measure its cranium to get any rows (a
                // trial on Lee Perry-Smith: --center 0,2.3,0 --radius 1.7 found by hand).
                // Its errors name the command and the hairline, not only "cranium" (a hostile trial).
                const Cranium fit = [&] {
                    try {
                        return fit_cranium(*scalp, *region, a.params.up);
                    }
                    catch (const InvalidGeometry& e) {
                        throw InvalidGeometry("cornrow-guides: fitting the cranium inside --hairline " + a.hairline + ": " + e.what());
                    }
                }();
                a.params.center = fit.center;
                a.params.radius = fit.radius;
                if (app->count("--pivot") == 0) a.params.pivot = 2.0f * fit.radius;
                a.params.validate(true);
                note(common, "cornrow-guides: " + (a.fit_cranium ? std::string("--fit-cranium") : "the default sphere does not fit " + a.scalp) +
                                 ": fitted the cranium to the scalp inside the hairline (" +
                                 std::to_string(fit.samples) + " points): --center " + format_xyz(fit.center) + " --radius " +
                                 format_number(fit.radius) + (app->count("--pivot") == 0 ? " --pivot " + format_number(a.params.pivot) : std::string()));
            }
            else if (top_off || median > 0.4f * r) {
                throw InvalidParam("cornrow-guides: the default --center " + format_xyz(c) + " and --radius " + format_number(r) +
                                   " are the default head's cranium (top at y " + format_number(top) + ", centimetres, +Y up), but " + a.scalp +
                                   (top_off ? " reaches y " + format_number(box.hi.y)
                                            : " lies " + format_number(median) + " from that sphere (the median over its upper half; within " +
                                                  format_number(0.4f * r) + " on a head it fits)") +
                                   " (bounds " + format_xyz(box.lo) + " to " + format_xyz(box.hi) +
                                   "): pass --center (the middle of this head's cranium) and --radius (about half its width), or a --hairline "
                                   "(`groom hairline`) to fit them to the scalp inside it");
            }
        }
        a.params.validate(!a.hairline.empty());  // with the radius the rows are laid on
        // The default tail is 1.2 radii of the rows' sphere (12 on the default head): a fixed 12
        // hung tails 6 heads long from a bust modelled in metres (a trial on Demosthenes).
        if (!a.tails_out.empty() && a.params.tail_length <= 0.0f) a.params.tail_length = 1.2f * a.params.radius;
        const CornrowGuides g = cornrow_guides(*scalp, a.params, region.get());
        OutputBatch outputs;  // both files land together, or neither
        write_curves(g.guides, a.output, outputs);
        if (!a.tails_out.empty()) write_curves(g.tails, a.tails_out, outputs);
        outputs.commit();
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "cornrow-guides: %zu guides x %d points, %.2f s -> ", g.guides.num_curves(), a.params.samples, secs);
        note(common, line + a.output + (a.tails_out.empty() ? std::string() : " (tails -> " + a.tails_out + ")"));
        // Rows whose nearest-point projection jumped across a fold of the scalp (a brow, an ear):
        // laid along rays instead, or, where that did not help, left with the jump, which cuts
        // through the head (ICT's face with the default --center: a trial).
        std::string along, jumped, trimmed;
        for (size_t c = 0; c < g.rows.size(); ++c) {
            if (g.rows[c].along_rays) along += (along.empty() ? "" : ", ") + std::to_string(c);
            if (g.rows[c].trimmed > 0.0f) trimmed += (trimmed.empty() ? "" : ", ") + std::to_string(c) + " (" + format_number(g.rows[c].trimmed) + ")";
            if (g.rows[c].jump > 0.0f) {
                jumped += (jumped.empty() ? "" : ", ") + std::to_string(c) + " (" + format_number(g.rows[c].jump) + ")";
            }
        }
        if (!trimmed.empty()) {
            // Laid on the scalp, rows can come closer than in their planes on the sphere (a trial on
            // the ponytail head: braids through each other at the nape).
            note(common, "cornrow-guides: rows " + trimmed + " were cut short by that length where, on the scalp, they came closer to the next row than " +
                             "--min-spacing " + format_number(a.params.min_spacing) + " of the rows' spacing over the crown");
        }
        // Straight-back rows whose walk never left the hairline keep their arcs: say which.
        std::string arcs;
        const bool any_walked = std::any_of(g.rows.begin(), g.rows.end(), [](const CornrowGuides::Row& r) { return r.walked; });
        for (size_t c = 0; any_walked && c < g.rows.size(); ++c) {
            if (!g.rows[c].walked) arcs += (arcs.empty() ? "" : ", ") + std::to_string(c);
        }
        if (!arcs.empty()) {
            note(common, "cornrow-guides: rows " + arcs + " were laid as arcs: walked along their planes' cut with the scalp they "
                             "never left the hairline");
        }
        if (!along.empty()) {
            note(common, "cornrow-guides: rows " + along + " jumped across a fold of the scalp when projected to its nearest point; " +
                             "they were laid on the outermost scalp along rays from their arc's centre instead");
        }
        if (!jumped.empty()) {
            // Only the ways out not taken: a trial on Lee Perry-Smith that had given --center, --radius
            // and --hairline was told to pass them.
            std::vector<std::string> ways;
            if (app->count("--center") == 0 || app->count("--radius") == 0) ways.push_back("pass this head's own --center and --radius");
            if (a.hairline.empty()) ways.push_back("a --hairline");
            ways.push_back("a smaller --spread (now " + format_number(a.params.spread) + ")");
            std::string way;
            for (size_t k = 0; k < ways.size(); ++k) way += (k == 0 ? "" : k + 1 == ways.size() ? ", or " : ", ") + ways[k];
            warn(common, "cornrow-guides: warning: rows " + jumped + " jump across a fold of the scalp in one step of that length, " +
                             "which cuts through the head (under a brow or an ear): " + way);
        }
        // A row cut to a stub by the hairline (at a sideburn, above an ear) braids into a short tuft
        // with its tail hanging by the face (a trial on Lee Perry-Smith and MakeHuman): say which.
        const double median = median_curve_length(g.guides);
        std::string stubs;
        for (size_t c = 0; c < g.guides.num_curves(); ++c) {
            const IndexRange r = g.guides.points_of(c);
            const float length = polyline_length(g.guides.positions().subspan(size_t(r.begin), size_t(r.size())));
            if (length < 0.25 * median) stubs += (stubs.empty() ? "" : ", ") + std::to_string(c) + " (" + format_number(length) + ")";
        }
        // Rows cut by much where they crowd end partway down the head, their tails hanging over the
        // rows beside them (a trial on Lee Perry-Smith: rows 6 and 7 cut by 1.37 and 1.22 while
        // their mirror rows lost 0.18 and 0, behind the ear on one side only): say so, with the way out.
        std::string short_cut;
        for (size_t c = 0; c < g.rows.size(); ++c) {
            if (g.rows[c].trimmed > 0.15 * median) {
                short_cut += (short_cut.empty() ? "" : ", ") + std::to_string(c) + " (" + format_number(g.rows[c].trimmed) + ")";
            }
        }
        if (!short_cut.empty()) {
            warn(common, "cornrow-guides: warning: rows " + short_cut + " were cut by more than 15% of the rows' median length " +
                             format_number(float(median)) + " where they crowd the next row, so they end partway down the head and " +
                             "their tails hang over the rows beside them: a smaller --spread (now " + format_number(a.params.spread) +
                             ") keeps the outer rows off the ears, or fewer rows (--count " + std::to_string(a.params.count) + ")");
        }
        if (!stubs.empty()) {
            warn(common, "cornrow-guides: warning: rows " + stubs + " are under a quarter of the rows' median length " +
                             format_number(float(median)) + " (the hairline cuts them short at the side): lower --spread, or drop them with " +
                             "groom select --ids");
        }
    };
}

const Registrar reg({"cornrow-guides", "Make front-to-back cornrow guide curves over a scalp", 190, setup});

}  // namespace
}  // namespace groom::cli
