// sections: the haired scalp (inside a hairline) parted into sections, one braid, twist or knot per
// section, as box braids, two-strand twists and bantu knots are laid out (a grid of roughly square
// cells), fulani-style braids (rows front to back with a centre row) and crown-centred styles (wedges
// around the crown). Writes one guide per section for `groom braid` (or `groom curl`), the parting
// curves between sections (bare scalp, drawn on it with fields/surface_path.h), and optionally every
// root of each section joined to its guide (the hair that feeds the braid).
//
// How the scalp is cut (ops/section_map.h): directions from the hairline's centroid are charted by
// two angles (s, t); s is cut into equal bands and each band into cells of equal area along t.
//   grid, rows: s = latitude about the ear-to-ear axis (bands run front to back, parallel to the
//               midline, symmetric about it), t = angle front to back over the top. A grid cuts each
//               band into cells as long as the band is wide (square); rows keep each band whole.
//   radial:     s = polar angle from the crown over the hairline's at the same azimuth (rings that
//               follow the hairline), t = azimuth around the crown: wedges.
// Areas come from a fine image of the chart (rays from the centroid onto the scalp, area element
// r^2 / cos(angle to the normal) times the chart's solid angle).
//
// Frame: `up` and `forward` as `groom hairline` (+Y up, the face towards +Z by default).
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/generate.h"

#include <cstdint>
#include <string>
#include <vector>

namespace groom {

enum class SectionLayout {
    Grid,    ///< bands front to back, each cut into square cells (box braids, twists, bantu knots)
    Rows,    ///< bands front to back, whole (fulani-style rows; an odd count has a centre row)
    Radial,  ///< rings around the crown cut into wedges
};

/// How each section's guide runs.
enum class SectionGuide {
    Auto,   ///< Along for rows, Hang otherwise
    Hang,   ///< from the section's root (near its centroid) off the scalp, then down under gravity
    Along,  ///< along the middle of the section front to back, on the scalp, then hanging (cornrows; grid and rows only)
};

/// Parses "grid" / "rows" / "radial" (and the guide names); throws InvalidParam naming `layout` / `guide`.
SectionLayout parse_section_layout(const std::string& name);
SectionGuide parse_section_guide(const std::string& name);

struct SectionsParams {
    SectionLayout layout = SectionLayout::Grid;
    float3 up{0.0f, 1.0f, 0.0f};       ///< the head's up direction (--up)
    float3 forward{0.0f, 0.0f, 1.0f};  ///< the direction the face looks (--forward); not parallel to up

    // --- How many sections. A count left at 0 comes from `size` when that is set, else the layout's default.
    int cols = 0;    ///< grid: bands across the head, ear to ear, [1, 256]; default 8
    /// grid: cells along the middle band front to back, [1, 256] (the others in proportion to their
    /// area); default: as many as make every cell as long as its band is wide.
    /// rows: rows across the head, [1, 256]; default 7 (odd: a centre row on the midline).
    int rows = 0;
    int rings = 0;   ///< radial: rings from the crown to the hairline, [1, 64]; default 1
    int wedges = 0;  ///< radial: wedges in the outermost ring (inner rings in proportion), [1, 256]; default 12
    /// Side of a section, scene units, >= 0; 0 = unset. Sets the counts not given: bands this wide
    /// (rows: rounded to an odd count) and cells this long.
    float size = 0.0f;
    /// radial: the crown the wedges turn around (projected along its direction from the hairline's
    /// centroid); unset (`has_crown` false): straight up from the centroid.
    float3 crown{};
    bool has_crown = false;

    // --- Partings.
    float parting_gap = 0.3f;  ///< bare width along each parting, scene units, > 0 (--parting-gap)
    float step = 0.25f;        ///< spacing of the parting curves' points, scene units, > 0 (--step)

    // --- Guides.
    SectionGuide guide = SectionGuide::Auto;
    /// Length of a guide's free part, scene units, > 0 (--length): all of a hanging guide; the part
    /// of an along guide past the end of its section.
    float length = 30.0f;
    int points = 48;           ///< points over `length`, [4, 100000] (an along guide has more, spaced the same) (--points)
    /// Arc length over which a guide turns through 90 degrees, scene units, > 0 (--bend): how stiff
    /// the braid is where it leaves the scalp.
    float bend = 1.0f;
    /// The direction a free guide falls (gravity), not zero; zero vector = -up (--hang).
    float3 hang{0.0f, 0.0f, 0.0f};
    /// While a guide lies on the scalp it is combed away from the face: its direction along the
    /// scalp is gravity's plus `sweep` times the direction away from a point in front of the face,
    /// both in the tangent plane; >= 0 (--sweep). 0 lets braids at the forehead fall over the face.
    float sweep = 1.5f;
    float clearance = 0.3f;    ///< least distance of a guide from the scalp, scene units, >= 0 (--clearance)
    /// Extra height per section side between a root and the hairline, scene units, >= 0 (--layer):
    /// hanging braids from high sections lie over those from lower ones instead of through them.
    float layer = 0.15f;
    float jitter = 4.0f;       ///< random tilt of each guide's fall, degrees, [0, 45] (--jitter)

    // --- Roots (the hair that feeds each section's braid).
    int64_t roots = 0;         ///< roots over the haired sections, >= 0; 0 = none (--roots)
    int root_points = 4;       ///< points of each root's curve to its guide, [2, 64] (--root-points)
    int64_t first_id = 0;      ///< guide ids are first_id + section; root ids follow them, >= 0 (--first-id)
    uint64_t seed = 0;         ///< jitter and root sampling (--seed)

    /// Throws InvalidParam naming the option, the value and the valid range, e.g.
    /// "sections: `cols` applies to the grid layout only (got 5 with rows)".
    void validate() const;
};

/// One section, as the result lists them (index = the `section` attribute).
struct SectionInfo {
    int band = 0;          ///< band across the head (grid/rows: from the head's right, -X, to its left), or ring from the crown
    int cell = 0;          ///< cell along the band (front to back; radial: around from the nape)
    double area = 0.0;     ///< scene units^2
    float3 centroid{};     ///< area-weighted mean point (off the scalp where it curves)
    float3 root{};         ///< the guide's root: on the scalp, inside the section, at least parting_gap from its partings
};

struct SectionsReport {
    int bands = 0;
    double haired_area = 0.0;   ///< area inside the hairline, scene units^2
    double min_area = 0.0, max_area = 0.0;  ///< smallest and largest section
    int64_t rays = 0;           ///< rays cast to chart the scalp
    int64_t roots_bare = 0;     ///< sampled roots dropped on a parting's bare gap
};

struct SectionsResult {
    /// One per section, in section order: point P; curve `id` (first_id + section), `section`,
    /// `band`, `cell` (int32), `area` (float), `scalp_length` (float: arc length lying along the
    /// scalp, 0 for a hanging guide).
    CurveSet guides;
    /// The partings, on the scalp: point P; curve `id`, `kind` (int32: 0 between bands, 1 between
    /// cells of a band), `band` (int32: the band after the border for kind 0, the band cut for kind 1).
    CurveSet partings;
    /// With params.roots > 0: one curve per root, from the root on the scalp to the nearest point of
    /// its section's guide near the scalp (root_points points, kept outside the scalp but for the
    /// root): point P; curve `id`, `section`.
    CurveSet roots;
    std::vector<SectionInfo> sections;
    SectionsReport report;
};

/// @brief Parts the scalp inside `hairline` into sections and makes their guides and partings.
/// @param hairline  one closed curve around the head (`groom hairline`; see ops/hair_region.h for
///                  what is accepted); required.
/// @param sample    area-uniform scalp sampler, used only when params.roots > 0 (may be null otherwise).
/// Deterministic: the same inputs give the same output for any thread count.
/// Throws InvalidParam (params, or roots asked for without a sampler), InvalidGeometry (no hairline,
/// a hairline that does not go once around the head or the crown, a ray from the hairline's centroid
/// that finds no scalp).
SectionsResult sections(const Surface& scalp, const CurveSet& hairline, const RootSampler* sample, const SectionsParams& params,
                        Progress* progress = nullptr);

}  // namespace groom
