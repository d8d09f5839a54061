// `groom convert IN -o OUT`: between the curve formats (kernel/io/format_table.h), saying which
// attributes the target format cannot hold.
#include "cli/command.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/format_table.h"

#include <filesystem>

namespace groom::cli {
namespace {

struct Args {
    std::string input, output;
    bool ascii = false;
    int samples = 8;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = .usda on stdin)")->required();
    app->add_option("-o,--output", args->output, "Output curves (" + io::format_list(io::kWriteCurves) + ", - = .usda on stdout)")->required();
    app->add_flag("--ascii", args->ascii, "Write .ply as ASCII (default binary little-endian)");
    app->add_option("--samples-per-segment", args->samples, "Points per segment when reading cubic and NURBS .usda curves (>= 1)");
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        check_output(args->output, {args->input}, common);
        if (args->samples < 1) throw InvalidParam("convert: --samples-per-segment must be >= 1 (got " + std::to_string(args->samples) + ")");
        const CurveSet cs = read_curve_input(args->input, common, true, args->samples);
        CurveWriteOptions wo;
        wo.ply_encoding = args->ascii ? PlyEncoding::Ascii : PlyEncoding::Binary;
        if (args->ascii && std::filesystem::path(args->output).extension() != ".ply") {
            // (`-o - --ascii` had written .usda without a word: a trial.)
            warn(common, "convert: warning: --ascii is for .ply outputs; " + (args->output == "-" ? std::string("stdout gets .usda") : args->output + " is not one") +
                             ", written as its format is");
        }
        write_curves(cs, args->output, wo);
        warn_up_axis_unsaid("convert", cs, args->output, common);
        note(common, "convert: " + std::to_string(cs.num_curves()) + " curves, " + std::to_string(cs.num_points()) + " points -> " + args->output);
    };
}

const Registrar reg({"convert", "Convert curves from one file format to another", 20, setup});

}  // namespace
}  // namespace groom::cli
