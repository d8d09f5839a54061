// `groom curl`: curl each input curve around its own centreline (talk, Sec. 3.1).
#include "cli/command.h"
#include "cli/scalp_options.h"
#include "cli/curl_options.h"
#include "cli/scene_scale.h"
#include "fields/scalp_field.h"
#include "kernel/curve_blocks.h"
#include "kernel/io/curve_io.h"
#include "ops/curl.h"

namespace groom::cli {
namespace {

/// Whether the output's format keeps curl's point `shape` and `cycle` columns: .hair does not, and
/// then they are not made (on a million hairs they were a quarter of the process's memory).
bool keeps_point_labels(const std::string& output)
{
    CurveSet probe = CurveSet::from_counts(std::vector<int64_t>{1});
    probe.add<int32_t>(Domain::Point, "shape");
    probe.add<int32_t>(Domain::Point, "cycle");
    return attributes_dropped(probe, output).empty();
}

struct Args {
    std::string input, output, scalp;
    ScalpBuildParams scalp_params;
    CurlOptions curl;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--scalp", args->scalp, "Scalp (.vdb from `groom scalp`, or a mesh): no curled point ends inside it");
    add_scalp_build_options(app, args->scalp_params);
    add_curl_options(app, args->curl);
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {args->input, args->scalp}, common);  // the scalp too: `-o head.obj` had overwritten it
        CurlParams params = curl_params_from(args->curl);
        params.labels = keeps_point_labels(args->output);
        const CurveSet in = read_curve_input(args->input, common);
        if (args->curl.amplitude.empty()) {
            warn_curl_scale(common, "curl", in, curl_default_radius(params),
                            "type " + params.hair_type + "'s default x --units-per-cm " + format_number(params.units_per_cm));
        }
        {
            // The op passes a curve of one point or of zero length through as it is (nothing to curl
            // around); a trial's five points at one spot came back unchanged without a word.
            const auto P = in.positions();
            int64_t flat = 0, first = -1;
            for (size_t c = 0; c < in.num_curves(); ++c) {
                const IndexRange r = in.points_of(c);
                bool moves = false;
                for (int64_t i = r.begin + 1; i < r.end && !moves; ++i) moves = P[size_t(i)] != P[size_t(r.begin)];
                if (!moves) {
                    if (first < 0) first = int64_t(c);
                    ++flat;
                }
            }
            if (flat > 0) {
                warn(common, "curl: warning: " + std::to_string(flat) + " of " + std::to_string(in.num_curves()) +
                                 " curves have one point or zero length (the first: curve " + std::to_string(first) +
                                 "); they were passed through uncurled");
            }
        }
        const auto progress = make_progress(common);
        std::shared_ptr<const ScalpField> scalp;
        if (!args->scalp.empty()) scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        int64_t curves = 0, points = 0;
        if (writes_curve_blocks(args->output)) {
            // Written as it is made: the output is never whole in memory (a million hairs' curl
            // held its input and its output, twice the file; now the input and two blocks).
            const CurveBlockCounts n = write_curve_blocks(args->output, [&](const CurveBlockStart& start, const CurveBlockEmit& emit) {
                curl_blocks(in, params, scalp.get(), progress.get(), kCurveBlockPoints, start, emit);
            });
            curves = int64_t(n.curves), points = int64_t(n.points);
        }
        else {
            const CurveSet out = curl(in, params, scalp.get(), progress.get());
            write_curves(out, args->output);
            curves = int64_t(out.num_curves()), points = int64_t(out.num_points());
        }
        note(common, "curl: " + std::to_string(curves) + " curves, " + std::to_string(points) + " points (type " + params.hair_type + ") -> " +
                         args->output);
    };
}

const Registrar reg({"curl", "Curl curves cycle by cycle with random cross-section shapes (talk 3.1)", 300, setup});

}  // namespace
}  // namespace groom::cli
