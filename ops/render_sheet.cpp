// The contact sheet: several named views side by side at one scale, each labelled. Apart from the
// rasteriser because it only lays out pictures that render() draws.
#include "ops/render_impl.h"

#include <algorithm>
#include <cstring>

namespace groom {

using namespace render_detail;

RgbImage render_sheet(const RenderScene& scene, std::span<const View> views, const RenderParams& params, Progress* progress)
{
    if (views.empty()) throw InvalidParam("render: `views` needs at least one view");
    params.validate();
    if (int64_t(params.width) * int64_t(views.size()) > kMaxSide) {
        throw InvalidParam("render: a sheet of " + std::to_string(views.size()) + " views of width " + std::to_string(params.width) +
                           " is wider than " + std::to_string(kMaxSide) + " pixels; lower `size`");
    }
    const float aspect = float(params.width) / float(params.height);
    // One scale for every view, so sizes compare across the sheet.
    std::vector<Camera> cams;
    float height = 0.0f;
    for (View v : views) {
        cams.push_back(frame_camera(scene, view_camera(v), aspect, params.margin));
        height = std::max(height, cams.back().ortho_height);
    }
    RgbImage sheet(params.width * int(views.size()), params.height);
    const int scale = std::max(2, params.height / 200);
    for (size_t i = 0; i < views.size(); ++i) {
        cams[i].ortho_height = height;
        RgbImage one = render(scene, cams[i], params, progress);
        draw_label(one, 4 * scale, 4 * scale, view_name(views[i]), scale, float3(0.25f, 0.25f, 0.28f));
        for (int y = 0; y < params.height; ++y) {
            std::memcpy(sheet.at(int(i) * params.width, y), one.at(0, y), size_t(params.width) * 3u);
            if (i > 0) std::memset(sheet.at(int(i) * params.width, y), 200, 3);  // a thin divider
        }
    }
    return sheet;
}

}  // namespace groom
