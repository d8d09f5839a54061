// The options every command that places roots shares for where hair grows (ops/hair_region.h):
// --hairline, --parting, --parting-gap, --up, spelled and read the same way by each.
#pragma once

#include "fields/surface.h"
#include "ops/hair_region.h"
#include "ops/hairline.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace groom::cli {

struct RegionOptions {
    std::string hairline, parting, up = "0,1,0";
    HairRegionParams params;
    bool given() const { return !hairline.empty() || !parting.empty(); }
    /// The files the region reads (for output-onto-input checks).
    std::vector<std::string> inputs() const { return {hairline, parting}; }
};

void add_region_options(CLI::App* app, RegionOptions& o);

struct CommonOptions;

/// Reads a --hairline file, every command the same way: a closed curve in any of its forms (USD
/// `wrap = "periodic"`, a record or chain back to its first point, an OBJ or PLY loop of edges as
/// Blender writes one) is the same hairline as the open one (check_hairline drops the repeated
/// point). Only here is a loop of edges a curve: hairs and guides are open. `common`: the reader's
/// warnings go through warn(); null = dropped. Throws ParseError / IoError naming the file.
CurveSet read_hairline(const std::string& path, const CommonOptions* common = nullptr);

/// make_hairline on the scalp, with what it reports (an axis moved to the head's middle, a head that
/// seems to face away from `forward`) printed as `command`'s notes and warnings: `groom hairline`,
/// and the commands that make the default hairline when given no --hairline (edges, sections, gather).
CurveSet reported_hairline(const std::string& command, const Surface& scalp, const Bounds3& bounds, const HairlineParams& params,
                           const CommonOptions& common);

/// A --hairline must be one (check_hairline, named by `file`) and lie on the scalp: one whose points lie a median of more than 0.15 of its half
/// width off it (another head's, or one in other units) throws InvalidGeometry naming `file` (it
/// had laid rows 6 from their hairline on a head 8 across, and fitted a cranium to nothing: a
/// hostile trial).
void check_hairline_on_scalp(const std::string& file, const CurveSet& hairline, const Surface& scalp);

/// A --hairline runs higher over the forehead than at the nape. When the given one's part ahead of
/// its centroid along `forward` lies lower than its part behind, the face probably looks the other
/// way: warn, as `command`, naming `file` and the --forward that would fit (a trial: baby hairs on
/// the back of the ponytail head, which faces -Z, with no word, while the same command without
/// --hairline, making the default one, said the head seemed to face away).
void warn_if_hairline_faces_away(const std::string& command, const std::string& file, const CurveSet& hairline, const float3& up,
                                 const float3& forward, const CommonOptions& common);

/// The region the options describe, or null when neither --hairline nor --parting is given.
/// `hairline_at_hand`: the hairline to use instead of reading --hairline: the one the caller has
/// already read from it (cornrow-guides checks it first), or the default one when none is given
/// (gather). Throws InvalidParam / InvalidGeometry naming the option or file.
std::unique_ptr<HairRegion> make_region(const RegionOptions& o, const Surface& scalp, const CurveSet* hairline_at_hand = nullptr);

}  // namespace groom::cli
