// section_map: how `groom sections` cuts the haired scalp into sections (see ops/sections.h for the
// layouts). A chart maps each direction from the hairline's centroid to two angles (s, t); a point of
// the scalp is charted by its direction. s is cut into equal bands, each band into cells of equal
// area along t. The areas come from an image of the chart: a fine (s, t) grid whose every sample is
// a ray from the centroid onto the scalp (the outermost surface), weighted by the area element
//     dA = r^2 / cos(alpha) * J(s, t) ds dt,
// r the ray's length to the scalp, alpha the angle between the ray and the scalp normal there, J the
// chart's solid angle per unit ds dt. The map answers which section a point lies in, how far it is
// from its section's border, and where the border lines run (for the partings).
#pragma once

#include "fields/point_index.h"
#include "fields/surface.h"
#include "ops/hair_region.h"
#include "ops/sections.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace groom {

class SectionMap {
public:
    /// Charts `scalp` inside `region` (which must have a hairline) and cuts it as params says
    /// (layout, counts, up, forward, crown). Parallel over image rows; the result does not depend on
    /// the thread count. Throws InvalidGeometry as sections() documents.
    /// @param hairline  the curve `region` was made from (its points set the chart's extent).
    SectionMap(const Surface& scalp, const CurveSet& hairline, const HairRegion& region, const SectionsParams& params,
               Progress* progress = nullptr);

    size_t num_sections() const { return sections_.size(); }
    int num_bands() const { return bands_; }
    const std::vector<SectionInfo>& sections() const { return sections_; }
    int64_t rays() const { return rays_; }
    /// Mean distance from the centroid to the haired scalp, scene units.
    float mean_radius() const { return mean_r_; }

    /// The section p lies in (p on or near the scalp), or -1 outside the hairline.
    int section_of(const float3& p) const;
    /// How far p lies inside its section `section` (scene units, along the scalp, approximate): the
    /// least distance to a border with a parting or to the hairline; negative when p is outside it.
    float margin(const float3& p, int section) const;

    /// Distance from p to the hairline curve, scene units: positive inside it, negative outside.
    float hairline_distance(const float3& p) const;

    /// Where the ray from the centroid along `dir` (unit) meets the scalp (the outermost surface).
    /// Throws InvalidGeometry when it does not.
    float3 hit(const float3& dir) const;

    /// One border line, as points on the scalp spaced about `spacing` apart (waypoints for a
    /// parting), running out past the hairline by `overshoot` (scene units) where it crosses it.
    struct Border {
        std::vector<float3> points;
        int kind = 0;  ///< 0 between bands b-1 and b, 1 between two cells of band b
        int band = 0;
    };
    std::vector<Border> borders(float spacing, float overshoot) const;

    /// Points on the scalp along the middle of section `section`'s band from where the section starts
    /// to where it ends along t (front to back), at least `inset` inside its ends, about `spacing`
    /// apart; empty when the band's middle misses the section. Grid and rows only.
    std::vector<float3> midline(int section, float inset, float spacing) const;

private:
    struct Param {
        double s = 0.0, t = 0.0;
    };
    Param to_param(const float3& dir) const;
    float3 to_dir(double s, double t) const;
    /// Solid angle per unit ds dt at (s, t).
    double jacobian(double s, double t) const;
    /// Scene units per unit s and per unit t at (s, t), at distance r from the centroid.
    double s_scale(double s, double t, double r) const;
    double t_scale(double s, double t, double r) const;
    double hairline_theta(double phi) const;  // radial: the hairline's polar angle at azimuth phi
    int band_of(double s) const;
    int cell_of(int band, double t) const;
    bool inside(double s, double t) const;
    /// Traces the parameter line at(lambda), lambda in [lo, hi], into runs inside the hairline.
    template <class At>
    void trace(At at, double lo, double hi, double unit_length, bool closed, float spacing, float overshoot, int kind, int band,
               std::vector<Border>& out) const;

    const Surface& scalp_;
    const HairRegion& region_;
    SectionLayout layout_;
    float3 c_{};                        ///< the chart's centre: the hairline's centroid
    float3 up_{}, fwd_{}, side_{}, back_{};  ///< grid/rows frame (side = up x forward)
    float3 pole_{}, e1_{}, e2_{};       ///< radial frame
    std::vector<double> phi_, theta_;   ///< radial: the hairline's (azimuth, polar angle), by azimuth
    std::vector<float3> hairline_;      ///< the closed hairline's points
    std::shared_ptr<const PointIndex> hairline_index_;
    float reach_ = 0.0f;                ///< rays start this far from the centre
    float mean_r_ = 0.0f;
    double s0_ = 0.0;                   ///< the chart's s starts here
    std::vector<double> edges_;         ///< band b covers s in [edges[b], edges[b+1])
    int bands_ = 0;
    double grid_target_ = 0.0;          ///< grid: the area each cell aims at
    std::vector<std::vector<double>> cuts_;  ///< per band: t where one cell ends and the next begins, increasing
    std::vector<int> first_;            ///< per band: index of its first section
    std::vector<SectionInfo> sections_;
    int64_t rays_ = 0;
};

}  // namespace groom
