// The largest length an op takes, scene units. Past it points land so far out that their squared
// distances overflow float, and the NaN that follows reached the scalp queries, which could only
// say "a non-finite point" without the option behind it (braid's `width` 3e38 crashed in GMP;
// generate --clearance 1e20 and cornrow-guides --radius 1e20: trials). Ops refuse a length past it
// by name; a scalp 1e15 units across is refused too (fields/), so nothing real is out of reach.
#pragma once

namespace groom {

inline constexpr float kMaxSceneLength = 1e15f;

}  // namespace groom
