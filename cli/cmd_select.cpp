// `groom select`: keep the curves matching an id range, guide, attribute comparison or prim path
// (ops/select.h).
#include "cli/command.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/io_util.h"
#include "ops/select.h"

#include <algorithm>

namespace groom::cli {
namespace {

struct Args {
    std::string input, output, ids, guides;
    std::vector<std::string> where, prims;
    bool invert = false;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--ids", args->ids, "Curve ids (attribute id, else the index): ids and inclusive ranges, e.g. 0-9,20,30-39");
    app->add_option("--guide", args->guides, "Curves grown from these guides (curve attribute guide), e.g. 3 or 0,2,5");
    app->add_option("--where", args->where,
                    "NAME OP NUMBER, OP one of < <= > >= == != (e.g. width>0.01, kind==2, Cd.x<=0.5); point attributes are "
                    "read at the root; repeat (or separate by commas) to require several")
        ->allow_extra_args(false);
    app->add_option("--prim", args->prims, "USD prim path the curves came from (the prim or anything under it); repeat (or separate by commas) for several")->allow_extra_args(false);
    app->add_flag("--invert", args->invert, "Keep the curves that do not match instead");
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        const Args& a = *args;
        check_output(a.output, {a.input}, common);
        SelectParams params;
        if (!a.ids.empty()) params.ids = parse_id_ranges(a.ids, "ids");
        if (!a.guides.empty()) {
            for (const IdRange& r : parse_id_ranges(a.guides, "guide")) {
                if (uint64_t(r.hi) - uint64_t(r.lo) > 1000000) throw InvalidParam("select: `guide` range " + std::to_string(r.lo) + "-" + std::to_string(r.hi) + " is too long (more than a million guides)");
                // Stops at r.hi itself: `g <= r.hi` never failed for r.hi = INT64_MAX (g wrapped; a trial).
                for (int64_t g = r.lo;; ++g) {
                    params.guides.push_back(g);
                    if (g >= r.hi) break;
                }
            }
        }
        // Several in one value, comma-separated (how the Python module passes a list); no comparison
        // or prim path holds a comma.
        auto split = [](const std::vector<std::string>& values) {
            std::vector<std::string> out;
            for (const std::string& v : values) {
                for (size_t pos = 0; pos <= v.size();) {
                    const size_t comma = std::min(v.find(',', pos), v.size());
                    out.push_back(v.substr(pos, comma - pos));
                    pos = comma + 1;
                }
            }
            return out;
        };
        for (const std::string& w : split(a.where)) params.where.push_back(parse_attribute_test(w, "where"));
        params.prims = split(a.prims);
        params.invert = a.invert;
        params.validate();
        // A USD input names each curve's prim for --prim (the reader's prim_paths), dropped again
        // from the output: they describe this file's prims, not the selection's.
        CurveReadOptions read_options;
        const std::string ext = io::extension_of(a.input);
        const bool usd = ext == "usda" || ext == "usd" || a.input == "-";
        read_options.prim_paths = usd && !params.prims.empty();
        read_options.warn = [&common](const std::string& w) { warn(common, "warning: " + w); };
        const CurveSet curves = read_curves(a.input, read_options);
        SelectStats stats;
        CurveSet out = select(curves, params, &stats);
        if (read_options.prim_paths) {
            out.attributes(Domain::Curve).remove("prim");
            out.attributes(Domain::Detail).remove("prim_paths");
        }
        write_curves(out, a.output);
        note(common, "select: " + std::to_string(stats.matched) + " of " + std::to_string(curves.num_curves()) + " curves match, " +
                         std::to_string(stats.kept) + " kept -> " + a.output);
        if (stats.kept == 0 && curves.num_curves() > 0) {
            // An empty file was written without a word (a trial's --ids past the input's last id).
            const std::vector<int64_t> ids = curves.curve_ids(0, curves.num_curves());
            const auto [lo, hi] = std::minmax_element(ids.begin(), ids.end());
            warn(common, "select: warning: no curve kept, " + a.output + " holds none (the input's ids run from " + std::to_string(*lo) + " to " +
                             std::to_string(*hi) + ")");
        }
    };
}

const Registrar reg({"select", "Keep curves by id range, guide, attribute comparison or prim path", 40, setup});

}  // namespace
}  // namespace groom::cli
