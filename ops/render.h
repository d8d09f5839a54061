// Preview pictures of grooms without a GPU or a display: a small CPU rasteriser that draws a scalp
// mesh (smooth-shaded, headlight + key light + ambient) and curves as anti-aliased tubes, both
// through one z-buffer, so curves are hidden by the head and by each other. Anti-aliasing is by
// supersampling (S x S samples per pixel, box-filtered down). Work is split into screen tiles that
// are drawn in parallel; within a tile items are drawn in input order with a strict depth test, so
// the picture is bitwise identical for any thread count.
#pragma once

#include "kernel/curve_set.h"
#include "kernel/polygon_soup.h"
#include "kernel/image.h"
#include "kernel/progress.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace groom {

/// Named views of a head that looks along +Z with +Y up (the convention of `groom head`).
/// front: eye on +Z; back: eye on -Z; left: eye on +X (the subject's left side); right: eye on -X;
/// top: eye on +Y with the face at the top of the picture; three-quarter: front-left, slightly above.
enum class View { Front, Back, Left, Right, Top, ThreeQuarter };

/// The view's name as `groom render --view` spells it (cli/render_options.h parses it).
std::string_view view_name(View view);

/// A pinhole or orthographic camera. Scene units throughout.
struct Camera {
    float3 eye{0.0f, 0.0f, 10.0f};
    float3 target{0.0f, 0.0f, 0.0f};
    float3 up{0.0f, 1.0f, 0.0f};   ///< if parallel to the view direction another axis is used
    float fov_degrees = 0.0f;      ///< 0: orthographic; else the vertical field of view, in (0, 170) degrees
    float ortho_height = 0.0f;     ///< orthographic only: scene units the picture height spans; 0 = fit everything drawn
    /// Throws InvalidParam: non-finite values, eye == target, fov outside {0} U (0, 170), ortho_height < 0.
    void validate() const;
};

/// The orthographic camera of a named view (direction only: ortho_height 0, so `render` frames it).
Camera view_camera(View view);

/// What gives curves their colour. Attributes are looked up on the point domain first, then on
/// the curve domain (int32, int64 or float); a value v gets `categorical_color(v)`.
enum class ColorBy { None, Strand, Guide, Shape, Kind, Id, File };
std::string_view color_by_name(ColorBy c);  ///< "none|strand|guide|shape|kind|id|file" (parsed in cli/render_options.h)

/// A stable categorical colour for an integer value: hues spaced by the golden ratio, so
/// consecutive values (strands 0, 1, 2; neighbouring guides) are always far apart. Components in [0, 1].
float3 categorical_color(int64_t value);

struct RenderParams {
    int width = 1024, height = 1024;  ///< pixels of one view, each in [1, 16384]
    int supersample = 3;              ///< samples per pixel along each axis, in [1, 4]
    ColorBy color_by = ColorBy::None;
    float3 color{0.20f, 0.12f, 0.07f};         ///< curves when color_by is None (or the attribute is absent); [0, 1]
    float3 scalp_color{0.60f, 0.42f, 0.32f};   ///< mesh albedo; [0, 1]
    float3 background{0.94f, 0.94f, 0.95f};    ///< [0, 1]
    float width_scale = 1.0f;       ///< multiplies curve widths (the point attribute `width`, a diameter in scene units); > 0
    float min_width_px = 1.0f;      ///< no curve is drawn thinner than this many pixels; [0.25, 64]
    float default_width_px = 1.5f;  ///< width of curves without a `width` attribute, pixels (times width_scale); (0, 256]
    float margin = 0.05f;           ///< orthographic auto-framing border, fraction of the picture per side; [0, 0.45]
    /// Throws InvalidParam naming the option (as the CLI spells it), the value and the valid range.
    void validate() const;
};

/// What is drawn. Nothing is owned; each CurveSet is one layer (one input file).
struct RenderScene {
    std::vector<const CurveSet*> curves;
    const PolygonSoup* mesh = nullptr;  ///< n-gons are drawn as triangle fans
};

/// True when `curves` has the attribute `color_by` reads (always true for None, Id and File).
bool has_color_attribute(const CurveSet& curves, ColorBy color_by);

/// The camera actually used for `camera` on `scene`: an orthographic camera with ortho_height 0 is
/// re-centred (in its image plane) and sized so everything drawn fits with `margin` on each side.
/// Other cameras come back unchanged. Throws InvalidParam (camera.validate()).
Camera frame_camera(const RenderScene& scene, const Camera& camera, float aspect, float margin);

/// Renders one view of params.width x params.height pixels.
/// Reads point P and width, and the colour attribute chosen by params.color_by.
/// Throws InvalidParam (params, camera), LimitExceeded (more than 2^32 - 1 curve points in all).
RgbImage render(const RenderScene& scene, const Camera& camera, const RenderParams& params, Progress* progress = nullptr);

/// Several named views side by side on one sheet ((views.size() * width) x height), each labelled
/// with its name, all at the same scale (the largest framing any view needs).
/// Throws InvalidParam (no views, params).
RgbImage render_sheet(const RenderScene& scene, std::span<const View> views, const RenderParams& params, Progress* progress = nullptr);

/// Draws `text` (A-Z, 0-9, space and - . : , /; lower case is drawn upper case) with a 5x7 pixel font
/// scaled by `scale`, top-left corner at (x, y), clipped to the image.
void draw_label(RgbImage& image, int x, int y, std::string_view text, int scale, const float3& color);

}  // namespace groom
