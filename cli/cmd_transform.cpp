// `groom transform`: translate, rotate, scale, change up axis or units (ops/transform.h).
#include "cli/command.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "ops/transform.h"

namespace groom::cli {
namespace {

struct Args {
    std::string input, output, translate, rotate, scale;
    TransformParams params;
};

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("CURVES", args->input, "Input curves (" + curve_formats() + ", - = stdin)")->required();
    app->add_option("-o,--output", args->output, "Output curves")->required();
    app->add_option("--translate", args->translate, "x,y,z: added last, output scene units");
    app->add_option("--rotate", args->rotate, "x,y,z: degrees about X, then Y, then Z (USD rotateXYZ)");
    app->add_option("--scale", args->scale, "s (uniform) or x,y,z (per axis; widths follow the uniform part)");
    app->add_option("--up-axis", args->params.up_axis, "y or z: convert to this up axis (from the curves' up_axis, else the other one)")
        ->check(CLI::IsMember({"y", "z", "Y", "Z"}));
    app->add_option("--units", args->params.units, "mm, cm, m or in: convert lengths to this unit")->check(CLI::IsMember({"mm", "cm", "m", "in"}));
    app->add_option("--from-units", args->params.from_units, "mm, cm, m or in: the curves' unit, when they do not carry one (detail units)")
        ->check(CLI::IsMember({"mm", "cm", "m", "in"}));
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, &common] {
        Args& a = *args;
        check_output(a.output, {a.input}, common);
        if (!a.translate.empty()) a.params.translate = parse_float3("--translate", a.translate);
        if (!a.rotate.empty()) a.params.rotate = parse_float3("--rotate", a.rotate);
        if (!a.scale.empty()) {
            const std::vector<float> s = parse_floats("--scale", a.scale, 1, 3);
            if (s.size() == 2) throw InvalidParam("transform: --scale '" + a.scale + "': expected one factor or three (x,y,z), found 2");
            a.params.scale = s.size() == 1 ? float3(s[0], s[0], s[0]) : float3(s[0], s[1], s[2]);
        }
        a.params.validate();
        const CurveSet out = transform(read_curves(a.input), a.params);
        write_curves(out, a.output);
        warn_up_axis_unsaid("transform", out, a.output, common);
        note(common, "transform: " + std::to_string(out.num_curves()) + " curves -> " + a.output);
    };
}

const Registrar reg({"transform", "Translate, rotate, scale; change up axis or units", 45, setup});

}  // namespace
}  // namespace groom::cli
