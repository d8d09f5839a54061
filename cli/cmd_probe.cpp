// `groom probe`: signed distance, normal and closest point of the scalp at given points, as CSV.
#include "cli/command.h"
#include "cli/scalp_options.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/curve_io.h"
#include "kernel/parallel.h"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace groom::cli {
namespace {

struct Args {
    ScalpBuildParams scalp_params;
    std::string scalp, input, output;
};

/// `x y z` per line (commas allowed); blank lines and lines starting with '#' are skipped.
std::vector<float3> read_point_text(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw IoError(path + ": cannot open");
    std::vector<float3> points;
    std::string line;
    for (int64_t lineno = 1; std::getline(in, line); ++lineno) {
        for (char& c : line)
            if (c == ',' || c == '\t' || c == '\r') c = ' ';
        const size_t first = line.find_first_not_of(' ');
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream s(line);
        float3 p;
        std::string extra;
        if (!(s >> p.x >> p.y >> p.z) || (s >> extra) || !isfinite(p)) {
            throw ParseError(path + ":" + std::to_string(lineno) + ": expected three finite numbers 'x y z', got '" + line + "'");
        }
        points.push_back(p);
    }
    return points;
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("--scalp", args->scalp, "Scalp: .vdb from `groom scalp`, or a mesh")->required();
    add_scalp_build_options(app, args->scalp_params);
    app->add_option("POINTS", args->input, "Points: text file of 'x y z' lines, or any curve file (all its points)")->required();
    app->add_option("-o,--output", args->output, "Output CSV: x,y,z,distance,nx,ny,nz,cx,cy,cz")->required();
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
            points = read_point_text(a.input);
        }
        auto progress = make_progress(common);
        const std::shared_ptr<const ScalpField> scalp = load_scalp(a.scalp, a.scalp_params, progress.get());
        const int64_t n = static_cast<int64_t>(points.size());
        std::vector<float> dist(points.size());
        std::vector<float3> normals(points.size()), closest(points.size());
        parallel_for(n, 1024, [&](int64_t b, int64_t e) {
            for (int64_t i = b; i < e; ++i) dist[i] = scalp->query(points[i], normals[i], closest[i]);
        });
        AtomicOutput out(a.output, false);
        std::ostream& s = out.stream();
        s << "x,y,z,distance,nx,ny,nz,cx,cy,cz\n";
        char buf[320];
        for (size_t i = 0; i < points.size(); ++i) {
            const float3 &p = points[i], &nn = normals[i], &c = closest[i];
            std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", p.x, p.y, p.z, dist[i], nn.x, nn.y,
                          nn.z, c.x, c.y, c.z);
            s << buf;
        }
        out.commit();
        int64_t inside = 0;
        for (float d : dist) inside += d < 0.0f;
        note(common, "probe: " + std::to_string(n) + " points (" + std::to_string(inside) + " inside) -> " + a.output);
    };
}

const Registrar reg({"probe", "Signed distance, normal and closest scalp point at given points (CSV)", 110, setup});

}  // namespace
}  // namespace groom::cli
