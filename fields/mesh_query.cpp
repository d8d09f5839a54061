// Exact geometry of the repaired mesh: closest point on a triangle, angle-weighted pseudo-normals
// and a CGAL AABB tree for the queries that fall outside the level set's narrow band.
#include "fields/scalp_impl.h"

#include "kernel/error.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

namespace groom::detail {

float3 closest_on_triangle(const float3& p, const float3& a, const float3& b, const float3& c, Feature& feature)
{
    const float3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) {
        feature = Feature::Vertex0;
        return a;
    }
    const float3 bp = p - b;
    const float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) {
        feature = Feature::Vertex1;
        return b;
    }
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        feature = Feature::Edge0;
        return a + ab * (d1 / (d1 - d3));
    }
    const float3 cp = p - c;
    const float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) {
        feature = Feature::Vertex2;
        return c;
    }
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        feature = Feature::Edge2;
        return a + ac * (d2 / (d2 - d6));
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        feature = Feature::Edge1;
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    const float denom = 1.0f / (va + vb + vc);
    feature = Feature::Face;
    return a + ab * (vb * denom) + ac * (vc * denom);
}

void MeshGeometry::compute(const TriMesh& mesh)
{
    // The mesh's points and faces (each face's corners from its halfedge, as OpenMesh lists them),
    // then the one computation from arrays that a mesh stored in a .vdb also goes through: a field
    // built from the mesh and one loaded from its file hold the same geometry to the bit. (Reading
    // boundary vertices from OpenMesh's is_boundary(vertex) instead missed rim vertices whose
    // outgoing halfedge, as CGAL's graph traits left it, was not the boundary one: all 32 of a
    // cap's rim vertices, 148 of Sintel's head, 1,196 of ICT's face; those were signed by a
    // pseudo-normal whose fan stops at the rim, where the winding number should decide.)
    std::vector<float3> pts(mesh.n_vertices());
    for (size_t v = 0; v < pts.size(); ++v) {
        const auto& q = mesh.point(TriMesh::VertexHandle{int(v)});
        pts[v] = float3(q[0], q[1], q[2]);
    }
    std::vector<std::array<int32_t, 3>> faces(mesh.n_faces());
    for (size_t f = 0; f < faces.size(); ++f) {
        int k = 0;
        for (auto fv : mesh.fv_range(TriMesh::FaceHandle{int(f)})) faces[f][k++] = fv.idx();
    }
    compute(std::move(pts), std::move(faces));
}

void MeshGeometry::compute(std::vector<float3> points_in, std::vector<std::array<int32_t, 3>> tris_in)
{
    points = std::move(points_in);
    tris = std::move(tris_in);
    const size_t nv = points.size(), nf = tris.size();
    Bounds3 box;
    for (const float3& p : points) box.extend(p);
    bounds_lo = box.lo;
    bounds_hi = box.hi;
    face_normals.resize(nf);
    face_areas.resize(nf);
    edge_normals.assign(nf * 3, float3());
    vertex_normals.assign(nv, float3());
    for (size_t f = 0; f < nf; ++f) {
        const float3 &a = points[tris[f][0]], &b = points[tris[f][1]], &c = points[tris[f][2]];
        const float3 n = cross(b - a, c - a);
        face_areas[f] = 0.5 * double(length(n));
        face_normals[f] = normalize(n);
        for (int j = 0; j < 3; ++j) {
            const float3& p = points[tris[f][j]];
            const float3 e1 = normalize(points[tris[f][(j + 1) % 3]] - p), e2 = normalize(points[tris[f][(j + 2) % 3]] - p);
            const float angle = std::acos(std::clamp(dot(e1, e2), -1.0f, 1.0f));
            vertex_normals[tris[f][j]] += face_normals[f] * angle;
        }
    }
    for (float3& n : vertex_normals) n = normalize(n);
    vertex_face_offsets.assign(nv + 1, 0);
    for (const auto& t : tris)
        for (int32_t v : t) ++vertex_face_offsets[v + 1];
    for (size_t v = 0; v < nv; ++v) vertex_face_offsets[v + 1] += vertex_face_offsets[v];
    vertex_faces.resize(nf * 3);
    std::vector<int32_t> fill(vertex_face_offsets.begin(), vertex_face_offsets.end() - 1);
    for (size_t f = 0; f < nf; ++f)
        for (int32_t v : tris[f]) vertex_faces[fill[v]++] = int32_t(f);
    boundary_edge.assign(nf * 3, 0);
    boundary_vertex.assign(nv, 0);
    for (size_t v = 0; v < nv; ++v) boundary_vertex[v] = vertex_face_offsets[v] == vertex_face_offsets[v + 1];
    // Edge k runs v_k -> v_k+1; its other side is the face around v_k+1 holding v_k+1 -> v_k.
    for (size_t f = 0; f < nf; ++f) {
        for (int k = 0; k < 3; ++k) {
            const int32_t from = tris[f][k], to = tris[f][(k + 1) % 3];
            int32_t opp = -1;
            for (int32_t i = vertex_face_offsets[to]; i < vertex_face_offsets[to + 1] && opp < 0; ++i) {
                const auto& t = tris[vertex_faces[i]];
                for (int j = 0; j < 3; ++j)
                    if (t[j] == to && t[(j + 1) % 3] == from) opp = vertex_faces[i];
            }
            float3 n = face_normals[f];
            if (opp >= 0) n += face_normals[opp];
            boundary_edge[f * 3 + k] = opp < 0;
            edge_normals[f * 3 + k] = normalize(n, face_normals[f]);
            if (opp < 0) boundary_vertex[from] = boundary_vertex[to] = 1;
        }
    }
}

int32_t MeshGeometry::refine_closest_face(const float3& p, int32_t face) const
{
    auto dist2 = [&](int32_t f) {
        Feature feature;
        return length_squared(p - closest_on_triangle(p, points[tris[f][0]], points[tris[f][1]], points[tris[f][2]], feature));
    };
    float best = dist2(face);
    for (int iter = 0; iter < 16; ++iter) {
        const int32_t start = face;
        for (int k = 0; k < 3; ++k) {
            const int32_t v = tris[start][k];
            for (int32_t i = vertex_face_offsets[v]; i < vertex_face_offsets[v + 1]; ++i) {
                const int32_t g = vertex_faces[i];
                if (g == start) continue;
                // A face sharing an earlier vertex of `start` was already measured around that vertex.
                const auto& t = tris[g];
                bool seen = false;
                for (int j = 0; j < k; ++j) {
                    const int32_t u = tris[start][j];
                    seen |= (t[0] == u) | (t[1] == u) | (t[2] == u);
                }
                if (seen) continue;
                const float d = dist2(g);
                if (d < best) {
                    best = d;
                    face = g;
                }
            }
        }
        if (face == start) break;
    }
    return face;
}

float3 MeshGeometry::pseudo_normal(int32_t face, Feature feature) const
{
    switch (feature) {
    case Feature::Face: return face_normals[face];
    case Feature::Edge0: return edge_normals[face * 3 + 0];
    case Feature::Edge1: return edge_normals[face * 3 + 1];
    case Feature::Edge2: return edge_normals[face * 3 + 2];
    case Feature::Vertex0: return vertex_normals[tris[face][0]];
    case Feature::Vertex1: return vertex_normals[tris[face][1]];
    case Feature::Vertex2: return vertex_normals[tris[face][2]];
    }
    return face_normals[face];
}

float MeshGeometry::signed_distance_to_face(const float3& p, int32_t f, float3& closest, bool* on_boundary) const
{
    Feature feature;
    closest = closest_on_triangle(p, points[tris[f][0]], points[tris[f][1]], points[tris[f][2]], feature);
    if (on_boundary) {
        switch (feature) {
        case Feature::Face: *on_boundary = false; break;
        case Feature::Edge0: *on_boundary = boundary_edge[f * 3 + 0]; break;
        case Feature::Edge1: *on_boundary = boundary_edge[f * 3 + 1]; break;
        case Feature::Edge2: *on_boundary = boundary_edge[f * 3 + 2]; break;
        case Feature::Vertex0: *on_boundary = boundary_vertex[tris[f][0]]; break;
        case Feature::Vertex1: *on_boundary = boundary_vertex[tris[f][1]]; break;
        case Feature::Vertex2: *on_boundary = boundary_vertex[tris[f][2]]; break;
        }
    }
    const float3 d = p - closest;
    const float dist = length(d);
    return dot(d, pseudo_normal(f, feature)) < 0.0f ? -dist : dist;
}

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

struct MeshQuery::Tree {
    Triangles triangles;
    AabbTree tree;
};

MeshQuery::MeshQuery(const MeshGeometry& geometry) : geometry_(geometry) {}

const MeshQuery::Tree& MeshQuery::tree() const
{
    std::call_once(built_, [this] { tree_ = build(geometry_); });
    return *tree_;
}

std::unique_ptr<MeshQuery::Tree> MeshQuery::build(const MeshGeometry& geometry)
{
    auto out = std::make_unique<Tree>();
    auto P = [&](int32_t v) { return K::Point_3(geometry.points[v].x, geometry.points[v].y, geometry.points[v].z); };
    out->triangles.reserve(geometry.tris.size());
    for (const auto& t : geometry.tris) out->triangles.emplace_back(P(t[0]), P(t[1]), P(t[2]));
    out->tree.insert(out->triangles.cbegin(), out->triangles.cend());
    out->tree.build();
    // Builds the internal kd-tree of hints now, so later const queries from many threads never write.
    out->tree.accelerate_distance_queries();
    return out;
}

MeshQuery::~MeshQuery() = default;

float MeshQuery::signed_distance(const float3& p, float3& closest, int32_t& face) const
{
    // CGAL's exact predicates convert the point to GMP rationals, and GMP raises SIGFPE on inf or
    // NaN: an op whose arithmetic overflowed must fail here with an error, not kill the process.
    // (Inputs and parameters are checked on ingest; this is the last line.)
    if (!isfinite(p)) {
        throw InvalidGeometry("scalp query at a non-finite point (" + format_number(p.x) + ", " + format_number(p.y) + ", " +
                              format_number(p.z) + "): a computation overflowed float; are the inputs or parameters extreme?");
    }
    // Far out, a stand-in on the same ray (see the header). The centre and radius of the mesh's box.
    const double cx = 0.5 * (double(geometry_.bounds_lo.x) + geometry_.bounds_hi.x);
    const double cy = 0.5 * (double(geometry_.bounds_lo.y) + geometry_.bounds_hi.y);
    const double cz = 0.5 * (double(geometry_.bounds_lo.z) + geometry_.bounds_hi.z);
    const double radius = 0.5 * double(length(geometry_.bounds_hi - geometry_.bounds_lo));
    const double dx = double(p.x) - cx, dy = double(p.y) - cy, dz = double(p.z) - cz;
    const double out = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double far = kFarRadii * std::max(radius, 1e-30);
    const bool stand_in = out > far;
    const float3 q = stand_in ? float3(float(cx + dx * (far / out)), float(cy + dy * (far / out)), float(cz + dz * (far / out))) : p;

    face = tree_closest_face(q);
    const float d = signed_distance_to(q, face, closest);
    if (!stand_in) return d;
    const double ex = double(p.x) - closest.x, ey = double(p.y) - closest.y, ez = double(p.z) - closest.z;
    const float dist = float(std::sqrt(ex * ex + ey * ey + ez * ez));
    return d < 0.0f ? -dist : dist;
}

int32_t MeshQuery::tree_closest_face(const float3& p) const
{
    const auto hit = tree().tree.closest_point_and_primitive(K::Point_3(p.x, p.y, p.z));
    return static_cast<int32_t>(hit.second - tree().triangles.cbegin());
}

float MeshQuery::signed_distance_to(const float3& p, int32_t face, float3& closest) const
{
    // The pseudo-normal of the feature hit gives the sign; at an open rim, the winding number.
    bool boundary = false;
    const float pseudo = geometry_.signed_distance_to_face(p, face, closest, &boundary);
    return sign_fixed(p, pseudo, boundary, true);
}

void MeshQuery::faces_within(const float3& center, double radius, std::vector<int32_t>& faces, std::vector<double>* distances) const
{
    // The tree is asked for the faces meeting the ball's bounding box, then each face's distance is
    // measured: CGAL's do_intersect(Sphere_3, Triangle_3) is about the sphere's surface and misses
    // a face wholly inside it.
    faces.clear();
    if (distances) distances->clear();
    const Tree& t = tree();
    std::vector<Triangles::const_iterator> hits;
    const CGAL::Bbox_3 box(double(center.x) - radius, double(center.y) - radius, double(center.z) - radius,
                           double(center.x) + radius, double(center.y) + radius, double(center.z) + radius);
    t.tree.all_intersected_primitives(box, std::back_inserter(hits));
    // Float rounding of the closest point: a few ulps of the coordinates, kept on the inclusive side.
    const double slack = 1e-6 * (std::max({std::fabs(center.x), std::fabs(center.y), std::fabs(center.z)}) + radius);
    const double reach2 = (radius + slack) * (radius + slack);
    faces.reserve(hits.size());
    for (const auto& it : hits) {
        const int32_t f = int32_t(it - t.triangles.cbegin());
        const auto& tri = geometry_.tris[f];
        Feature feature;
        const float3 c = closest_on_triangle(center, geometry_.points[tri[0]], geometry_.points[tri[1]], geometry_.points[tri[2]], feature);
        const double dx = double(c.x) - center.x, dy = double(c.y) - center.y, dz = double(c.z) - center.z;
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (!(d2 <= reach2)) continue;
        faces.push_back(f);
        if (distances) distances->push_back(std::sqrt(d2));
    }
}

namespace {

/// What faces_seen_from asks of a sphere (centre m, radius rho) holding some of the mesh: can a
/// point inside it be nearer than s0 (plus the slack) to a point p of the ball B(c, r)?
/// (beyond_bisector, with rho + slack, reach R = |c - s0| + r, and the bisector's linear form least
/// over the ball at c - r (m - s0) / |m - s0|.) Far from the mesh this keeps the patch around s0 a
/// small ball can see, where a sphere around c keeps every face in it.
struct SeenFrom {
    double cx, cy, cz, r, sx, sy, sz, slack, cs2, R, gather2;

    bool excluded(double mx, double my, double mz, double rho) const
    {
        const double ax = mx - cx, ay = my - cy, az = mz - cz;
        const double bx = mx - sx, by = my - sy, bz = mz - sz;
        const double at = ax * ax + ay * ay + az * az - cs2;  // |c - m|^2 - |c - s0|^2
        // Double rounding of the terms, far below the slack the caller gives for float coordinates.
        return beyond_bisector(at, 2.0 * r * std::sqrt(bx * bx + by * by + bz * bz), rho + slack, R,
                               1e-9 * (ax * ax + ay * ay + az * az + cs2 + R * R));
    }
};

/// CGAL's traversal traits (the interface of its own Listing_primitive_traits): a node is entered
/// when its box is within the gather radius of the centre and not excluded by its bounding sphere;
/// a face is listed when within that radius and not excluded by its own.
template <class Tree>
class SeenFromTraits {
public:
    using Primitive = typename Tree::Primitive;
    using Node = CGAL::AABB_node<typename Tree::AABB_traits>;

    SeenFromTraits(const SeenFrom& q, const MeshGeometry& g, const Triangles& tris, std::vector<int32_t>& faces,
                   std::vector<double>& distances)
        : q_(q), g_(g), tris_(tris), faces_(faces), distances_(distances)
    {
    }
    bool go_further() const { return true; }
    bool do_intersect(int, const Node& node) const
    {
        const CGAL::Bbox_3& b = node.bbox();
        // The box's distance from the centre, squared.
        const double dx = std::max({b.xmin() - q_.cx, 0.0, q_.cx - b.xmax()}), dy = std::max({b.ymin() - q_.cy, 0.0, q_.cy - b.ymax()}),
                     dz = std::max({b.zmin() - q_.cz, 0.0, q_.cz - b.zmax()});
        if (dx * dx + dy * dy + dz * dz > q_.gather2) return false;
        const double hx = 0.5 * (b.xmax() - b.xmin()), hy = 0.5 * (b.ymax() - b.ymin()), hz = 0.5 * (b.zmax() - b.zmin());
        return !q_.excluded(b.xmin() + hx, b.ymin() + hy, b.zmin() + hz, std::sqrt(hx * hx + hy * hy + hz * hz));
    }
    void intersection(int, const Primitive& primitive)
    {
        const int32_t f = int32_t(primitive.id() - tris_.cbegin());
        const auto& t = g_.tris[size_t(f)];
        const float3 &a = g_.points[size_t(t[0])], &b = g_.points[size_t(t[1])], &c = g_.points[size_t(t[2])];
        const double mx = (double(a.x) + b.x + c.x) / 3.0, my = (double(a.y) + b.y + c.y) / 3.0, mz = (double(a.z) + b.z + c.z) / 3.0;
        double rho2 = 0.0;
        for (const float3* v : {&a, &b, &c}) {
            const double ex = v->x - mx, ey = v->y - my, ez = v->z - mz;
            rho2 = std::max(rho2, ex * ex + ey * ey + ez * ez);
        }
        if (q_.excluded(mx, my, mz, std::sqrt(rho2) * (1.0 + 1e-9))) return;
        Feature feature;
        const float3 centre(float(q_.cx), float(q_.cy), float(q_.cz));
        const float3 p = closest_on_triangle(centre, a, b, c, feature);
        const double px = double(p.x) - centre.x, py = double(p.y) - centre.y, pz = double(p.z) - centre.z;
        const double d2 = px * px + py * py + pz * pz;
        if (!(d2 <= q_.gather2)) return;
        faces_.push_back(f);
        distances_.push_back(std::sqrt(d2));
    }

private:
    const SeenFrom& q_;
    const MeshGeometry& g_;
    const Triangles& tris_;
    std::vector<int32_t>& faces_;
    std::vector<double>& distances_;
};

}  // namespace

void MeshQuery::faces_seen_from(const float3& center, double r, const double s0[3], double slack, std::vector<int32_t>& faces,
                                std::vector<double>& distances) const
{
    faces.clear();
    distances.clear();
    SeenFrom q;
    q.cx = center.x, q.cy = center.y, q.cz = center.z;
    q.r = r;
    q.sx = s0[0], q.sy = s0[1], q.sz = s0[2];
    q.slack = slack;
    const double ex = q.cx - q.sx, ey = q.cy - q.sy, ez = q.cz - q.sz;
    q.cs2 = ex * ex + ey * ey + ez * ez;
    const double cs = std::sqrt(q.cs2);
    q.R = cs + r;
    // Every candidate is within |c - s0| + 2 r + slack of the centre; float rounding of a face's
    // closest point (a few ulps of the coordinates) kept on the inclusive side, as faces_within.
    const double gather = cs + 2.0 * r + slack;
    const double round = 1e-6 * (std::max({std::fabs(q.cx), std::fabs(q.cy), std::fabs(q.cz)}) + gather);
    q.gather2 = (gather + round) * (gather + round);
    const Tree& t = tree();
    SeenFromTraits<AabbTree> traits(q, geometry_, t.triangles, faces, distances);
    t.tree.traversal(0, traits);
}

const WindingNumber& MeshQuery::winding() const
{
    std::call_once(winding_built_, [this] { winding_ = std::make_unique<WindingNumber>(geometry_.points, geometry_.tris); });
    return *winding_;
}

bool MeshQuery::inside_by_winding(const float3& p, bool exact_near_half) const
{
    // The fast estimate (error up to 0.07) decides where it is clear; near 1/2 (beside an opening,
    // 7-15% of the queries on open heads) a finer one (error up to 0.02) does. Those errors depend
    // on how the tree split the triangles, that is on the mesh's pose: with `exact_near_half`, the
    // exact sum decides within 0.03 of 1/2, so a point reads the same in any pose.
    const double w = winding()(p, 2.0);
    if (std::fabs(w - 0.5) > 0.1) return w > 0.5;
    const double finer = winding()(p, 4.0);
    if (!exact_near_half || std::fabs(finer - 0.5) > 0.03) return finer > 0.5;
    const double finest = winding()(p, 8.0);
    if (std::fabs(finest - 0.5) > 0.008) return finest > 0.5;
    return winding().exact(p) > 0.5;
}

float MeshQuery::sign_fixed(const float3& p, float d, bool on_boundary, bool exact_near_half) const
{
    if (!on_boundary) return d;
    return inside_by_winding(p, exact_near_half) ? -std::fabs(d) : std::fabs(d);
}

}  // namespace groom::detail
