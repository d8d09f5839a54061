// `groom partition`: edge hairs between braids (talk, Sec. 2.2), from the guides the braids follow.
#include "cli/command.h"
#include "cli/region_options.h"
#include "cli/scalp_options.h"
#include "cli/scene_scale.h"
#include "cli/width_options.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/curve_io.h"
#include "ops/partition.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace groom::cli {
namespace {

struct Args {
    std::string input, output, scalp, adjacent_file, write_adjacent, centroids, knot_density, mediate;
    ScalpBuildParams scalp_params;
    float frequency = 0.0f, knot_length = 0.0f, knot_bias = 0.0f;
    PartitionParams params;
    RegionOptions hair_region;
    WidthOptions widths;
    float width = 0.0f;
    CLI::Option* width_opt = nullptr;
    bool width_given() const { return width_opt && width_opt->count() > 0; }
};

/// Lines of a small text file with their numbers, comments (#) and blank lines dropped, each split at
/// commas with surrounding spaces trimmed.
struct CsvLine {
    int number = 0;
    std::string text;
    std::vector<std::string> fields;
};

std::vector<CsvLine> read_csv(const std::string& path, const std::string& option)
{
    std::ifstream in(path);
    if (!in) {
        const int err = errno;
        // --centroids takes a word too: say so where the value is neither (`--centroids 0`: a trial).
        throw IoError(option + " " + path + ": cannot open for reading (" + std::strerror(err) + ")" +
                      (option == "--centroids" ? "; --centroids takes every:K, knots, or a file of 'guide,u' lines" : ""));
    }
    std::vector<CsvLine> lines;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        CsvLine l{number, line, {}};
        size_t start = 0;
        while (true) {
            const size_t end = line.find(',', start);
            std::string f = line.substr(start, end == std::string::npos ? std::string::npos : end - start);
            f.erase(0, f.find_first_not_of(" \t"));
            f.erase(f.find_last_not_of(" \t") + 1);
            l.fields.push_back(f);
            if (end == std::string::npos) break;
            start = end + 1;
        }
        lines.push_back(std::move(l));
    }
    return lines;
}

template <class T> bool parse_number(const std::string& s, T& v)
{
    const auto res = std::from_chars(s.data(), s.data() + s.size(), v);
    return !s.empty() && res.ec == std::errc() && res.ptr == s.data() + s.size();
}

/// `source,left,right` per line (guide indices, -1 = none), checked against the guide count.
std::vector<AdjacentGuides> read_adjacent(const std::string& path, size_t guides)
{
    const std::string range = " (" + std::to_string(guides) + " guides: 0 to " + std::to_string(int64_t(guides) - 1);
    std::vector<AdjacentGuides> out;
    std::map<int32_t, int> seen;  // source -> line
    for (const CsvLine& l : read_csv(path, "--adjacent")) {
        const std::string where = path + ":" + std::to_string(l.number) + ": ";
        int32_t v[3];
        if (l.fields.size() != 3 || !parse_number(l.fields[0], v[0]) || !parse_number(l.fields[1], v[1]) ||
            !parse_number(l.fields[2], v[2])) {
            throw ParseError(where + "expected 'source,left,right' (3 guide indices, -1 for none), got '" + l.text + "'");
        }
        const char* names[3] = {"source", "left", "right"};
        for (int k = 0; k < 3; ++k) {
            const bool ok = v[k] < int64_t(guides) && (v[k] >= 0 || (k > 0 && v[k] == -1));
            if (!ok) throw ParseError(where + names[k] + " guide " + std::to_string(v[k]) + " out of range" + range + (k > 0 ? ", or -1)" : ")"));
        }
        if (v[1] == v[0] || v[2] == v[0]) throw ParseError(where + "guide " + std::to_string(v[0]) + " cannot be its own neighbour");
        if (auto it = seen.find(v[0]); it != seen.end()) {
            throw ParseError(where + "source guide " + std::to_string(v[0]) + " already listed at line " + std::to_string(it->second));
        }
        seen[v[0]] = l.number;
        out.push_back({v[0], v[1], v[2]});
    }
    return out;
}

/// `guide,u` per line: a centroid at arc-length fraction u (0 root, 1 tip) of the guide.
std::vector<CentroidPoint> read_centroids(const std::string& path, size_t guides)
{
    std::vector<CentroidPoint> out;
    for (const CsvLine& l : read_csv(path, "--centroids")) {
        const std::string where = path + ":" + std::to_string(l.number) + ": ";
        CentroidPoint c;
        if (l.fields.size() != 2 || !parse_number(l.fields[0], c.guide) || !parse_number(l.fields[1], c.u)) {
            throw ParseError(where + "expected 'guide,u' (a guide index and an arc-length fraction in [0, 1]), got '" + l.text + "'");
        }
        if (c.guide < 0 || size_t(c.guide) >= guides) {
            throw ParseError(where + "guide " + std::to_string(c.guide) + " out of range (" + std::to_string(guides) + " guides: 0 to " +
                             std::to_string(int64_t(guides) - 1) + ")");
        }
        if (!(c.u >= 0.0f && c.u <= 1.0f)) throw ParseError(where + "u must be in [0, 1] (got " + l.fields[1] + ")");
        out.push_back(c);
    }
    return out;
}

void write_adjacent(const std::vector<AdjacentGuides>& adjacent, const std::string& path, OutputBatch& outputs)
{
    std::ostream& out = outputs.open(path, false);
    out << "# source,left,right (guide indices; -1 = none). Left = scalp normal x guide tangent.\n";
    for (const AdjacentGuides& a : adjacent) out << a.source << "," << a.left << "," << a.right << "\n";
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    PartitionParams& p = args->params;
    app->add_option("GUIDES", args->input, "Guide curves, the braids' sources (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("-o,--output", args->output, "Output edge-hair curves")->required();
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp`, or a mesh converted on the fly")->required();
    add_scalp_build_options(app, args->scalp_params);
    add_region_options(app, args->hair_region);
    app->add_option("--adjacent", args->adjacent_file,
                    "Neighbours instead of searching: lines 'source,left,right' (guide indices, -1 = none); only listed guides are partitioned");
    app->add_option("--write-adjacent", args->write_adjacent, "Write the neighbours found (or given) in --adjacent's format, to edit and reuse");
    app->add_option("--mediate", args->mediate,
                    "Roots between the source (0) and the adjacent guide (1), drawn per segment from lo,hi; 0.5 = all on the midpoint "
                    "(the talk's); default 0.1,0.47: spread over the strip, a bare parting line in the middle 6%");
    auto* count = app->add_option("--count", p.count, "Segments per side of each guide (>= 1); default: one every 1/200 of the typical gap between guides");
    auto* spacing = app->add_option("--spacing", p.spacing, "Arc length between segments along the guide, scene units (> 0)");
    app->add_option("--samples", p.samples, "Points per segment (>= 2)")->capture_default_str();
    add_width_options(app, args->widths, "the defaults x --units-per-cm");
    app->add_option("--units-per-cm", p.units_per_cm, "Scene units per centimetre, for the default widths (0.01 for metres)")->capture_default_str();
    args->width_opt = app->add_option("--width", args->width, "One hair diameter root to tip (--root-width W --tip-width W), scene units, > 0")
        ->excludes(args->widths.root_opt)
        ->excludes(args->widths.tip_opt);
    app->add_option("--jitter", p.jitter, "Random shift of segments along the guide, fraction of the spacing [0, 1]")->capture_default_str();
    app->add_option("--seed", p.seed, "Random seed for --jitter and --mediate")->capture_default_str();
    app->add_option("--max-gap", p.max_gap, "Ignore neighbours (and stations) farther than this, scene units; 0 = automatic, 4 typical gaps between guides")->capture_default_str();
    app->add_option("--max-height", p.max_height, "No segments where the guide is higher than this above the scalp, scene units (0 = no limit)")->capture_default_str();
    app->add_option("--centroids", args->centroids,
                    "Group segments so each group ends on one point of the guide: knots (the braid's knots), every:K (K consecutive "
                    "segments), or a FILE of "
                    "lines 'guide,u' (u = arc-length fraction 0..1); default: each segment ends at its own point");
    app->add_option("--converge", p.converge,
                    "With --centroids: how far a group's segments converge on its centroid, 0..1 (1 = all on it, the talk's)")
        ->capture_default_str();
    auto* frequency = app->add_option("--frequency", args->frequency, "With --centroids knots: knots per guide, as in groom braid");
    auto* knot_length = app->add_option("--knot-length", args->knot_length, "With --centroids knots: arc length of one knot, scene units, as in groom braid");
    auto* knot_bias = app->add_option("--knot-bias", args->knot_bias, "With --centroids knots: knot distribution bias (-1, 1), as in groom braid");
    auto* knot_density = app->add_option("--knot-density", args->knot_density,
                                         "With --centroids knots: relative knot density spline v0,v1,... (> 0, root to tip), as in groom braid");
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, count, spacing, frequency, knot_length, knot_bias, knot_density, &common] {
        PartitionParams& params = args->params;
        check_outputs({{"-o", args->output}, {"--write-adjacent", args->write_adjacent}},
                      {args->input, args->scalp, args->adjacent_file, args->hair_region.hairline, args->hair_region.parting}, common);
        // 0 means automatic to the op; typed on the command line it is a mistake.
        if (count->count() && params.count < 1) {
            throw InvalidParam("partition: --count must be >= 1 (got " + std::to_string(params.count) + ")");
        }
        if (spacing->count() && !(params.spacing > 0.0f)) {
            throw InvalidParam("partition: --spacing must be > 0 scene units (got " + format_number(params.spacing) + ")");
        }
        params.mediate = parse_range("partition: --mediate", args->mediate, params.mediate);
        const std::string& spec = args->centroids;
        if (spec.rfind("every:", 0) == 0) {
            params.centroids = CentroidMode::Every;
            if (!parse_number(spec.substr(6), params.every)) {
                throw InvalidParam("partition: --centroids every:K needs an integer K >= 1 (got '" + spec + "')");
            }
        }
        else if (spec == "knots") {
            params.centroids = CentroidMode::Knots;
            if (frequency->count()) params.knots.frequency = args->frequency;
            if (knot_length->count()) params.knots.knot_length = args->knot_length;
            params.knots.knot_bias = args->knot_bias;
            if (!args->knot_density.empty()) {
                params.knots.knot_density = parse_floats("partition: --knot-density", args->knot_density, 1, 1024);
            }
        }
        else if (!spec.empty()) {
            params.centroids = CentroidMode::Points;
        }
        if (params.centroids != CentroidMode::Knots) {
            for (const CLI::Option* o : {frequency, knot_length, knot_bias, knot_density}) {
                if (o->count()) throw InvalidParam("partition: " + o->get_name() + " applies only with --centroids knots");
            }
        }
        params.widths = hair_widths_from(args->widths, "partition");
        if (args->width_given()) {
            if (!(std::isfinite(args->width) && args->width > 0.0f)) {
                throw InvalidParam("partition: --width must be > 0 scene units (got " + format_number(args->width) + ")");
            }
            params.widths.root = params.widths.tip = args->width;
        }
        params.validate();  // options first: no need to read anything to reject them

        const CurveSet guides = read_curve_input(args->input, common);
        if (!args->adjacent_file.empty()) {
            params.adjacent = read_adjacent(args->adjacent_file, guides.num_curves());
            // Empty, it would fall to the automatic search below, against "only the sources listed
            // are partitioned" (a trial's file of comments only did).
            if (params.adjacent.empty()) {
                throw ParseError(args->adjacent_file + ": --adjacent lists no guide (expected 'source,left,right' lines); to let partition "
                                 "find the neighbours itself, leave --adjacent out");
            }
        }
        if (params.centroids == CentroidMode::Points) params.centroid_points = read_centroids(spec, guides.num_curves());
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        if (!params.widths.given()) warn_scene_scale(common, "partition", scalp->bounds(), params.units_per_cm, "the default widths");

        if (params.adjacent.empty()) {
            params.adjacent = find_adjacent_guides(guides, *scalp, params.max_gap, progress.get());
        }
        int64_t both = 0, one = 0;
        for (const AdjacentGuides& a : params.adjacent) {
            (a.left >= 0 && a.right >= 0 ? both : one) += (a.left >= 0 || a.right >= 0);
            detail(common, "partition: guide " + std::to_string(a.source) + ": left " + std::to_string(a.left) + ", right " +
                               std::to_string(a.right));
        }
        const std::unique_ptr<HairRegion> region = make_region(args->hair_region, *scalp);
        params.region = region.get();
        const CurveSet out = partition(guides, *scalp, params, progress.get());
        OutputBatch outputs;  // both files land together, or neither
        if (!args->write_adjacent.empty()) write_adjacent(params.adjacent, args->write_adjacent, outputs);
        write_curves(out, args->output, outputs);
        outputs.commit();
        note(common, "partition: " + std::to_string(out.num_curves()) + " segments from " + std::to_string(guides.num_curves()) +
                         " guides (" + std::to_string(both) + " with two neighbours, " + std::to_string(one) + " with one) -> " +
                         args->output);
    };
}

const Registrar reg({"partition", "Edge hairs parted between braids, pulled into each (talk 2.2)", 210, setup});

}  // namespace
}  // namespace groom::cli
