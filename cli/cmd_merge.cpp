// `groom merge`: curve files one after another into one, every column carried: puts the parts of a
// `--shard I/N` run back together (cli/frame_options.h), byte for byte the whole run's output.
#include "cli/command.h"
#include "kernel/curve_set_edit.h"
#include "kernel/io/curve_io.h"

namespace groom::cli {
namespace {

struct Args {
    std::vector<std::string> inputs;
    std::string output;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->inputs, "Curve files (" + curve_formats() + "), in order: shard 0/N first")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        for (const std::string& in : args->inputs) check_output(args->output, {in}, common);
        CurveSet all = read_curves(args->inputs[0]);
        for (size_t i = 1; i < args->inputs.size(); ++i) all = join(all, read_curves(args->inputs[i]));
        write_curves(all, args->output);
        note(common, "merge: " + std::to_string(all.num_curves()) + " curves, " + std::to_string(all.num_points()) + " points from " +
                         std::to_string(args->inputs.size()) + " files -> " + args->output);
    };
}

const Registrar reg({"merge", "Join curve files in order (the shards of a --shard run) into one", 950, setup});

}  // namespace
}  // namespace groom::cli
