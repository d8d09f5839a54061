#include "ops/head.h"

#include "kernel/error.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace groom {

namespace {

constexpr float kPi = 3.14159265358979f;

/// Inigo Quilez's ellipsoid distance bound: exact on the surface, a fair estimate near it.
float ellipsoid(const float3& p, const float3& c, const float3& r)
{
    const float3 q = p - c;
    const float k0 = length(float3(q.x / r.x, q.y / r.y, q.z / r.z));
    const float k1 = length(float3(q.x / (r.x * r.x), q.y / (r.y * r.y), q.z / (r.z * r.z)));
    return k1 > 0.0f ? k0 * (k0 - 1.0f) / k1 : -std::min({r.x, r.y, r.z});
}

/// Polynomial smooth minimum: blends two shapes over a fillet of size k (scene units).
float smin(float a, float b, float k)
{
    const float h = std::max(k - std::fabs(a - b), 0.0f) / k;
    return std::min(a, b) - h * h * k * 0.25f;
}
float smax(float a, float b, float k) { return -smin(-a, -b, k); }

/// Vertical cylinder with rounded ends, axis (x0, z0), from y0 to y1, radius r, edge rounding e.
float rounded_cylinder(const float3& p, float x0, float z0, float y0, float y1, float r, float e)
{
    const float dx = std::hypot(p.x - x0, p.z - z0) - (r - e);
    const float dy = std::fabs(p.y - 0.5f * (y0 + y1)) - (0.5f * (y1 - y0) - e);
    return std::min(std::max(dx, dy), 0.0f) + std::hypot(std::max(dx, 0.0f), std::max(dy, 0.0f)) - e;
}

// The vertices are found along rays from this point, inside the skull behind the face.
const float3 kCenter{0.0f, -2.0f, -0.5f};
constexpr float kMaxRadius = 30.0f;  // beyond the neck's base corners (~22 cm away)

}  // namespace

void HeadParams::validate() const
{
    if (resolution < 8 || resolution > 1024) {
        throw InvalidParam("head: `resolution` must be in [8, 1024] (got " + std::to_string(resolution) + ")");
    }
    if (!std::isfinite(scale) || scale <= 0.0f) {
        throw InvalidParam("head: `scale` must be a finite number > 0 (got " + std::to_string(scale) + ")");
    }
}

float head_distance(const float3& p, bool ears)
{
    // Proportions of an adult head in centimetres (breadth ~15, length ~20, crown to chin ~23.5).
    float d = ellipsoid(p, {0.0f, 3.0f, -1.0f}, {7.4f, 9.0f, 9.8f});                 // cranium
    d = smin(d, ellipsoid(p, {0.0f, -4.0f, 2.4f}, {6.3f, 7.3f, 6.5f}), 3.0f);        // face and jaw
    d = smin(d, ellipsoid(p, {0.0f, -6.0f, 0.8f}, {6.4f, 4.4f, 5.8f}), 2.5f);        // jaw angle, cheeks
    d = smin(d, ellipsoid(p, {0.0f, 1.6f, 7.4f}, {5.6f, 1.5f, 2.2f}), 1.2f);         // brow ridge
    d = smax(d, -ellipsoid(p, {-3.0f, 0.0f, 9.3f}, {1.5f, 1.1f, 1.2f}), 0.8f);       // eye sockets
    d = smax(d, -ellipsoid(p, {3.0f, 0.0f, 9.3f}, {1.5f, 1.1f, 1.2f}), 0.8f);
    d = smin(d, ellipsoid(p, {-3.0f, 0.0f, 8.1f}, {1.15f, 1.0f, 1.0f}), 0.3f);      // eyeballs
    d = smin(d, ellipsoid(p, {3.0f, 0.0f, 8.1f}, {1.15f, 1.0f, 1.0f}), 0.3f);
    d = smin(d, ellipsoid(p, {0.0f, -2.6f, 9.3f}, {1.25f, 2.6f, 1.7f}), 0.9f);       // nose
    d = smin(d, ellipsoid(p, {0.0f, -4.4f, 9.9f}, {1.7f, 0.9f, 1.1f}), 0.6f);        // nostrils
    d = smin(d, ellipsoid(p, {0.0f, -6.6f, 8.6f}, {2.3f, 0.75f, 1.1f}), 0.5f);       // upper lip
    d = smin(d, ellipsoid(p, {0.0f, -7.7f, 8.3f}, {2.0f, 0.7f, 1.0f}), 0.5f);        // lower lip
    d = smin(d, ellipsoid(p, {0.0f, -9.9f, 6.6f}, {2.4f, 1.6f, 1.8f}), 1.8f);       // chin
    if (ears) {
        d = smin(d, ellipsoid(p, {-7.4f, -1.0f, -0.9f}, {1.1f, 3.1f, 1.9f}), 0.7f);
        d = smin(d, ellipsoid(p, {7.4f, -1.0f, -0.9f}, {1.1f, 3.1f, 1.9f}), 0.7f);
    }
    d = smin(d, rounded_cylinder(p, 0.0f, -1.8f, -22.0f, -4.0f, 5.4f, 0.8f), 4.0f);  // neck
    return d;
}

PolygonSoup make_head(const HeadParams& params)
{
    params.validate();
    const int nlat = params.resolution, nlon = 2 * params.resolution;
    // Vertices: the top pole, (nlat - 1) rings of nlon, the bottom pole.
    const int64_t nverts = 2 + int64_t(nlat - 1) * nlon;
    PolygonSoup soup;
    soup.points.resize(size_t(nverts));
    auto direction = [&](int64_t v) -> float3 {
        if (v == 0) return {0, 1, 0};
        if (v == nverts - 1) return {0, -1, 0};
        const int64_t ring = (v - 1) / nlon + 1, k = (v - 1) % nlon;
        const float theta = kPi * float(ring) / float(nlat), phi = 2.0f * kPi * float(k) / float(nlon);
        // phi = 0 faces +Z (the face), increasing towards +X.
        return {std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
    };
    parallel_for(nverts, 256, [&](int64_t b, int64_t e) {
        for (int64_t v = b; v < e; ++v) {
            const float3 dir = direction(v);
            // March inwards from far outside to the first point inside: that is the outermost
            // surface crossing along the ray, which keeps the mesh closed even where the head is
            // not star-shaped (behind the ears, under the jaw). Then bisect to 1e-5 cm.
            float outside = kMaxRadius, inside = 0.0f;
            // Steps of 1 mm: finer than any feature (the ears are ~2 cm thick).
            for (float r = kMaxRadius; r > 0.0f; r -= 0.1f) {
                if (head_distance(kCenter + dir * r, params.ears) < 0.0f) {
                    inside = r;
                    break;
                }
                outside = r;
            }
            for (int it = 0; it < 24; ++it) {
                const float mid = 0.5f * (inside + outside);
                (head_distance(kCenter + dir * mid, params.ears) < 0.0f ? inside : outside) = mid;
            }
            soup.points[size_t(v)] = (kCenter + dir * (0.5f * (inside + outside))) * params.scale;
        }
    });
    auto ring_vertex = [&](int ring, int k) -> int32_t { return int32_t(1 + int64_t(ring - 1) * nlon + (k % nlon)); };
    // Winding: seen from outside, counter-clockwise. With phi increasing towards +X from +Z and
    // theta increasing downwards, (ring, k) -> (ring+1, k) -> (ring+1, k+1) -> (ring, k+1) is CCW.
    for (int k = 0; k < nlon; ++k) {
        const int32_t tri[3] = {0, ring_vertex(1, k), ring_vertex(1, k + 1)};
        soup.add_face(tri);
    }
    for (int ring = 1; ring < nlat - 1; ++ring) {
        for (int k = 0; k < nlon; ++k) {
            const int32_t quad[4] = {ring_vertex(ring, k), ring_vertex(ring + 1, k), ring_vertex(ring + 1, k + 1), ring_vertex(ring, k + 1)};
            soup.add_face(quad);
        }
    }
    const int32_t bottom = int32_t(nverts - 1);
    for (int k = 0; k < nlon; ++k) {
        const int32_t tri[3] = {bottom, ring_vertex(nlat - 1, k + 1), ring_vertex(nlat - 1, k)};
        soup.add_face(tri);
    }
    return soup;
}

}  // namespace groom
