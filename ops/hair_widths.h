// hair widths: the per-point `width` (fibre diameter) every op that makes hairs writes, tapered
// linearly in arc length from a root width to a tip width. One helper so every op spells the
// options, the defaults and the taper the same way (--root-width, --tip-width).
#pragma once

#include "kernel/curve_set.h"

#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace groom {

/// Default root and tip diameters of a human hair, in centimetres (the units of our heads). A scalp
/// hair is 0.005-0.01 cm across (50-100 um); 0.008 cm is a typical root. The tip is half of it: cut
/// hair ends blunt and uncut hair thins to a point over its last centimetres, so a linear taper to a
/// half gives the thinning renderers show without tips that vanish below a pixel.
inline constexpr float kDefaultRootWidthCm = 0.008f;
inline constexpr float kDefaultTipWidthCm = 0.004f;

/// The widths asked for. Unset root and tip: keep the width the curves already carry (an input's
/// widths, interpolated by the op), else the defaults. Either set: the whole taper is rewritten
/// (an unset end takes its default).
struct HairWidths {
    std::optional<float> root;  ///< diameter at the root, scene units; finite, > 0 (--root-width)
    std::optional<float> tip;   ///< diameter at the tip, scene units; finite, >= 0 (--tip-width)

    bool given() const { return root.has_value() || tip.has_value(); }
    /// Both ends set: the given ones, the others the defaults times units_per_cm.
    HairWidths resolved(float units_per_cm = 1.0f) const;
    /// Throws InvalidParam "<op>: --root-width must be ... (got ...)".
    void validate(std::string_view op) const;
};

/// Writes point `width` on every point: w = (1 - t) root + t tip, t the point's fraction of its
/// curve's arc length (of its point index when the curve has no length), so the root point gets
/// `root` and the tip point `tip` exactly and widths change monotonically in between.
void taper_widths(CurveSet& curves, float root, float tip);

/// taper_widths() on one curve: its points P and their widths W (same size). `scratch` is kept by
/// the caller from curve to curve. An op that writes its curves one at a time tapers each while its
/// points are still in cache (curl: a second pass over a whole output was 5% of the op, perf).
void taper_curve_widths(std::span<const float3> P, std::span<float> W, float root, float tip, std::vector<double>& scratch);

/// The taper apply_hair_widths() would write on an op's output whose point and curve `width`
/// columns are those of `input` (the op carries them): widths.resolved(units_per_cm) when it
/// tapers, nothing when it keeps the carried widths.
std::optional<HairWidths> hair_widths_taper(const CurveSet& input, const HairWidths& widths, float units_per_cm = 1.0f);

/// The last step of an op that makes hairs: when `widths` is given, or the curves carry no float
/// point `width`, writes the taper of widths.resolved(units_per_cm); otherwise leaves the carried
/// widths as they are.
void apply_hair_widths(CurveSet& curves, const HairWidths& widths, float units_per_cm = 1.0f);

}  // namespace groom
