// `groom probe`: signed distance, normal and closest point of the scalp at given points, as CSV.
#include "cli/command.h"
#include "cli/scalp_options.h"
#include "fields/point_queries.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/point_table.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace groom::cli {
namespace {

struct Args {
    ScalpBuildParams scalp_params;
    std::string scalp, input, output;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("--scalp", args->scalp, "Scalp: .vdb from `groom scalp`, or a mesh")->required();
    add_scalp_build_options(app, args->scalp_params);
    app->add_option("POINTS", args->input,
                    "Points: text of 'x y z' lines (any other extension, - = stdin), a NumPy .npy array (N, 3) of float32/float64, "
                    "or any curve file (all its points)")
        ->required();
    app->add_option("-o,--output", args->output,
                    "Output: CSV x,y,z,distance,nx,ny,nz,cx,cy,cz, or a .npy array (N, 10) of float32 with those columns")
        ->required();
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        const Args& a = *args;
        check_output(a.output, {a.input, a.scalp}, common);
        std::vector<float3> points;
        if (is_curve_path(a.input)) {
            const CurveSet curves = read_curve_input(a.input, common);
            const auto P = curves.positions();
            points.assign(P.begin(), P.end());
        }
        else {
            points = read_points(a.input);
        }
        auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(a.scalp, a.scalp_params, progress.get());
        const int64_t n = static_cast<int64_t>(points.size());
        // One row of the table per point, filled in place: x,y,z,distance,nx,ny,nz,cx,cy,cz.
        constexpr int kColumns = 10;
        std::vector<float> table(points.size() * kColumns);
        query_points(*scalp, points, [&](size_t i, float d, const float3& nn, const float3& c) {
            const float3& p = points[i];
            const float values[kColumns] = {p.x, p.y, p.z, d, nn.x, nn.y, nn.z, c.x, c.y, c.z};
            std::copy(values, values + kColumns, table.data() + i * kColumns);
        });
        AtomicOutput out(a.output, true);
        if (is_npy_path(a.output)) write_npy_table(out.stream(), table, kColumns);
        else write_csv_table(out.stream(), "x,y,z,distance,nx,ny,nz,cx,cy,cz", table, kColumns);
        out.commit();
        int64_t inside = 0;
        for (int64_t i = 0; i < n; ++i) inside += table[size_t(i) * kColumns + 3] < 0.0f;
        note(common, "probe: " + std::to_string(n) + " points (" + std::to_string(inside) + " inside) -> " + a.output);
    };
}

const Registrar reg({"probe", "Signed distance, normal and closest scalp point at given points (CSV)", 110, setup});

}  // namespace
}  // namespace groom::cli
