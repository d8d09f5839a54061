// The options every command with --scalp shares for converting a mesh on the fly, so each command
// spells them the same way as `groom scalp` (--voxel, --band, --flip there; --scalp-* here).
#pragma once

#include "fields/scalp_field.h"

#include <CLI/CLI.hpp>

namespace groom::cli {

/// Adds --scalp-voxel, --scalp-band, --scalp-flip and --scalp-group, which only matter when --scalp is a mesh
/// (a .vdb from `groom scalp` is used as it is), and --scalp-grid, which picks a .vdb's grid.
void add_scalp_build_options(CLI::App* app, ScalpBuildParams& params);

}  // namespace groom::cli
