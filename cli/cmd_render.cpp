// `groom render`: preview pictures of curves on a scalp mesh (ops/render.h), written as PNG.
#include "cli/command.h"
#include "cli/render_options.h"
#include "fields/scalp_field.h"
#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/mesh_io.h"
#include "kernel/io/png.h"
#include "ops/render.h"

#include <chrono>
#include <cstdio>
#include <optional>

namespace groom::cli {
namespace {

struct Args {
    std::vector<std::string> inputs;
    std::string scalp, scalp_group, scalp_grid, output, view, views, camera, up, size = "1024x1024", color_by = "none", color, scalp_color, background;
    float fov = 0.0f;
    RenderParams params;
};

bool ends_with(const std::string& s, const std::string& suffix)
{
    if (s.size() < suffix.size()) return false;
    for (size_t i = 0; i < suffix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
    return true;
}

/// "WxH" or "N" (square) into width and height.
void parse_size(const std::string& text, int& w, int& h)
{
    const size_t x = text.find_first_of("xX");
    auto parse_int = [&](const std::string& s) -> int {
        size_t used = 0;
        long long v = 0;
        try {
            v = std::stoll(s, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (s.empty() || used != s.size()) throw InvalidParam("render: --size expects WxH in pixels, e.g. 1024x768 (got '" + text + "')");
        if (v < 0 || v > 1000000) throw InvalidParam("render: --size " + text + " is out of range (each side in [1, 16384])");
        return static_cast<int>(v);
    };
    if (x == std::string::npos) w = h = parse_int(text);
    else {
        w = parse_int(text.substr(0, x));
        h = parse_int(text.substr(x + 1));
    }
}

std::vector<View> parse_views(const std::string& text)
{
    std::vector<View> out;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find(',', start);
        if (end == std::string::npos) end = text.size();
        out.push_back(parse_view(text.substr(start, end - start)));
        start = end + 1;
    }
    return out;
}

void setup(CommandContext& ctx)
{
    auto args = std::make_shared<Args>();
    CLI::App* app = ctx.app;
    app->add_option("FILES", args->inputs, "Curve files to draw (" + curve_formats() + "), each a layer");
    app->add_option("--scalp", args->scalp, "Scalp to draw under the curves: a mesh (" + mesh_formats() + ") or a .vdb from `groom scalp`");
    app->add_option("--scalp-group", args->scalp_group, "When --scalp is an OBJ mesh: draw only the faces of this object ('o') or group ('g')");
    app->add_option("--scalp-grid", args->scalp_grid,
                    "When --scalp is a .vdb: the grid to draw (default: the grid named 'scalp', else the file's only float level set)");
    app->add_option("-o,--output", args->output, "Output picture (.png)")->required();
    auto* view = app->add_option("--view", args->view, "front|back|left|right|top|three-quarter (default front)");
    auto* views = app->add_option("--views", args->views, "Several views on one labelled sheet, e.g. front,left,top");
    auto* camera = app->add_option("--camera", args->camera, "Explicit camera: eye_x,eye_y,eye_z,target_x,target_y,target_z");
    app->add_option("--up", args->up, "Camera up vector with --camera (default 0,1,0)")->needs(camera);
    app->add_option("--fov", args->fov, "Perspective vertical field of view with --camera, degrees in (0, 170); omitted = orthographic, framed to fit")
        ->needs(camera);
    view->excludes(views)->excludes(camera);
    views->excludes(camera);
    app->add_option("--size", args->size, "Pixels of one view, WxH (or N for NxN)")->capture_default_str();
    app->add_option("--supersample", args->params.supersample, "Samples per pixel along each axis (anti-aliasing), [1, 4]")
        ->capture_default_str();
    app->add_option("--color-by", args->color_by, "Colour curves by none|strand|guide|shape|kind|id|file")->capture_default_str();
    app->add_option("--color", args->color, "Curve colour R,G,B in [0, 1] (with --color-by none)");
    app->add_option("--scalp-color", args->scalp_color, "Mesh colour R,G,B in [0, 1]");
    app->add_option("--background", args->background, "Background colour R,G,B in [0, 1]");
    app->add_option("--width-scale", args->params.width_scale, "Multiplies the curves' width attribute (scene units -> pixels)")
        ->capture_default_str();
    app->add_option("--min-width", args->params.min_width_px, "Thinnest curve drawn, pixels, [0.25, 64]")->capture_default_str();
    app->add_option("--line-width", args->params.default_width_px, "Width of curves without a width attribute, pixels")
        ->capture_default_str();
    app->add_option("--margin", args->params.margin, "Border when framing to fit, fraction of the picture, [0, 0.45]")
        ->capture_default_str();
    add_prim_option(app, *ctx.common);
    const CommonOptions& common = *ctx.common;
    ctx.run = [args, camera, &common] {
        Args& a = *args;
        if (a.inputs.empty() && a.scalp.empty()) throw InvalidParam("render: nothing to draw: give curve FILES and/or --scalp MESH");
        if (!ends_with(a.output, ".png") && !written_in_place(a.output)) throw InvalidParam("render: -o must name a .png file (got '" + a.output + "')");
        for (const std::string& in : a.inputs) check_output(a.output, {in}, common);
        check_output(a.output, {a.scalp}, common);
        parse_size(a.size, a.params.width, a.params.height);
        a.params.color_by = parse_color_by(a.color_by);
        if (!a.color.empty()) a.params.color = parse_float3("--color", a.color);
        if (!a.scalp_color.empty()) a.params.scalp_color = parse_float3("--scalp-color", a.scalp_color);
        if (!a.background.empty()) a.params.background = parse_float3("--background", a.background);
        a.params.validate();

        std::vector<View> sheet;
        Camera cam = view_camera(View::Front);
        if (!a.views.empty()) sheet = parse_views(a.views);
        else if (!a.view.empty()) cam = view_camera(parse_view(a.view));
        else if (camera->count() > 0) {
            const std::vector<float> v = parse_floats("--camera", a.camera, 6, 6);
            cam.eye = {v[0], v[1], v[2]};
            cam.target = {v[3], v[4], v[5]};
            if (!a.up.empty()) {
                const std::vector<float> u = parse_floats("--up", a.up, 3, 3);
                cam.up = {u[0], u[1], u[2]};
            }
            cam.fov_degrees = a.fov;
            cam.validate();
        }

        const auto start = std::chrono::steady_clock::now();
        std::vector<CurveSet> layers;
        layers.reserve(a.inputs.size());
        size_t curves = 0, points = 0;
        for (const std::string& in : a.inputs) {
            layers.push_back(read_curve_input(in, common));
            curves += layers.back().num_curves();
            points += layers.back().num_points();
            if (!has_color_attribute(layers.back(), a.params.color_by)) {
                note(common, "render: " + in + " has no '" + std::string(color_by_name(a.params.color_by)) +
                                 "' attribute; its curves are drawn in --color");
            }
        }
        std::optional<PolygonSoup> mesh;
        // A mesh is drawn as it is; a .vdb as its scalp's mesh: the repaired mesh `groom scalp` stored
        // in it, else (another program's file) the surface extracted from its level set.
        ScalpBuildParams scalp_params;
        scalp_params.group = a.scalp_group;  // a .vdb with a group is refused by load_scalp
        scalp_params.grid = a.scalp_grid;    // and a mesh with a grid
        if (!a.scalp.empty()) {
            mesh = ends_with(a.scalp, ".vdb") || !a.scalp_grid.empty() ? load_scalp(a.scalp, scalp_params)->mesh() : read_mesh(a.scalp, a.scalp_group);
        }
        RenderScene scene;
        for (const CurveSet& c : layers) scene.curves.push_back(&c);
        if (mesh) scene.mesh = &*mesh;

        auto progress = make_progress(common);
        const RgbImage image = sheet.empty() ? render(scene, cam, a.params, progress.get())
                                             : render_sheet(scene, sheet, a.params, progress.get());
        write_png(image, a.output);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char line[256];
        std::snprintf(line, sizeof line, "render: %zu curves, %zu points, %zu mesh faces, %dx%d, %.2f s -> ", curves, points,
                      mesh ? mesh->num_faces() : size_t(0), image.width, image.height, secs);
        note(common, line + a.output);
    };
}

const Registrar reg({"render", "Draw curves (and a scalp mesh) into a PNG preview, no GPU needed", 600, setup});

}  // namespace
}  // namespace groom::cli
