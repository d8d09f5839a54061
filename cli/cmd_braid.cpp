// `groom braid`: N-strand braids and cornrows from hand-sculpted guides (talk, Sec. 2.1; ops/braid.h).
#include "cli/command.h"
#include "cli/scalp_options.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "ops/braid.h"

#include <algorithm>
#include <cstdio>
#include <string_view>

namespace groom::cli {
namespace {

struct Args {
    std::string input, output, scalp, orient = "frame", taper, knot_density, initial_normal, pattern = "plait", hand = "auto";
    float frequency = 0, knot_length = 0, width = 0, height = 0, tie = 0;
    CLI::Option *frequency_opt = nullptr, *knot_length_opt = nullptr, *width_opt = nullptr, *height_opt = nullptr,
                *tie_opt = nullptr;
    ScalpBuildParams scalp_params;
    BraidParams params;
};

/// The --pattern and --hand words (braid_pattern_name spells each pattern); false for an unknown word.
bool parse_braid_pattern(std::string_view word, BraidPattern& out)
{
    for (BraidPattern p : braid_patterns()) {
        if (word == braid_pattern_name(p)) {
            out = p;
            return true;
        }
    }
    return false;
}

bool parse_braid_hand(std::string_view word, BraidHand& out)
{
    if (word == "under") out = BraidHand::Under;
    else if (word == "over") out = BraidHand::Over;
    else if (word == "auto") out = BraidHand::Auto;
    else return false;
    return true;
}

std::string fmt(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

BraidParams params_from(const Args& a)
{
    BraidParams p = a.params;
    if (a.frequency_opt->count()) p.frequency = a.frequency;
    if (a.knot_length_opt->count()) p.knot_length = a.knot_length;
    if (a.width_opt->count()) p.width = a.width;
    if (a.height_opt->count()) p.height = a.height;
    if (a.tie_opt->count()) p.tie = a.tie;
    if (!parse_braid_pattern(a.pattern, p.pattern)) {
        throw InvalidParam("braid: --pattern must be one of " + braid_pattern_list() + " (got '" + a.pattern + "')");
    }
    if (!parse_braid_hand(a.hand, p.hand)) throw InvalidParam("braid: --hand must be under, over or auto (got '" + a.hand + "')");
    if (a.orient == "frame") p.orient = BraidOrient::Frame;
    else if (a.orient == "scalp") p.orient = BraidOrient::Scalp;
    else throw InvalidParam("braid: --orient must be frame or scalp (got '" + a.orient + "')");
    if (!a.taper.empty()) p.taper = parse_floats("braid: --taper", a.taper, 1, 1024);
    if (!a.knot_density.empty()) p.knot_density = parse_floats("braid: --knot-density", a.knot_density, 1, 1024);
    if (!a.initial_normal.empty()) {
        const auto v = parse_floats("braid: --initial-normal", a.initial_normal, 3, 3);
        p.initial_normal = {v[0], v[1], v[2]};
    }
    if (p.orient == BraidOrient::Scalp && a.scalp.empty()) {
        throw InvalidParam("braid: --orient scalp needs a scalp (give --scalp SCALP)");
    }
    p.validate();
    return p;
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    Args& a = *args;
    const BraidParams d;
    CLI::App* app = ctx.app;
    app->add_option("GUIDES", a.input, "Guide curves, root to tip (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("-o,--output", a.output, "Output curves (strands, or fibers with --fibers)")->required();
    app->add_option("--scalp", a.scalp, "Scalp: a .vdb from `groom scalp` or a mesh; keeps every point outside it");
    add_scalp_build_options(app, a.scalp_params);
    app->add_option("--pattern", a.pattern,
                    "How strands cross: plait (woven, every strand over then under), fishtail, twist (2 plies), rope, "
                    "round (tubular), lissajous (the talk's formula as written)")
        ->capture_default_str();
    app->add_option("--hand", a.hand,
                    "under (Dutch: the strand from the edge passes beneath, the braid stands proud), over (French), "
                    "or auto: under with --orient scalp, else over. For rope and twist: the lay's direction")
        ->capture_default_str();
    app->add_option("--strands", a.params.strands,
                    "Strands per braid N, [2, 32] (default: the pattern's: plait 3, fishtail 8, twist 2, rope 3, round 4)");
    a.frequency_opt = app->add_option("--frequency", a.frequency,
                                      "F: knots (full x cycles) over each whole guide, >= 0 (default " + fmt(d.kDefaultFrequency) + ")");
    a.knot_length_opt = app->add_option("--knot-length", a.knot_length,
                                        "L: length of one knot, scene units, > 0; F = guide length / L (exclusive with --frequency)");
    a.width_opt = app->add_option("--width", a.width, "A: lateral amplitude, scene units, >= 0 (default: knot length / 3)");
    a.height_opt = app->add_option("--height", a.height,
                                   "B: amplitude along the normal, scene units, >= 0 (default: strands touch where they cross; "
                                   "A / (N - 1) for a plait)");
    app->add_option("--samples", a.params.samples, "Points per strand N_cv, >= 2 (default: >= 16 per knot, >= the guide's points)");
    app->add_option("--root-amplitude", a.params.root_amplitude, "Amplitude scale at the root, >= 0")->capture_default_str();
    app->add_option("--tip-amplitude", a.params.tip_amplitude, "Amplitude scale at the tip, >= 0 (blended linearly from the root)")
        ->capture_default_str();
    app->add_option("--taper", a.taper, "Amplitude scale spline over the guide, v0,v1,... (>= 0, evenly spaced root to tip)");
    app->add_option("--knot-bias", a.params.knot_bias, "Knot distribution, (-1, 1): > 0 packs knots toward the tip, < 0 toward the root")
        ->capture_default_str();
    app->add_option("--knot-density", a.knot_density, "Relative knot density spline over the guide, v0,v1,... (> 0, root to tip)");
    app->add_option("--orient", a.orient, "frame: rotation-minimising frames; scalp: cornrows, normal = scalp normal (needs --scalp)")
        ->capture_default_str();
    app->add_option("--initial-normal", a.initial_normal,
                    "x,y,z: frame normal at the root with --orient frame (default: scalp normal, else +Y, or +Z for vertical guides)");
    app->add_option("--clearance", a.params.clearance, "With --scalp: least distance from any hair to the scalp, scene units, >= 0")
        ->capture_default_str();
    app->add_flag("--rest", a.params.rest, "With --scalp: also lower braids floating above the scalp until they rest on it");
    app->add_option("--strand-width", a.params.strand_width,
                    "Strand thickness, scene units (0 = neighbouring strands touch: 2 A / (N - 1) for a plait)")
        ->capture_default_str();
    app->add_option("--fibers", a.params.fibers, "Hair fibers per strand M (0 = strand centrelines only)")->capture_default_str();
    app->add_option("--fiber-radius", a.params.fiber_radius, "Radius of each strand's fiber disc, scene units (0 = half the strand width)")
        ->capture_default_str();
    app->add_option("--fiber-width", a.params.fiber_width, "Fiber width, scene units (0 = 2 radius / sqrt(M))")->capture_default_str();
    app->add_option("--fiber-twist", a.params.fiber_twist, "Turns of each fiber about its strand per knot")->capture_default_str();
    app->add_option("--flatten", a.params.flatten, "How much a strand flattens where strands press together, [0, 0.9]")
        ->capture_default_str();
    app->add_option("--loose-length", a.params.loose_length, "Unbraided end at each tip, scene units, >= 0")->capture_default_str();
    app->add_option("--flare", a.params.flare, "How far the loose end opens: strands and fibers spread (1 + flare) times at the tip")
        ->capture_default_str();
    a.tie_opt = app->add_option("--tie", a.tie, "Hair tie at this arc-length fraction [0, 1] of each guide (curves with kind = 1)");
    app->add_option("--tie-width", a.params.tie_width, "Tie band thickness, scene units (0 = 0.35 strand widths)")->capture_default_str();
    app->add_option("--tie-turns", a.params.tie_turns, "Wraps of the tie band, [1, 64]")->capture_default_str();
    app->add_option("--flyaways", a.params.flyaways, "Fraction of fibers leaving their strand in a loop, [0, 1]")->capture_default_str();
    app->add_option("--flyaway-height", a.params.flyaway_height, "How far a flyaway loop leaves its strand (0 = one strand width)")
        ->capture_default_str();
    app->add_option("--feed-in", a.params.feed_in, "Fraction of fibers joining along the braid instead of at the root, [0, 1); the braid starts at sqrt(1 - F) of its width and grows as they join")
        ->capture_default_str();
    app->add_option("--feed-length", a.params.feed_length, "Length over which fibers feed in, scene units (0 = three knots)")
        ->capture_default_str();
    app->add_option("--seed", a.params.seed, "Random seed for the fibers, flyaways and feed-in")->capture_default_str();
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        const Args& a = *args;
        check_output(a.output, {a.input, a.scalp}, common);
        const BraidParams params = params_from(a);
        a.scalp_params.validate();
        const CurveSet guides = read_curve_input(a.input, common);
        const auto progress = make_progress(common);
        std::shared_ptr<const ScalpField> scalp;
        if (!a.scalp.empty()) scalp = load_scalp(a.scalp, a.scalp_params, progress.get());
        const BraidResult res = braid(guides, params, scalp.get(), progress.get());
        write_curves(res.curves, a.output);
        const BraidReport& r = res.report;
        note(common, "braid: " + std::to_string(r.guides) + " guides -> " + std::to_string(r.strands) + " strands (" +
                         std::to_string(params.strand_count()) + " each, " + braid_pattern_name(params.pattern) + ")" +
                         (params.fibers > 0 ? " x " + std::to_string(params.fibers) + " fibers" : std::string()) + " = " +
                         std::to_string(r.curves) + " curves, " + std::to_string(r.points) + " points -> " + a.output +
                         (r.ties > 0 ? "; " + std::to_string(r.ties) + " ties" : std::string()) +
                         (r.flyaways > 0 ? "; " + std::to_string(r.flyaways) + " flyaways" : std::string()) +
                         (r.fed_in > 0 ? "; " + std::to_string(r.fed_in) + " fibers fed in" : std::string()));
        if (r.skipped_guides > 0) {
            warn(common, "braid: warning: skipped " + std::to_string(r.skipped_guides) +
                             " guides with fewer than 2 points or zero length");
        }
        if (scalp) {
            note(common, "braid: scalp: lifted " + std::to_string(r.lifted_sections) + " cross-sections off the scalp (max " +
                             fmt(r.max_lift) + ")" +
                             (params.rest ? ", lowered " + std::to_string(r.lowered_sections) + " onto it (max " + fmt(r.max_lower) + ")"
                                          : std::string()) +
                             ", pushed " + std::to_string(r.pushed_points) + " single points out; clearance " +
                             fmt(params.clearance));
            // Each guide by name, so the artist can find it (groom select --ids) and mend it.
            const size_t shown = std::min<size_t>(r.scalp_issues.size(), 8);
            for (size_t k = 0; k < shown; ++k) {
                const BraidScalpIssue& s = r.scalp_issues[k];
                const std::string who = "braid: warning: guide " + std::to_string(s.guide) + " (id " + std::to_string(s.id) + ")";
                if (s.deep > 0) {
                    warn(common, who + " runs up to " + fmt(s.depth) + " inside the scalp (at " + format_xyz(s.deepest) +
                                     "), deeper than its braid is wide: its braid follows it in there (" + std::to_string(s.deep) +
                                     " cross-sections left inside); move the guide out first (groom cull --mode push) or drop it " +
                                     "(groom select --ids " + std::to_string(s.id) + " --invert)");
                }
                if (s.blocked > 0) {
                    warn(common, who + ": " + std::to_string(s.blocked) + " cross-sections (the first at " + format_xyz(s.blocked_at) +
                                     ") have no clear place along the scalp normal short of passing through the scalp " +
                                     "(a gap narrower than the braid, a thin part in the way); they stay where they are clearest, up to " +
                                     fmt(s.short_by) + " short of the clearance, and their hair is pushed out point by point");
                }
            }
            if (r.scalp_issues.size() > shown) {
                warn(common, "braid: warning: and " + std::to_string(r.scalp_issues.size() - shown) + " more guides like these");
            }
        }
    };
}

const Registrar reg({"braid", "Braids and cornrows from guide curves (talk 2.1)", 200, setup});

}  // namespace
}  // namespace groom::cli
