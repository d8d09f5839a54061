// gather: the whole scalp's hair pulled into puffs (Izzy's look: talk, Sec. 3.2, as the film shows
// it). Every root inside the hairline that is not under a puff's own base grows a hair that lies on
// the scalp, within its clearance, along the path on the scalp to the nearest puff in its section
// (partings bound the sections), passes under that puff's band at the base and goes on up into the
// puff along its sphere guides, curled like the puff's own hairs. The bands (hair ties) are emitted as
// their own curves. Run after `groom puff`, whose guides and base it reads.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"
#include "kernel/progress.h"
#include "ops/curl.h"
#include "ops/generate.h"
#include "ops/hair_region.h"

#include <cstdint>
#include <vector>

namespace groom {

/// One puff the hair is gathered into: what `groom puff` wrote (its guides and the detail attributes
/// puff_base, puff_radius, puff_sphere_center, puff_sphere_radius).
struct GatherPuff {
    CurveSet guides;          ///< the puff's sphere guides, root to tip (kind 0 of `groom puff`)
    float3 base{};            ///< centre of the puff's root region, on the scalp
    float base_radius = 0.0f; ///< radius of that region, scene units, > 0
    float3 sphere_center{};
    float sphere_radius = 0.0f;
    /// The cap its guides' tips cover, degrees (detail `puff_cap_angle`); 0 for a puff written
    /// without it: each hair's tip then goes onto the sphere straight out from its centre.
    float cap_angle = 0.0f;
};

struct GatherParams {
    int64_t hairs = 20000;  ///< roots over the whole haired region outside the puffs' bases, >= 1 (--hairs)
    /// Height of the gathered hair above the scalp, scene units: each hair lies at its own height in
    /// [lift/4, lift] (a layer, not one sheet), rising to it within `step` of its root; > 0 (--lift).
    float lift = 0.08f;
    float step = 0.25f;     ///< spacing of a hair's points along the scalp, scene units, > 0 (--step)
    int hair_points = 24;   ///< points of a hair's part inside the puff before curling, >= 4 (--hair-points)
    int neighbours = 4;     ///< puff guides blended for that part (--neighbours), >= 1
    float power = 2.0f;     ///< inverse-distance exponent of that blend (--power), > 0
    /// The band at each puff's base: rings around the base circle, from `lift` up to lift + band_width
    /// above the scalp (--band-width, > 0), band_strands curves (--band-strands, 0 = no band) each
    /// band_thickness wide (--band-thickness, > 0).
    float band_width = 0.8f;
    int band_strands = 12;
    float band_thickness = 0.12f;
    /// The curl of the part in the puff (every `groom curl` option; curl.seed also seeds the roots).
    CurlParams curl;
    int64_t first_id = 0;   ///< hair ids first_id.., then band ids (--first-id), >= 0
    void validate() const;  ///< throws InvalidParam naming the option
};

struct GatherResult {
    /// P, point `width` (curl.widths, tapered over the whole hair), curve `id`, `kind` = 1, `puff`
    /// (index into the puffs), point `flat` (1 on the scalp part)
    CurveSet hairs;
    CurveSet bands;   ///< P, `width`, curve `id`, `kind` = 2, `puff`
    int64_t roots_without_puff = 0;  ///< sections of the scalp with no puff in them: no hair there
};

/// @brief Gathers the hair of `region` into `puffs`.
///
/// Roots: area-uniform on the scalp (`sample`, asked in rounds with fresh seeds until params.hairs
/// are found), kept when region.haired() and outside every puff's base disc. Each root goes to the
/// puff in its own section (region.section() equal at the root and at the puff's base) whose base
/// circle is nearest; a root whose section holds no puff grows no hair (counted).
/// The flat part: surface_path() from the root to the point of the base circle toward the root, at
/// height h = lift (1 + 3u)/4 (u uniform per hair), eased in from 0 over the first `step`.
/// The puff part: from that point (on the scalp), a centreline blended from the puff's guides
/// (generate_at_roots), its tip warped onto the sphere as `puff` does, kept outside the scalp, curled
/// by curl() (its root ramp makes the join continuous), then shifted up by h fading to 0 over its
/// first third, so it starts where the flat part ends.
/// Deterministic: Rng(curl.seed, ...) per round and per hair id; any thread count gives the same.
/// Throws InvalidParam (params), InvalidGeometry (no puff, a puff without guides), LimitExceeded
/// (the region holds no root after 64 rounds).
GatherResult gather(const Surface& scalp, const RootSampler& sample, const std::vector<GatherPuff>& puffs, const HairRegion& region,
                    const GatherParams& params, Progress* progress = nullptr);

}  // namespace groom
