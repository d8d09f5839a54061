// The words of `groom render` (--view, --views, --color-by) turned into the renderer's enums. In cli/
// because only the command line parses user text; ops/render.h keeps view_name / color_by_name.
#pragma once

#include "ops/render.h"

#include <string_view>

namespace groom::cli {

/// Parses "front", "back", "left", "right", "top", "three-quarter" (also "side" = left).
/// Throws InvalidParam listing the valid names.
View parse_view(std::string_view name);

ColorBy parse_color_by(std::string_view name);  ///< "none|strand|guide|shape|kind|id|file"; throws InvalidParam

}  // namespace groom::cli
