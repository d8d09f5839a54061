#include "support/sphere_mesh.h"

#include "kernel/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <map>
#include <string>
#include <utility>

namespace groom {
namespace {

constexpr double kPi = 3.14159265358979323846;

void check_sphere(const char* what, float radius)
{
    if (!(radius > 0.0f) || !std::isfinite(radius)) {
        throw InvalidParam(std::string(what) + ": radius must be > 0 (got " + std::to_string(radius) + ")");
    }
}

void add_tri(PolygonSoup& s, int32_t a, int32_t b, int32_t c)
{
    const int32_t f[3] = {a, b, c};
    s.add_face(f);
}

/// Point on the unit sphere for polar angle theta from `axis` and azimuth phi, in the frame (u, v, axis).
float3 on_sphere(const float3& u, const float3& v, const float3& w, double theta, double phi)
{
    const double st = std::sin(theta);
    return u * float(st * std::cos(phi)) + v * float(st * std::sin(phi)) + w * float(std::cos(theta));
}

/// Rings of a latitude-longitude grid around `w` from the pole (a single vertex) down to polar angle
/// `theta_max`; closes with a second pole when `close` is set.
PolygonSoup lat_long(const float3& c, float r, const float3& w, double theta_max, int rings, int segments, bool close)
{
    const float3 u = any_perpendicular(w), v = cross(w, u);
    PolygonSoup s;
    s.points.push_back(c + w * r);
    const int last_ring = close ? rings - 1 : rings;  // rings of `segments` vertices
    for (int i = 1; i <= last_ring; ++i) {
        const double theta = theta_max * double(i) / double(rings);
        for (int j = 0; j < segments; ++j) {
            s.points.push_back(c + on_sphere(u, v, w, theta, 2.0 * kPi * double(j) / double(segments)) * r);
        }
    }
    auto ring = [&](int i, int j) { return int32_t(1 + (i - 1) * segments + (j % segments)); };
    for (int j = 0; j < segments; ++j) add_tri(s, 0, ring(1, j), ring(1, j + 1));
    for (int i = 1; i < last_ring; ++i) {
        for (int j = 0; j < segments; ++j) {
            add_tri(s, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
            add_tri(s, ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
        }
    }
    if (close) {
        const int32_t south = int32_t(s.points.size());
        s.points.push_back(c - w * r);
        for (int j = 0; j < segments; ++j) add_tri(s, ring(last_ring, j), south, ring(last_ring, j + 1));
    }
    return s;
}

}  // namespace

PolygonSoup uv_sphere(const float3& center, float radius, int rings, int segments)
{
    check_sphere("uv_sphere", radius);
    if (rings < 2 || segments < 3) {
        throw InvalidParam("uv_sphere: needs rings >= 2 and segments >= 3 (got " + std::to_string(rings) + ", " +
                           std::to_string(segments) + ")");
    }
    return lat_long(center, radius, float3(0, 1, 0), kPi, rings, segments, true);
}

PolygonSoup sphere_cap(const float3& center, float radius, const float3& axis, float half_angle_deg, int rings, int segments)
{
    check_sphere("sphere_cap", radius);
    if (!(half_angle_deg > 0.0f && half_angle_deg < 180.0f)) {
        throw InvalidParam("sphere_cap: half angle must be in (0, 180) degrees (got " + std::to_string(half_angle_deg) + ")");
    }
    if (rings < 1 || segments < 3) {
        throw InvalidParam("sphere_cap: needs rings >= 1 and segments >= 3 (got " + std::to_string(rings) + ", " +
                           std::to_string(segments) + ")");
    }
    const float3 w = normalize(axis);
    if (length(w) == 0.0f) throw InvalidParam("sphere_cap: axis must be non-zero");
    return lat_long(center, radius, w, double(half_angle_deg) * kPi / 180.0, rings, segments, false);
}

PolygonSoup icosphere(const float3& center, float radius, int subdivisions)
{
    check_sphere("icosphere", radius);
    if (subdivisions < 0 || subdivisions > 8) {
        throw InvalidParam("icosphere: subdivisions must be in 0..8 (got " + std::to_string(subdivisions) + ")");
    }
    // Unit-sphere icosahedron in double precision; midpoints are normalised, so vertices are exact.
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<std::array<double, 3>> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                            {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& q : p) {
        const double l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        for (double& x : q) x /= l;
    }
    std::vector<std::array<int32_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int32_t, int32_t>, int32_t> mid;
        auto midpoint = [&](int32_t a, int32_t b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            std::array<double, 3> m{};
            for (int k = 0; k < 3; ++k) m[k] = p[a][k] + p[b][k];
            const double l = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
            for (double& x : m) x /= l;
            p.push_back(m);
            return mid[key] = int32_t(p.size() - 1);
        };
        std::vector<std::array<int32_t, 3>> g;
        g.reserve(f.size() * 4);
        for (const auto& tri : f) {
            const int32_t a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
            g.push_back({tri[0], a, c});
            g.push_back({tri[1], b, a});
            g.push_back({tri[2], c, b});
            g.push_back({a, b, c});
        }
        f.swap(g);
    }
    PolygonSoup soup;
    soup.points.reserve(p.size());
    for (const auto& q : p) soup.points.push_back(center + float3(float(q[0]), float(q[1]), float(q[2])) * radius);
    for (const auto& tri : f) add_tri(soup, tri[0], tri[1], tri[2]);
    return soup;
}

float sphere_chordal_error(const PolygonSoup& soup, const float3& center, float radius)
{
    // The point of a flat triangle nearest the centre is the deepest point below the sphere; for
    // triangles inscribed in the sphere that is the foot of the perpendicular when it falls inside.
    double worst = 0.0;
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        const auto idx = soup.face(f);
        for (size_t k = 1; k + 1 < idx.size(); ++k) {
            const float3 a = soup.points[idx[0]] - center, b = soup.points[idx[k]] - center, c = soup.points[idx[k + 1]] - center;
            const float3 n = normalize(cross(b - a, c - a));
            const double plane = std::fabs(double(dot(n, a)));
            // Is the foot inside the triangle? Barycentric signs of the projected origin.
            const float3 foot = n * float(dot(n, a));
            const bool in = dot(cross(b - a, foot - a), n) >= 0 && dot(cross(c - b, foot - b), n) >= 0 &&
                            dot(cross(a - c, foot - c), n) >= 0;
            double nearest = plane;
            if (!in) {
                // Otherwise the nearest point is on an edge: distance to each edge's closest point.
                nearest = 1e300;
                const float3 e[3][2] = {{a, b}, {b, c}, {c, a}};
                for (const auto& seg : e) {
                    const float3 d = seg[1] - seg[0];
                    const float t = std::clamp(-dot(seg[0], d) / std::max(dot(d, d), 1e-30f), 0.0f, 1.0f);
                    nearest = std::min(nearest, double(length(seg[0] + d * t)));
                }
            }
            worst = std::max(worst, double(radius) - nearest);
        }
    }
    return float(worst);
}

PolygonSoup messy_uv_sphere(const PolygonSoup& clean, int rings, int segments, const float3& center, float R)
{
    PolygonSoup m;
    m.points = clean.points;
    auto ring = [&](int i, int j) { return int32_t(1 + (i - 1) * segments + (j % segments)); };
    std::vector<char> skip(clean.num_faces(), 0);
    // Face numbering of uv_sphere: `segments` pole triangles, then 2 per quad per band.
    auto band_face = [&](int i, int j, int k) { return size_t(segments + ((i - 1) * segments + j) * 2 + k); };
    // Quads: band 3 as quads; n-gon: two quads of band 5 as one hexagon.
    for (int j = 0; j < segments; ++j) {
        skip[band_face(3, j, 0)] = skip[band_face(3, j, 1)] = 1;
        const int32_t q[4] = {ring(3, j), ring(4, j), ring(4, j + 1), ring(3, j + 1)};
        m.add_face(q);
    }
    for (int k = 0; k < 4; ++k) skip[band_face(5, 0 + k / 2, k % 2)] = 1;
    const int32_t hex[6] = {ring(5, 0), ring(6, 0), ring(6, 1), ring(6, 2), ring(5, 2), ring(5, 1)};
    m.add_face(hex);
    // A hole: two faces of band 8 at j = 0 are simply missing.
    skip[band_face(8, 0, 0)] = skip[band_face(8, 0, 1)] = 1;
    for (size_t f = 0; f < clean.num_faces(); ++f) {
        if (skip[f]) continue;
        std::vector<int32_t> idx(clean.face(f).begin(), clean.face(f).end());
        if (f % 3 == 0) {  // split seams: this face gets its own copies of its vertices
            for (int32_t& v : idx) {
                m.points.push_back(m.points[v]);
                v = int32_t(m.points.size() - 1);
            }
        }
        if (f % 7 == 0) std::reverse(idx.begin(), idx.end());  // flipped
        m.add_face(idx);
    }
    // Degenerate triangles: a repeated vertex, and three collinear points.
    const int32_t a = ring(10, 3), b = ring(10, 4);
    m.points.push_back(lerp(m.points[a], m.points[b], 0.5f));
    const int32_t deg1[3] = {a, a, b}, deg2[3] = {a, int32_t(m.points.size() - 1), b};
    m.add_face(deg1);
    m.add_face(deg2);
    // A non-manifold fin: a third face on edge (a, b) reaching a little inside.
    m.points.push_back(lerp(m.points[a], m.points[b], 0.5f) + (center - m.points[a]) * 0.02f);
    const int32_t fin[3] = {a, b, int32_t(m.points.size() - 1)};
    m.add_face(fin);
    // A stray shell: a small closed sphere inside (an eye in a head).
    const PolygonSoup eye = icosphere(center + float3(0.1f, 0.2f, 0.0f) * R, R * 0.2f, 2);
    const int32_t base = int32_t(m.points.size());
    m.points.insert(m.points.end(), eye.points.begin(), eye.points.end());
    for (size_t f = 0; f < eye.num_faces(); ++f) {
        std::vector<int32_t> idx(eye.face(f).begin(), eye.face(f).end());
        for (int32_t& v : idx) v += base;
        m.add_face(idx);
    }
    return m;
}

PolygonSoup latlong_uv_sphere(float R, int rings, int segments)
{
    PolygonSoup soup;
    soup.points.emplace_back(0.0f, R, 0.0f);
    for (int r = 1; r < rings; ++r) {
        const double t = std::numbers::pi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const double p = 2 * std::numbers::pi * s / segments;
            soup.points.emplace_back(float(R * std::sin(t) * std::cos(p)), float(R * std::cos(t)), float(R * std::sin(t) * std::sin(p)));
        }
    }
    soup.points.emplace_back(0.0f, -R, 0.0f);
    const int32_t south = int32_t(soup.points.size() - 1);
    auto vid = [&](int r, int s) { return r == 0 ? 0 : r == rings ? south : int32_t(1 + (r - 1) * segments + s % segments); };
    auto uv = [&](double u, double v) {
        soup.uvs.push_back(float(u));
        soup.uvs.push_back(float(v));
        return int32_t(soup.uvs.size() / 2 - 1);
    };
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            // Counter-clockwise seen from outside: (r, s) -> (r+1, s) -> (r+1, s+1) -> (r, s+1).
            const double u0 = double(s) / segments, u1 = double(s + 1) / segments;
            const double v0 = 1.0 - double(r) / rings, v1 = 1.0 - double(r + 1) / rings;
            const double um = 0.5 * (u0 + u1);
            if (r == 0) {
                const int32_t f[3] = {vid(0, s), vid(1, s + 1), vid(1, s)};
                const int32_t t[3] = {uv(um, v0), uv(u1, v1), uv(u0, v1)};
                soup.add_face(f, t);
            }
            else if (r == rings - 1) {
                const int32_t f[3] = {vid(r, s), vid(r, s + 1), vid(rings, s)};
                const int32_t t[3] = {uv(u0, v0), uv(u1, v0), uv(um, v1)};
                soup.add_face(f, t);
            }
            else {
                const int32_t f[4] = {vid(r, s), vid(r, s + 1), vid(r + 1, s + 1), vid(r + 1, s)};
                const int32_t t[4] = {uv(u0, v0), uv(u1, v0), uv(u1, v1), uv(u0, v1)};
                soup.add_face(f, t);
            }
        }
    }
    return soup;
}


}  // namespace groom
