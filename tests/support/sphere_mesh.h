// Analytic test meshes: triangulated spheres and spherical caps whose exact surface is known, so
// tests of the scalp field (and of every op that takes a scalp) can compare against AnalyticSphere.
// Faces are wound counter-clockwise seen from outside (normals point away from the centre).
#pragma once

#include "kernel/polygon_soup.h"
#include "kernel/math/vec.h"

namespace groom {

/// Latitude-longitude sphere: `rings` >= 2 latitude bands, `segments` >= 3 longitude slices. Poles
/// are single vertices (triangle fans); other bands are quads split into two triangles each.
/// Vertices lie exactly on the sphere. Throws InvalidParam for radius <= 0 or too few rings/segments.
PolygonSoup uv_sphere(const float3& center, float radius, int rings, int segments);

/// Geodesic sphere: an icosahedron subdivided `subdivisions` times (0..8), each new vertex pushed
/// onto the sphere: 20 * 4^subdivisions triangles. Throws InvalidParam.
PolygonSoup icosphere(const float3& center, float radius, int subdivisions);

/// Open spherical cap around the axis `axis` (unit, the cap's pole direction): the part of the sphere
/// within `half_angle_deg` (0 < a < 180) of the pole, `rings` bands by `segments` slices. Its
/// boundary is the circle at the cap's rim. Throws InvalidParam.
PolygonSoup sphere_cap(const float3& center, float radius, const float3& axis, float half_angle_deg, int rings, int segments);

/// Largest distance between the flat triangles of `soup` and the sphere its vertices lie on: the
/// chordal (sagitta) error, radius - min over faces of the distance from the centre to the face's
/// plane-clipped disc. Tests subtract it from what a scalp field built from the mesh can achieve.
float sphere_chordal_error(const PolygonSoup& soup, const float3& center, float radius);

/// `clean` (uv_sphere(center, R, rings, segments), rings >= 11) as a user might bring it: band 3 as
/// quads, a hexagon in band 5, a hole of two faces in band 8, every third face with its own copies
/// of its vertices (split seams), every seventh flipped, two degenerate triangles, a non-manifold
/// fin reaching inside, and a small closed sphere inside (an eye in a head).
PolygonSoup messy_uv_sphere(const PolygonSoup& clean, int rings, int segments, const float3& center, float R);

/// Lat-long sphere of radius R about the origin, Y up: ring r at theta = pi r / rings from +Y,
/// slice s at phi = 2 pi s / segments in the XZ plane (x = sin theta cos phi, z = sin theta sin phi).
/// Face-varying UVs u = s / segments, v = 1 - r / rings: the seam at phi = 0 has u = 0 on the faces
/// after it and u = 1 on the faces before it; a pole's corner takes the middle of its slice.
PolygonSoup latlong_uv_sphere(float R, int rings, int segments);

}  // namespace groom
