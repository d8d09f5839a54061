// root_uv: each root's texture coordinate on the scalp, for renderers' texture lookups (USD's
// primvars:st) and engine importers. One helper every op that grows hair from the scalp calls last.
#pragma once

#include "fields/surface.h"
#include "kernel/curve_set.h"

namespace groom {

/// @brief When `scalp` has texture coordinates (Surface::has_uvs: a scalp mesh with UVs, or the
/// .vdb `groom scalp` made from one), writes curve attribute `root_uv`, float3 (u, v, 0) (Houdini's
/// uv layout; the .usda writer adds texCoord2f primvars:st), the UV at the point of the mesh closest
/// to each curve's first point; a curve without points gets (0, 0, 0). Otherwise changes nothing.
/// Reads point P. Deterministic for any thread count.
void add_root_uvs(CurveSet& curves, const Surface& scalp);

}  // namespace groom
