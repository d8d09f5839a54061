// `groom head`: writes the synthetic default head (ops/head.h), the demo's scalp.
#include "cli/command.h"
#include "kernel/io/mesh_io.h"
#include "ops/head.h"

#include <chrono>
#include <cstdio>

namespace groom::cli {
namespace {

struct Args {
    std::string output;
    HeadParams params;
    bool no_ears = false;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("-o,--output", args->output, "Output mesh (.obj .ply)")->required();
    app->add_option("--resolution", args->params.resolution, "Latitude bands of the sphere the head is sampled on, [8, 1024]")
        ->capture_default_str();
    app->add_option("--scale", args->params.scale, "Multiplies every coordinate: 1 = centimetres, 0.01 = metres")->capture_default_str();
    app->add_flag("--no-ears", args->no_ears, "Leave the ears out");
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {}, common);
        args->params.ears = !args->no_ears;
        args->params.validate();
        const auto start = std::chrono::steady_clock::now();
        const PolygonSoup head = make_head(args->params);
        write_mesh(head, args->output);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "head: %zu vertices, %zu faces, %.1f s -> ", head.points.size(), head.num_faces(), secs);
        note(common, line + args->output);
    };
}

const Registrar reg({"head", "Write the synthetic default head (closed mesh, +Y up, centimetres)", 500, setup});

}  // namespace
}  // namespace groom::cli
