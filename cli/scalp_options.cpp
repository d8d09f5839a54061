#include "cli/scalp_options.h"

#include <cmath>
#include <string>

namespace groom::cli {

void add_scalp_build_options(CLI::App* app, ScalpBuildParams& params)
{
    app->add_option("--scalp-voxel", params.voxel_size,
                    "When --scalp is a mesh: voxel size of its field, scene units (0 = bounding-box diagonal / 256)")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                double v = 0.0;
                if (!CLI::detail::lexical_cast(text, v) || !(v >= 0.0) || !std::isfinite(v)) {
                    return "expected a voxel size >= 0 in scene units (0 = automatic), got " + text;
                }
                return {};
            },
            "SIZE"))
        ->capture_default_str();
    app->add_option("--scalp-band", params.band_voxels, "When --scalp is a mesh: narrow-band half width in voxels (1..64)")
        ->check(CLI::Range(1.0f, 64.0f))
        ->capture_default_str();
    app->add_flag("--scalp-flip", params.flip, "When --scalp is a mesh: it is inside out, swap inside and outside");
    app->add_option("--scalp-group", params.group,
                    "When --scalp is an OBJ mesh: only the faces of this object ('o') or group ('g'), e.g. the head without eyes and teeth");
    app->add_option("--scalp-grid", params.grid,
                    "When --scalp is a .vdb: the grid to use (default: the grid named 'scalp', else the file's only float level set)");
}

}  // namespace groom::cli
