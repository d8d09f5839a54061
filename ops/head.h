// The demo's default head: a synthetic, closed, plausible human head and neck that the project
// generates itself (no scan, no licence), so the demo and tests run on a fresh clone with nothing
// downloaded. Built as a smooth signed-distance blend of ellipsoids (cranium, face and jaw, brow,
// nose, lips, chin, ears) and a neck, then sampled as a star-shaped surface around a point inside
// the head: each vertex of a latitude-longitude sphere is pushed out along its direction to the
// outermost zero of the distance (bisection), so the mesh is closed and genus 0 by construction.
//
// Frame: +Y up, the face looks along +Z, centimetres at scale 1. The cranium spans about
// y = -2 .. 12 above the ears (top at y = 12), the chin is near y = -11.7, the neck is cut flat at y = -22.
#pragma once

#include "kernel/polygon_soup.h"

namespace groom {

struct HeadParams {
    int resolution = 64;   ///< latitude bands (longitudes: twice as many); [8, 1024]
    float scale = 1.0f;    ///< multiplies every coordinate (1 = centimetres, 0.01 = metres); > 0
    bool ears = true;      ///< add ears (they are blended bumps: a star-shaped surface cannot fold behind them)
    void validate() const; ///< throws InvalidParam naming the option, value and range
};

/// Approximate signed distance (centimetres, negative inside) to the unscaled head; a lower bound
/// of the true distance within a factor of about 1.5 near the surface. Exposed for tests.
float head_distance(const float3& p, bool ears = true);

/// The head as quads (triangles at the two poles, the crown and the neck's base), outward facing
/// (counter-clockwise seen from outside), no duplicate vertices. Throws InvalidParam.
PolygonSoup make_head(const HeadParams& params);

}  // namespace groom
