// `groom parting`: parting curves on the scalp through points the user picks (fields/surface_path.h),
// for the --parting options of other commands. Each --through draws one parting.
#include "cli/command.h"
#include "cli/scalp_options.h"
#include "fields/scalp_field.h"
#include "fields/surface_path.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "kernel/memory_budget.h"

#include <chrono>
#include <cstdio>
#include <sstream>

namespace groom::cli {
namespace {

struct Args {
    std::string scalp, output;
    std::vector<std::string> through;
    ScalpBuildParams scalp_params;
    float step = 0.25f;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("--scalp", args->scalp, "Scalp: a .vdb from `groom scalp` or a mesh (" + mesh_formats() + ")")->required();
    app->add_option("-o,--output", args->output, "Output curve file, one curve per --through (" + curve_formats() + ")")->required();
    app->add_option("--through", args->through,
                    "X,Y,Z/X,Y,Z/...: points the parting passes through, in order (each projected onto the scalp); repeat for more partings")
        ->required();
    app->add_option("--step", args->step, "Spacing of the curve's points, scene units, > 0")->capture_default_str();
    add_scalp_build_options(app, args->scalp_params);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {args->scalp}, common);
        if (!(args->step > 0.0f) || !std::isfinite(args->step)) {
            throw InvalidParam("parting: --step must be a finite number > 0 (got " + format_number(args->step) + ")");
        }
        std::vector<std::vector<float3>> waypoints;
        for (const std::string& text : args->through) {
            std::vector<float3> w;
            std::stringstream ss(text);
            for (std::string item; std::getline(ss, item, '/');) {
                w.push_back(parse_float3("--through", item));
            }
            if (w.size() < 2) throw InvalidParam("parting: --through needs at least two points X,Y,Z/X,Y,Z (got '" + text + "')");
            waypoints.push_back(std::move(w));
        }
        const auto start = std::chrono::steady_clock::now();
        const auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(args->scalp, args->scalp_params, progress.get());
        // Before walking: each leg takes at most 4 |a - b| / step + 16 steps between the waypoints'
        // surface points (surface_path), each point held three times (path, all, output).
        // `--step 1e-6` across the head made 12 million points past a 64 MiB --memory (op fuzzer).
        double bound = 0.0;
        for (const std::vector<float3>& w : waypoints)
            for (size_t k = 0; k + 1 < w.size(); ++k)
                bound += 4.0 * double(distance(scalp->closest_point(w[k]), scalp->closest_point(w[k + 1]))) / double(args->step) + 16.0;
        check_memory("parting: up to " + format_number(bound) + " points at --step " + format_number(args->step), bound * 36.0,
                     "use a larger --step");
        std::vector<int64_t> counts;
        std::vector<float3> all, path;
        for (size_t i = 0; i < waypoints.size(); ++i) {
            if (!surface_path_through(*scalp, waypoints[i], args->step, 0.0f, path)) {
                throw InvalidGeometry("parting: --through '" + args->through[i] + "': the path on the scalp did not reach its next point " +
                                      "(a hole or a fold between them?); add a point between");
            }
            counts.push_back(static_cast<int64_t>(path.size()));
            all.insert(all.end(), path.begin(), path.end());
        }
        CurveSet out = CurveSet::from_counts(counts);
        std::copy(all.begin(), all.end(), out.positions_for_write().begin());
        auto ids = out.add<int64_t>(Domain::Curve, attr::id);
        for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int64_t>(i);
        write_curves(out, args->output);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "parting: %zu curves, %zu points, %.2f s -> ", out.num_curves(), out.num_points(), secs);
        note(common, line + args->output);
    };
}

const Registrar reg({"parting", "Parting curves on the scalp through the points you give", 150, setup});

}  // namespace
}  // namespace groom::cli
