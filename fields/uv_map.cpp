#include "fields/uv_map.h"

#include "fields/metadata_text.h"
#include "kernel/error.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>

namespace groom::detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

struct D3 {
    double x, y, z;
};
D3 sub(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 d3(const float3& p) { return {p.x, p.y, p.z}; }

/// Closest point on triangle (a, b, c) to p as barycentric weights (Ericson, Real-Time Collision
/// Detection 5.1.5, in double), and its squared distance.
double closest_barycentric(const D3& p, const D3& a, const D3& b, const D3& c, double w[3])
{
    const D3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    auto finish = [&](double wa, double wb, double wc) {
        w[0] = wa, w[1] = wb, w[2] = wc;
        const D3 q{wa * a.x + wb * b.x + wc * c.x, wa * a.y + wb * b.y + wc * c.y, wa * a.z + wb * b.z + wc * c.z};
        const D3 d = sub(p, q);
        return dot(d, d);
    };
    if (d1 <= 0 && d2 <= 0) return finish(1, 0, 0);
    const D3 bp = sub(p, b);
    const double d3_ = dot(ab, bp), d4 = dot(ac, bp);
    if (d3_ >= 0 && d4 <= d3_) return finish(0, 1, 0);
    const double vc = d1 * d4 - d3_ * d2;
    if (vc <= 0 && d1 >= 0 && d3_ <= 0) {
        const double t = d1 / (d1 - d3_);
        return finish(1 - t, t, 0);
    }
    const D3 cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return finish(0, 0, 1);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double t = d2 / (d2 - d6);
        return finish(1 - t, 0, t);
    }
    const double va = d3_ * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3_) >= 0 && (d5 - d6) >= 0) {
        const double t = (d4 - d3_) / ((d4 - d3_) + (d5 - d6));
        return finish(0, 1 - t, t);
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, wgt = vc * denom;
    return finish(1 - v - wgt, v, wgt);
}

}  // namespace

struct UvMap::Tree {
    Triangles triangles;
    AabbTree tree;
};

UvMap::UvMap(std::vector<float3> points, std::vector<std::array<int32_t, 3>> tris, std::vector<float> uvs,
             std::vector<std::array<int32_t, 3>> tri_uvs)
    : points_(std::move(points)), tris_(std::move(tris)), uvs_(std::move(uvs)), tri_uvs_(std::move(tri_uvs))
{
}

const UvMap::Tree& UvMap::tree() const
{
    // On first use: every command that loads a scalp with UVs has the map, few ask it anything.
    std::call_once(built_, [this] { tree_ = build(); });
    return *tree_;
}

std::unique_ptr<UvMap::Tree> UvMap::build() const
{
    auto out = std::make_unique<Tree>();
    auto P = [&](int32_t v) { return K::Point_3(points_[v].x, points_[v].y, points_[v].z); };
    out->triangles.reserve(tris_.size());
    for (const auto& t : tris_) out->triangles.emplace_back(P(t[0]), P(t[1]), P(t[2]));
    if (!tris_.empty()) {
        out->tree.insert(out->triangles.cbegin(), out->triangles.cend());
        out->tree.build();
        // Now, inside the call_once: queries then only read, from any thread.
        out->tree.accelerate_distance_queries();
    }
    return out;
}

UvMap::~UvMap() = default;

std::unique_ptr<UvMap> UvMap::from_soup(const PolygonSoup& soup)
{
    if (!soup.has_uvs()) return nullptr;
    if (soup.face_uv_indices.size() != soup.face_indices.size()) {
        throw InvalidGeometry("mesh: " + std::to_string(soup.face_uv_indices.size()) + " texture coordinate indices for " +
                              std::to_string(soup.face_indices.size()) + " face corners; expected one per corner");
    }
    std::vector<std::array<int32_t, 3>> tris, tri_uvs;
    const int64_t num_uvs = int64_t(soup.uvs.size() / 2), num_points = int64_t(soup.points.size());
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        const int64_t b = soup.face_offsets[f], n = soup.face_offsets[f + 1] - b;
        if (n < 3) continue;
        const int32_t* vi = soup.face_indices.data() + b;
        const int32_t* ti = soup.face_uv_indices.data() + b;
        bool complete = true;
        for (int64_t k = 0; k < n; ++k) complete = complete && ti[k] >= 0 && ti[k] < num_uvs && vi[k] >= 0 && vi[k] < num_points;
        if (!complete) continue;
        auto add = [&](int64_t i, int64_t j, int64_t k) {
            tris.push_back({vi[i], vi[j], vi[k]});
            tri_uvs.push_back({ti[i], ti[j], ti[k]});
        };
        if (n == 4) {
            // The repair's split (fields/mesh_repair.cpp triangulate_polygon): the shorter diagonal.
            const float d02 = length_squared(soup.points[vi[0]] - soup.points[vi[2]]);
            const float d13 = length_squared(soup.points[vi[1]] - soup.points[vi[3]]);
            if (d02 <= d13) add(0, 1, 2), add(0, 2, 3);
            else add(1, 2, 3), add(1, 3, 0);
            continue;
        }
        for (int64_t k = 1; k + 1 < n; ++k) add(0, k, k + 1);
    }
    if (tris.empty()) return nullptr;
    return std::make_unique<UvMap>(soup.points, std::move(tris), soup.uvs, std::move(tri_uvs));
}

bool UvMap::lookup(const float3& p, float& u, float& v) const
{
    if (tris_.empty()) return false;
    const K::Point_3 q(p.x, p.y, p.z);
    const Tree& tr = tree();
    const auto hit = tr.tree.closest_point_and_primitive(q);
    const D3 pd = d3(p);
    double w[3];
    int32_t best = int32_t(hit.second - tr.triangles.cbegin());
    double best_d2 = closest_barycentric(pd, d3(points_[tris_[best][0]]), d3(points_[tris_[best][1]]), d3(points_[tris_[best][2]]), w);
    // Every triangle as close, to float rounding (a seam edge has two): the lowest index answers.
    const double d = std::sqrt(best_d2);
    const double slack = 1e-6 * (std::max({std::fabs(pd.x), std::fabs(pd.y), std::fabs(pd.z)}) + d) + 1e-30;
    const double r = d + slack;
    std::vector<Triangles::const_iterator> near;
    tr.tree.all_intersected_primitives(CGAL::Bbox_3(pd.x - r, pd.y - r, pd.z - r, pd.x + r, pd.y + r, pd.z + r), std::back_inserter(near));
    const double reach2 = r * r;
    for (const auto& it : near) {
        const int32_t f = int32_t(it - tr.triangles.cbegin());
        if (f >= best) continue;
        double wf[3];
        const double d2 = closest_barycentric(pd, d3(points_[tris_[f][0]]), d3(points_[tris_[f][1]]), d3(points_[tris_[f][2]]), wf);
        if (d2 <= reach2) {
            best = f;
            std::copy(wf, wf + 3, w);
        }
    }
    const auto& t = tri_uvs_[best];
    double uu = 0, vv = 0;
    for (int k = 0; k < 3; ++k) {
        uu += w[k] * uvs_[2 * size_t(t[k])];
        vv += w[k] * uvs_[2 * size_t(t[k]) + 1];
    }
    u = float(uu), v = float(vv);
    return true;
}

std::string UvMap::encode() const
{
    std::string out = "groom-uv-mesh 1 " + std::to_string(points_.size()) + " " + std::to_string(uvs_.size() / 2) + " " +
                      std::to_string(tris_.size()) + "\n";
    out.reserve(out.size() + points_.size() * 36 + uvs_.size() * 12 + tris_.size() * 42);
    char buf[32];
    auto num = [&](auto x, char sep) {
        const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
        out.append(buf, end);
        out += sep;
    };
    for (const float3& p : points_) num(p.x, ' '), num(p.y, ' '), num(p.z, '\n');
    for (size_t i = 0; i < uvs_.size(); i += 2) num(uvs_[i], ' '), num(uvs_[i + 1], '\n');
    for (size_t f = 0; f < tris_.size(); ++f) {
        for (int k = 0; k < 3; ++k) num(tris_[f][k], ' ');
        for (int k = 0; k < 3; ++k) num(tri_uvs_[f][k], k == 2 ? '\n' : ' ');
    }
    return out;
}

std::unique_ptr<UvMap> UvMap::decode(std::string_view text, const std::string& what)
{
    MetadataText in(text, what + ": texture coordinates (grid metadata 'groom_uv_mesh')");
    in.header("groom-uv-mesh");
    const int64_t np = in.count(1, "a point count");
    const int64_t nu = in.count(1, "a texture coordinate count");
    const int64_t nt = in.count(1, "a triangle count");
    in.expect_numbers(np * 3 + nu * 2 + nt * 6);
    std::vector<float3> points(static_cast<size_t>(np));
    for (float3& p : points) p.x = in.real(), p.y = in.real(), p.z = in.real();
    std::vector<float> uvs(static_cast<size_t>(2 * nu));
    for (float& x : uvs) x = in.real();
    std::vector<std::array<int32_t, 3>> tris(static_cast<size_t>(nt)), tri_uvs(static_cast<size_t>(nt));
    for (size_t f = 0; f < size_t(nt); ++f) {
        for (int k = 0; k < 3; ++k) tris[f][k] = int32_t(in.integer(0, np - 1, "a vertex index"));
        for (int k = 0; k < 3; ++k) tri_uvs[f][k] = int32_t(in.integer(0, nu - 1, "a texture coordinate index"));
    }
    if (!in.token().empty()) in.fail("unexpected text after the last triangle");
    return std::make_unique<UvMap>(std::move(points), std::move(tris), std::move(uvs), std::move(tri_uvs));
}

}  // namespace groom::detail
