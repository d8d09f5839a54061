// Soup -> oriented manifold triangle mesh with CGAL Polygon Mesh Processing, then into OpenMesh
// through CGAL's graph traits (one mesh type). Shell orientation, enclosed-shell removal and buried
// faces are ours: PMP orients each component consistently but picks its side arbitrarily, and knows
// nothing of eyes inside heads.
#include "fields/scalp_impl.h"

#include "fields/rims.h"

#include "kernel/error.h"
#include "kernel/position_key.h"
#include "kernel/parallel.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/graph_traits_TriMesh_ArrayKernelT.h>

#include <algorithm>
#include <array>
#include <set>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

namespace groom {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Polygon = std::vector<std::size_t>;

namespace detail {

void validate_soup(const PolygonSoup& soup, const std::string& what)
{
    if (soup.points.empty() || soup.num_faces() == 0) {
        throw InvalidGeometry(what + ": the mesh is empty (" + std::to_string(soup.points.size()) + " vertices, " +
                              std::to_string(soup.num_faces()) + " faces); a scalp needs at least one face");
    }
    for (size_t i = 0; i < soup.points.size(); ++i) {
        if (!isfinite(soup.points[i])) {
            throw InvalidGeometry(what + ": vertex " + std::to_string(i + 1) + " has a non-finite coordinate (NaN or inf)");
        }
    }
    if (soup.face_offsets.empty() || soup.face_offsets.front() != 0 ||
        soup.face_offsets.back() != static_cast<int64_t>(soup.face_indices.size())) {
        throw InvalidGeometry(what + ": face offsets do not match the index list");
    }
    if (soup.has_parts()) {
        if (soup.face_part.size() != soup.num_faces()) throw InvalidGeometry(what + ": part names do not match the faces");
        for (const int32_t k : soup.face_part) {
            if (k < 0 || size_t(k) >= soup.part_names.size()) throw InvalidGeometry(what + ": a face's part is out of range");
        }
    }
    const int64_t n = static_cast<int64_t>(soup.points.size());
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        if (soup.face_offsets[f + 1] < soup.face_offsets[f]) throw InvalidGeometry(what + ": face offsets decrease at face " + std::to_string(f + 1));
        for (int32_t i : soup.face(f)) {
            if (i < 0 || i >= n) {
                throw InvalidGeometry(what + ": face " + std::to_string(f + 1) + " uses vertex index " + std::to_string(i) +
                                      ", out of range (" + std::to_string(n) + " vertices)");
            }
        }
    }
}

namespace {

struct UnionFind {
    std::vector<size_t> parent;
    explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), size_t(0)); }
    size_t find(size_t x)
    {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(size_t a, size_t b) { parent[find(a)] = find(b); }
};

/// Counts what CGAL's orientation did, through its visitor concept.
struct OrientVisitor : PMP::Default_orientation_visitor {
    int64_t* nm_edges;
    int64_t* nm_vertices;
    int64_t* duplicated;
    std::vector<char>* reversed;
    void non_manifold_edge(std::size_t, std::size_t, std::size_t) { ++*nm_edges; }
    void non_manifold_vertex(std::size_t, std::size_t) { ++*nm_vertices; }
    void duplicated_vertex(std::size_t, std::size_t) { ++*duplicated; }
    void polygon_orientation_reversed(std::size_t p) { (*reversed)[p] ^= 1; }
};

inline K::Vector_3 tri_cross(const std::vector<Point>& pts, const Polygon& t)
{
    return CGAL::cross_product(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]);
}

/// Triangulates polygon `poly` (4+ vertices) into `out`, wound like the polygon. Quads split along
/// the shorter diagonal; larger polygons through CGAL's minimal-area hole triangulation (works for
/// non-planar polygons), fanned if that fails.
void triangulate_polygon(const std::vector<Point>& pts, const Polygon& poly, std::vector<Polygon>& out)
{
    const size_t n = poly.size();
    if (n == 4) {
        const double d02 = CGAL::squared_distance(pts[poly[0]], pts[poly[2]]);
        const double d13 = CGAL::squared_distance(pts[poly[1]], pts[poly[3]]);
        if (d02 <= d13) {
            out.push_back({poly[0], poly[1], poly[2]});
            out.push_back({poly[0], poly[2], poly[3]});
        }
        else {
            out.push_back({poly[1], poly[2], poly[3]});
            out.push_back({poly[1], poly[3], poly[0]});
        }
        return;
    }
    // Newell normal gives the polygon's winding even when it is not planar.
    K::Vector_3 newell(0, 0, 0);
    for (size_t i = 0; i < n; ++i) {
        const Point& a = pts[poly[i]];
        const Point& b = pts[poly[(i + 1) % n]];
        newell = newell + K::Vector_3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                                      (a.x() - b.x()) * (a.y() + b.y()));
    }
    std::vector<Point> polyline;
    for (size_t i : poly) polyline.push_back(pts[i]);
    std::vector<CGAL::Triple<int, int, int>> patch;
    PMP::triangulate_hole_polyline(polyline, std::back_inserter(patch));
    if (patch.size() != n - 2) {
        for (size_t i = 1; i + 1 < n; ++i) out.push_back({poly[0], poly[i], poly[i + 1]});
        return;
    }
    for (const auto& t : patch) {
        Polygon tri{poly[t.first], poly[t.second], poly[t.third]};
        if (tri_cross(pts, tri) * newell < 0) std::swap(tri[1], tri[2]);
        out.push_back(std::move(tri));
    }
}

/// The soup in CGAL's types: points in double, polygons as index lists.
void to_cgal(const PolygonSoup& soup, std::vector<Point>& pts, std::vector<Polygon>& polys)
{
    pts.reserve(soup.points.size());
    for (const float3& p : soup.points) pts.emplace_back(p.x, p.y, p.z);
    polys.resize(soup.num_faces());
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        const auto idx = soup.face(f);
        polys[f].assign(idx.begin(), idx.end());
    }
}

/// Soup clean-up: the steps of PMP::repair_polygon_soup one by one, so each can be counted. Three of
/// them (simplify, split pinched, remove invalid) are only in PMP::internal in CGAL 5.5: the public
/// repair_polygon_soup runs the same six in this order but reports no counts, and no public function
/// does any of the three alone, so they stay. Returns the invalid polygons removed (fewer than 3
/// distinct vertices), which the report counts as degenerate faces.
size_t clean_soup(std::vector<Point>& pts, std::vector<Polygon>& polys, RepairReport& report)
{
    report.duplicate_vertices_merged = static_cast<int64_t>(PMP::merge_duplicate_points_in_polygon_soup(pts, polys));
    PMP::internal::simplify_polygons_in_polygon_soup<K>(pts, polys, K());
    report.pinched_faces_split = static_cast<int64_t>(PMP::internal::split_pinched_polygons_in_polygon_soup<K>(pts, polys, K()));
    const size_t invalid = PMP::internal::remove_invalid_polygons_in_polygon_soup(pts, polys);
    report.duplicate_faces_removed = static_cast<int64_t>(PMP::merge_duplicate_polygons_in_polygon_soup(pts, polys));
    report.isolated_vertices_removed = static_cast<int64_t>(PMP::remove_isolated_points_in_polygon_soup(pts, polys));
    return invalid;
}

/// The square of the points' size, twice the largest distance from their centroid: the scale the
/// repair's tolerances are relative to. Unlike the bounding box's diagonal (which grows by up to
/// 1.7x as the mesh turns) it is the same for the mesh in any pose, so are the decisions made with it.
double squared_size(const std::vector<Point>& pts)
{
    if (pts.empty()) return 0.0;
    double c[3] = {0, 0, 0};
    for (const Point& p : pts) c[0] += p.x(), c[1] += p.y(), c[2] += p.z();
    const Point center(c[0] / double(pts.size()), c[1] / double(pts.size()), c[2] / double(pts.size()));
    double r2 = 0.0;
    for (const Point& p : pts) r2 = std::max(r2, CGAL::squared_distance(p, center));
    return 4.0 * r2;
}

/// True when triangle t is flat to within the float rounding of its own coordinates: its height
/// over its longest edge below 16 float ulps of its largest coordinate (the points came in as
/// floats, so three collinear points moved, turned or scaled are collinear only to that), or its
/// area below 1e-12 of the mesh's size squared.
bool flat_triangle(const std::vector<Point>& pts, const Polygon& t, double min_area2)
{
    const double cross2 = tri_cross(pts, t).squared_length();
    if (cross2 <= min_area2) return true;
    double edge2 = 0.0, coord = 0.0;
    for (int k = 0; k < 3; ++k) {
        const Point& a = pts[t[k]];
        edge2 = std::max(edge2, CGAL::squared_distance(a, pts[t[(k + 1) % 3]]));
        coord = std::max({coord, std::fabs(a.x()), std::fabs(a.y()), std::fabs(a.z())});
    }
    const double tol = 16.0 * double(std::numeric_limits<float>::epsilon()) * coord;
    return cross2 <= edge2 * tol * tol;  // height = |cross| / longest edge
}

/// Triangulates every polygon, then drops flat triangles (collinear vertices, to float rounding):
/// they carry no surface and have no normal to sign a distance with. `invalid` polygons were
/// dropped already and count as degenerate too. Throws InvalidGeometry when nothing is left.
std::vector<Polygon> triangulate(std::vector<Point>& pts, const std::vector<Polygon>& polys, size_t invalid, double size2,
                                 const std::string& what, RepairReport& report)
{
    const double min_area2 = size2 * size2 * 1e-24;  // (area * 2)^2 below (1e-12 size^2)^2
    std::vector<Polygon> tris;
    tris.reserve(polys.size() * 2);
    int64_t degenerate = static_cast<int64_t>(invalid);
    for (const Polygon& poly : polys) {
        const size_t first = tris.size();
        if (poly.size() == 3) {
            tris.push_back(poly);
        }
        else {
            ++report.ngons_triangulated;
            triangulate_polygon(pts, poly, tris);
            report.triangles_from_ngons += static_cast<int64_t>(tris.size() - first);
        }
        for (size_t t = first; t < tris.size();) {
            if (flat_triangle(pts, tris[t], min_area2)) {
                tris.erase(tris.begin() + static_cast<std::ptrdiff_t>(t));
                ++degenerate;
            }
            else {
                ++t;
            }
        }
    }
    report.degenerate_faces_removed = degenerate;
    report.isolated_vertices_removed += static_cast<int64_t>(PMP::remove_isolated_points_in_polygon_soup(pts, tris));
    if (tris.empty()) {
        throw InvalidGeometry(what + ": no face with a non-zero area is left after removing " +
                              std::to_string(report.degenerate_faces_removed) + " degenerate faces");
    }
    return tris;
}

/// The points in groom's float type (what the field and the winding number take).
std::vector<float3> float_points(const std::vector<Point>& at)
{
    std::vector<float3> points(at.size());
    for (size_t i = 0; i < at.size(); ++i) points[i] = float3(float(at[i].x()), float(at[i].y()), float(at[i].z()));
    return points;
}

/// Triangles as index triples: all of `faces`, or those listed in `only` (one shell's).
std::vector<std::array<int32_t, 3>> index_triangles(const std::vector<Polygon>& faces, const std::vector<size_t>* only = nullptr)
{
    const size_t n = only ? only->size() : faces.size();
    std::vector<std::array<int32_t, 3>> triangles(n);
    for (size_t i = 0; i < n; ++i) {
        const Polygon& f = faces[only ? (*only)[i] : i];
        triangles[i] = {int32_t(f[0]), int32_t(f[1]), int32_t(f[2])};
    }
    return triangles;
}

/// Hands the triangles to options.on_triangles, if set, in groom's types.
void report_triangles(const RepairOptions& options, const std::vector<Point>& at, const std::vector<Polygon>& faces)
{
    if (options.on_triangles) options.on_triangles(float_points(at), index_triangles(faces));
}

/// Consistent orientation per component; non-manifold vertices and edges are cut apart so the soup
/// becomes a valid manifold mesh. A soup that is an oriented manifold already is left alone (the
/// linear check is far cheaper than CGAL's orientation). reversed[t] records the triangles CGAL
/// turned. Returns whether the soup was an oriented manifold on arrival.
bool orient(std::vector<Point>& pts, std::vector<Polygon>& tris, const RepairOptions& options, RepairReport& report,
            std::vector<char>& reversed)
{
    reversed.assign(tris.size(), 0);
    OrientVisitor visitor;
    visitor.nm_edges = &report.non_manifold_edges;
    visitor.nm_vertices = &report.non_manifold_vertices;
    visitor.duplicated = &report.vertices_added_by_split;
    visitor.reversed = &reversed;
    const bool manifold_in = is_oriented_manifold(tris, pts.size());
    if (!manifold_in) {
        // CGAL reverses polygons and duplicates pinched vertices in place: positions and face
        // order are final already, so the caller can start on them while CGAL works.
        report_triangles(options, pts, tris);
        PMP::orient_polygon_soup(pts, tris, CGAL::parameters::visitor(visitor));
    }
    return manifold_in;
}

/// A connected component of the triangles (over shared vertices) and what the repair decides of it.
struct Shell {
    double area = 0, volume = 0, scale = 0;
    K::Vector_3 centroid{0, 0, 0};
    size_t vertex_count = 0, faces = 0, boundary_edges = 0;
    CGAL::Bbox_3 box;
    bool flip = false, removed = false;
    double winding = 0.0;
    size_t buried_faces = 0;
    std::string source;  ///< the file's part most of its triangles came from, "" where unnamed
};

/// " ('name')" for a shell whose source is named, else "": what notes add after a shell.
std::string named(const Shell& s) { return s.source.empty() ? std::string() : " ('" + s.source + "')"; }

/// The shells: shell[t] for each triangle, and per shell its area, signed volume about its
/// centroid, size and boundary edges. Counts shells, closed shells and boundary loops into `report`.
std::vector<Shell> find_shells(const std::vector<Point>& pts, const std::vector<Polygon>& tris, std::vector<int32_t>& shell,
                               RepairReport& report)
{
    UnionFind uf(pts.size());
    for (const Polygon& t : tris) {
        uf.unite(t[0], t[1]);
        uf.unite(t[0], t[2]);
    }
    std::vector<int32_t> shell_of_root(pts.size(), -1);
    shell.assign(tris.size(), 0);
    size_t nshells = 0;
    for (size_t t = 0; t < tris.size(); ++t) {
        int32_t& id = shell_of_root[uf.find(tris[t][0])];
        if (id < 0) id = int32_t(nshells++);
        shell[t] = id;
    }
    report.shells = static_cast<int64_t>(nshells);
    std::vector<Shell> shells(nshells);
    for (size_t t = 0; t < tris.size(); ++t) {
        Shell& s = shells[shell[t]];
        ++s.faces;
        s.area += 0.5 * std::sqrt(tri_cross(pts, tris[t]).squared_length());
        for (size_t v : tris[t]) {
            s.centroid = s.centroid + (pts[v] - CGAL::ORIGIN);
            ++s.vertex_count;
            s.box += pts[v].bbox();
        }
    }
    for (Shell& s : shells) s.centroid = s.centroid / double(s.vertex_count);
    for (size_t t = 0; t < tris.size(); ++t) {
        Shell& s = shells[shell[t]];
        const Point c = CGAL::ORIGIN + s.centroid;
        s.volume += CGAL::determinant(pts[tris[t][0]] - c, pts[tris[t][1]] - c, pts[tris[t][2]] - c) / 6.0;
        for (size_t v : tris[t]) s.scale = std::max(s.scale, std::sqrt(CGAL::squared_distance(pts[v], c)));
    }
    // Boundary edges: edges used by one triangle. The soup is an oriented manifold by now (each
    // directed edge at most once), so that is a directed edge a -> b without b -> a, found in b's
    // short list of outgoing edges.
    std::vector<uint32_t> out_offsets(pts.size() + 1, 0), out_to(tris.size() * 3);
    for (const Polygon& t : tris)
        for (size_t v : t) ++out_offsets[v + 1];
    for (size_t v = 0; v < pts.size(); ++v) out_offsets[v + 1] += out_offsets[v];
    {
        std::vector<uint32_t> fill(out_offsets.begin(), out_offsets.end() - 1);
        for (const Polygon& t : tris)
            for (int k = 0; k < 3; ++k) out_to[fill[t[k]]++] = uint32_t(t[(k + 1) % 3]);
    }
    auto has_edge = [&](size_t a, size_t b) {
        for (uint32_t i = out_offsets[a]; i < out_offsets[a + 1]; ++i)
            if (out_to[i] == b) return true;
        return false;
    };
    UnionFind loops(pts.size());
    std::vector<char> on_boundary(pts.size(), 0);
    for (size_t t = 0; t < tris.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const size_t a = tris[t][k], b = tris[t][(k + 1) % 3];
            if (!has_edge(b, a)) {
                ++shells[shell[t]].boundary_edges;
                loops.unite(a, b);
                on_boundary[a] = on_boundary[b] = 1;
            }
        }
    }
    for (size_t v = 0; v < pts.size(); ++v) report.boundary_loops += (on_boundary[v] && loops.find(v) == v);
    for (const Shell& s : shells) report.closed_shells += (s.boundary_edges == 0);
    return shells;
}

/// Outward orientation: decides Shell::flip. A closed shell is outward when its signed volume is
/// positive. An open shell (a scalp patch, a bust open at the neck) is judged by which side the world
/// can see (below); failing that by its volume about its centroid when that is decisive (a cap, a
/// nearly closed head); a nearly flat patch keeps the winding most of its area had in the file.
void orient_outward(const std::vector<Point>& pts, const std::vector<Polygon>& tris, const std::vector<int32_t>& shell,
                    const std::vector<char>& reversed, double size2, std::vector<Shell>& shells, RepairReport& report)
{
    const size_t nshells = shells.size();
    std::vector<double> agree(nshells, 0.0);
    for (size_t t = 0; t < tris.size(); ++t) {
        const double a = std::sqrt(tri_cross(pts, tris[t]).squared_length());
        agree[shell[t]] += reversed[t] ? -a : a;
    }
    // Open shells: which side of the shell can the world see? Rays from sample faces along +n and
    // -n that escape without hitting any geometry (ambient visibility) decide: an eye socket or a
    // bowl-shaped patch faces where its opening is, which no local rule can tell.
    // The tree is built only when some shell is open (closed heads need none).
    std::vector<K::Triangle_3> all;
    using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<K::Triangle_3>::const_iterator>;
    CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> tree;
    if (std::any_of(shells.begin(), shells.end(), [](const Shell& s) { return s.boundary_edges > 0; })) {
        all.reserve(tris.size());
        for (const Polygon& t : tris) all.emplace_back(pts[t[0]], pts[t[1]], pts[t[2]]);
        tree.insert(all.cbegin(), all.cend());
        tree.build();
    }
    std::vector<std::vector<size_t>> faces_of(nshells);
    for (size_t t = 0; t < tris.size(); ++t) faces_of[shell[t]].push_back(t);
    const double eps = 1e-5 * std::sqrt(size2);
    for (size_t i = 0; i < nshells; ++i) {
        Shell& s = shells[i];
        const double decisive = 0.25 * s.area * s.scale / 3.0;
        if (s.boundary_edges == 0) {
            s.flip = s.volume < 0.0;
        }
        else {
            const auto& fs = faces_of[i];
            const size_t samples = std::min<size_t>(fs.size(), 64);
            int escape_out = 0, escape_in = 0;
            for (size_t k = 0; k < samples; ++k) {
                const size_t t = fs[k * fs.size() / samples];
                const K::Vector_3 n = tri_cross(pts, tris[t]);
                const K::Vector_3 u = n / std::sqrt(n.squared_length());
                const Point c = CGAL::centroid(pts[tris[t][0]], pts[tris[t][1]], pts[tris[t][2]]);
                escape_out += !tree.do_intersect(K::Ray_3(c + u * eps, u));
                escape_in += !tree.do_intersect(K::Ray_3(c - u * eps, -u));
            }
            // n here is the winding after PMP's orientation: reversed[t] says how it relates to the file.
            if (std::abs(escape_out - escape_in) >= std::max<int>(2, int(samples) / 10)) s.flip = escape_in > escape_out;
            else if (std::fabs(s.volume) > decisive) s.flip = s.volume < 0.0;
            else s.flip = agree[i] < 0.0;
        }
        report.shells_flipped += s.flip;
    }
}

/// Each shell's source: the part of the soup (an OBJ object or group, a joined file) most of its
/// triangles came from, with how many others it joins ("'EyeL' (+1 more part)"). The repair
/// renumbers and splits vertices but never moves one, so a triangle is traced back by its first
/// vertex's position to the first face of the soup that uses it.
void name_shells(const PolygonSoup& soup, const std::vector<Point>& pts, const std::vector<Polygon>& tris,
                 const std::vector<int32_t>& shell, std::vector<Shell>& shells)
{
    if (!soup.has_parts()) return;
    std::unordered_map<PositionKey, int32_t, PositionHash> part_at;
    part_at.reserve(soup.points.size());
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        for (const int32_t v : soup.face(f)) {
            part_at.emplace(PositionKey::of(soup.points[size_t(v)]), soup.face_part[f]);
        }
    }
    std::vector<std::map<int32_t, size_t>> count(shells.size());
    for (size_t t = 0; t < tris.size(); ++t) {
        const Point& q = pts[tris[t][0]];
        const auto it = part_at.find(PositionKey::of(float3(float(q.x()), float(q.y()), float(q.z()))));
        if (it != part_at.end()) ++count[size_t(shell[t])][it->second];
    }
    for (size_t i = 0; i < shells.size(); ++i) {
        const auto& c = count[i];
        if (c.empty()) continue;
        const auto top = std::max_element(c.begin(), c.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
        const std::string& name = soup.part_names[size_t(top->first)];
        if (name.empty()) continue;
        const size_t others = c.size() - 1;
        shells[i].source = name + (others == 0 ? "" : " (+" + std::to_string(others) + (others == 1 ? " more part)" : " more parts)"));
    }
}

/// Enclosed shells: a shell whose sampled vertices all have |winding number| > 1/2 with respect to a
/// larger shell lies inside it (eyes and teeth in a head, joint helpers in a body). Hair never
/// reaches them, and they would give the inside of the head a false outside. Decides Shell::removed.
void remove_enclosed(const std::vector<Point>& pts, const std::vector<Polygon>& tris, const std::vector<int32_t>& shell,
                     std::vector<Shell>& shells, RepairReport& report)
{
    const size_t nshells = shells.size();
    std::vector<std::vector<size_t>> tris_of_shell(nshells);
    for (size_t t = 0; t < tris.size(); ++t) tris_of_shell[shell[t]].push_back(t);
    std::vector<size_t> order(nshells);
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return shells[a].area > shells[b].area; });
    // Each shell's vertices (ascending), and up to kSamples of them spread evenly by index: what the
    // winding number is asked at. Chosen by index and tested against hosts found by a rotation
    // invariant rule, so the same shells go for the mesh in any pose (the axis-aligned boxes this
    // used to compare, and three samples, removed 104 or 105 of makehuman's shells as it turned).
    constexpr size_t kSamples = 32;
    std::vector<std::vector<size_t>> vertices_of(nshells);
    {
        std::vector<int32_t> seen(pts.size(), -1);
        for (size_t t = 0; t < tris.size(); ++t) {
            for (size_t v : tris[t]) {
                if (seen[v] == shell[t]) continue;
                seen[v] = shell[t];
                vertices_of[shell[t]].push_back(v);
            }
        }
        for (auto& vs : vertices_of) std::sort(vs.begin(), vs.end());
    }
    // A shell inside another lies inside that shell's bounding sphere (centroid, scale): every one of
    // its vertices does. A cheap necessary test that, unlike a bounding box, does not change as the
    // mesh turns.
    auto within_sphere = [&](size_t a, size_t b) {
        const Point c = CGAL::ORIGIN + shells[b].centroid;
        const double r2 = shells[b].scale * shells[b].scale * (1.0 + 1e-9);
        for (size_t v : vertices_of[a])
            if (CGAL::squared_distance(pts[v], c) > r2) return false;
        return true;
    };
    // |winding number| of vertex v with respect to shell b: the hierarchical estimate (built once
    // per host shell), and where it lies within 0.02 of the 1/2 threshold, the exact sum.
    // Brute force alone took 150 ms for makehuman's 104 helper cubes inside a 27k-face body.
    const std::vector<float3> points = float_points(pts);
    std::vector<std::unique_ptr<WindingNumber>> estimate(nshells);
    auto host_winding = [&](size_t b, size_t v) {
        if (!estimate[b]) estimate[b] = std::make_unique<WindingNumber>(points, index_triangles(tris, &tris_of_shell[b]));
        const double w = std::fabs((*estimate[b])(points[v], 8.0));
        return std::fabs(w - 0.5) > 0.02 ? w : std::fabs(estimate[b]->exact(points[v]));
    };
    size_t biggest_host = order[0];
    std::vector<std::string> removed_names;  // the first few removed shells' sources, for the note
    for (size_t ai = 1; ai < nshells; ++ai) {
        const size_t a = order[ai];
        const auto& va = vertices_of[a];
        std::vector<size_t> samples;
        const size_t count = std::min(va.size(), kSamples);
        for (size_t k = 0; k < count; ++k) samples.push_back(va[k * va.size() / count]);
        for (size_t bi = 0; bi < ai && !shells[a].removed; ++bi) {
            const size_t b = order[bi];
            if (shells[b].removed || !within_sphere(a, b)) continue;
            bool inside = true;
            double wmin = 1e30;
            for (size_t v : samples) {
                const double w = host_winding(b, v);
                wmin = std::min(wmin, std::fabs(w));
                if (wmin <= 0.5) {
                    inside = false;
                    break;
                }
            }
            shells[a].winding = std::max(shells[a].winding, wmin);
            if (inside) {
                shells[a].removed = true;
                biggest_host = b;
                const std::string& name = shells[a].source;
                if (!name.empty() && std::find(removed_names.begin(), removed_names.end(), name) == removed_names.end()) {
                    removed_names.push_back(name);
                }
                ++report.enclosed_shells_removed;
                report.faces_in_removed_shells += static_cast<int64_t>(shells[a].faces);
            }
        }
    }
    if (report.enclosed_shells_removed > 0) {
        const int64_t n = report.enclosed_shells_removed;
        // The first four names; "..." only where more names follow (two shells of one part are one name).
        std::string which;
        for (size_t k = 0; k < removed_names.size() && k < 4; ++k) which += (which.empty() ? " ('" : "', '") + removed_names[k];
        if (!which.empty()) which += removed_names.size() > 4 ? "', ...)" : "')";
        report.notes.push_back("removed " + std::to_string(n) + (n == 1 ? " shell" : " shells") + which + " (" +
                               std::to_string(report.faces_in_removed_shells) + " faces) lying entirely inside a larger shell (" +
                               (n == 1 ? "inside" : "e.g. inside") + " one of " + std::to_string(shells[biggest_host].faces) + " faces" +
                               named(shells[biggest_host]) + "): eyes, teeth or helpers inside a head would make its inside read as outside");
    }
}

/// Buried faces: where shells overlap without one enclosing the other (eyeballs through the eyelids
/// of a head with open sockets, a jacket collar through the neck), the faces of each that lie inside
/// another are not on the solid's surface. Kept, they give points inside the head between them a
/// false outside: the closest face is an eyeball's back, whose normal points away from the eye. The
/// field of the union needs only the faces outside every other shell; the faces crossing another
/// shell are kept, and the open rims left where a buried part went are signed by the generalized
/// winding number like any other rim. A face is buried when all three of its vertices have
/// |winding number| > 1/2 with respect to one other shell (a threshold of 0.6, 0.75 or 0.9 left
/// more points of Sintel's head and eyeballs with the wrong sign: 19, 19, 190 of 200,000 against
/// 12). Marks buried[t].
void remove_buried_faces(const std::vector<Point>& pts, const std::vector<Polygon>& tris, const std::vector<int32_t>& shell,
                         std::vector<Shell>& shells, std::vector<char>& buried, RepairReport& report)
{
    const size_t nshells = shells.size();
    buried.assign(tris.size(), 0);
    std::vector<std::vector<size_t>> tris_of_shell(nshells);
    for (size_t t = 0; t < tris.size(); ++t) tris_of_shell[shell[t]].push_back(t);
    std::vector<float3> points;
    // inside[v] with respect to the host shell in hand: 0 outside (or not asked), 1 inside.
    std::vector<char> inside(pts.size(), 0), asked(pts.size(), 0);
    std::vector<int32_t> candidates;
    for (size_t b = 0; b < nshells; ++b) {
        if (shells[b].removed) continue;
        const Point cb = CGAL::ORIGIN + shells[b].centroid;
        const double rb2 = shells[b].scale * shells[b].scale * (1.0 + 1e-9);
        // The guests: shells whose bounding spheres meet b's; their vertices inside b's sphere are asked.
        std::vector<size_t> guests;
        candidates.clear();
        for (size_t a = 0; a < nshells; ++a) {
            if (a == b || shells[a].removed) continue;
            const double gap = std::sqrt(CGAL::squared_distance(cb, CGAL::ORIGIN + shells[a].centroid));
            if (gap > shells[b].scale + shells[a].scale) continue;
            guests.push_back(a);
            for (size_t t : tris_of_shell[a]) {
                for (size_t v : tris[t]) {
                    if (asked[v] || CGAL::squared_distance(pts[v], cb) > rb2) continue;
                    asked[v] = 1;
                    candidates.push_back(int32_t(v));
                }
            }
        }
        if (candidates.empty()) continue;
        if (points.empty()) points = float_points(pts);
        const WindingNumber winding(points, index_triangles(tris, &tris_of_shell[b]));
        // Each vertex on its own (the same answer for any thread count), each estimate asked only
        // where the one before is too close to call: at 2 radii (error about 0.07), at 4 (0.02)
        // within 0.15 of the threshold, at 8 (0.005) within 0.05, exact within 0.02. On ICT's 52
        // shells: 0.27 s at 2 threads, from 0.43 s starting at 4 radii and 0.79 s at 8 on one core.
        parallel_for(int64_t(candidates.size()), 64, [&](int64_t begin, int64_t end) {
            for (int64_t i = begin; i < end; ++i) {
                const float3& p = points[size_t(candidates[size_t(i)])];
                double w = std::fabs(winding(p, 2.0));
                if (std::fabs(w - 0.5) <= 0.15) w = std::fabs(winding(p, 4.0));
                if (std::fabs(w - 0.5) <= 0.05) w = std::fabs(winding(p, 8.0));
                if (std::fabs(w - 0.5) <= 0.02) w = std::fabs(winding.exact(p));
                inside[size_t(candidates[size_t(i)])] = w > 0.5;
            }
        });
        for (size_t a : guests) {
            for (size_t t : tris_of_shell[a]) {
                if (buried[t] || !inside[tris[t][0]] || !inside[tris[t][1]] || !inside[tris[t][2]]) continue;
                buried[t] = 1;
                ++shells[a].buried_faces;
                ++report.buried_faces_removed;
            }
        }
        for (int32_t v : candidates) inside[size_t(v)] = asked[size_t(v)] = 0;
    }
    // A shell buried whole (ICT's eyeballs, inside the slightly larger shells around them) is gone
    // as an enclosed one is: listed as removed. The shell that lost the most is named, with its share:
    // makehuman's body loses 45% under its tights and skirt helpers, which "an eyeball's back" hid.
    int64_t whole = 0;
    const Shell* most = nullptr;
    for (Shell& s : shells) {
        report.shells_with_buried_faces += s.buried_faces > 0;
        if (s.buried_faces > 0 && s.buried_faces == s.faces) s.removed = true, ++whole, ++report.buried_shells_removed;
        if (s.buried_faces > 0 && (!most || s.buried_faces > most->buried_faces)) most = &s;
    }
    if (report.buried_faces_removed > 0) {
        auto plural = [](int64_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
        std::string note = "removed " + plural(report.buried_faces_removed, "face", "faces") + " of " +
                           plural(report.shells_with_buried_faces, "shell", "shells") +
                           " lying inside another shell where shells overlap (an eyeball's back inside a head, a body under "
                           "a garment): the scalp is the shells' union, and those faces would make its inside read as outside";
        if (whole > 0) note += "; " + plural(whole, "shell lies", "shells lie") + " inside others whole and went";
        note += "; the most from a shell of " + std::to_string(most->faces) + " faces" + named(*most) + ": " + std::to_string(most->buried_faces) + " (" +
                format_number(std::round(1000.0 * double(most->buried_faces) / double(most->faces)) / 10.0) + "%)";
        report.notes.push_back(note);
    }
}

/// The shells into the report, largest first.
void list_shells(const std::vector<Shell>& shells, RepairReport& report)
{
    std::vector<size_t> order(shells.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return shells[a].area > shells[b].area; });
    for (size_t i : order) {
        const Shell& s = shells[i];
        RepairReport::Shell out;
        out.faces = static_cast<int64_t>(s.faces);
        out.area = s.area;
        out.lo[0] = float(s.box.xmin()), out.lo[1] = float(s.box.ymin()), out.lo[2] = float(s.box.zmin());
        out.hi[0] = float(s.box.xmax()), out.hi[1] = float(s.box.ymax()), out.hi[2] = float(s.box.zmax());
        out.closed = s.boundary_edges == 0;
        out.flipped = s.flip;
        out.removed = s.removed;
        out.winding = s.winding;
        out.buried_faces = static_cast<int64_t>(s.buried_faces);
        out.source = s.source;
        report.shell_list.push_back(out);
    }
}

/// The triangles of the shells kept, each wound as its shell was decided (and all reversed with
/// options.flip); counts the faces whose winding ends up other than in the file.
std::vector<Polygon> kept_triangles(const std::vector<Polygon>& tris, const std::vector<int32_t>& shell,
                                    const std::vector<char>& reversed, const std::vector<Shell>& shells,
                                    const std::vector<char>& buried, const RepairOptions& options, RepairReport& report)
{
    std::vector<Polygon> kept;
    kept.reserve(tris.size());
    for (size_t t = 0; t < tris.size(); ++t) {
        const Shell& s = shells[shell[t]];
        if (s.removed || (!buried.empty() && buried[t])) continue;
        Polygon tri = tris[t];
        const bool net = (reversed[t] != 0) != s.flip;
        report.faces_flipped += net;
        if (s.flip != options.flip) std::swap(tri[1], tri[2]);
        kept.push_back(std::move(tri));
    }
    return kept;
}

}  // namespace

TriMesh repair_soup(const PolygonSoup& soup, const RepairOptions& options, RepairReport& report, Progress* progress)
{
    validate_soup(soup, options.what);
    ProgressStep step(progress, "repair mesh", 6);
    report = RepairReport{};
    report.input_vertices = static_cast<int64_t>(soup.points.size());
    report.input_faces = static_cast<int64_t>(soup.num_faces());
    report.flipped_by_user = options.flip;

    std::vector<Point> pts;
    std::vector<Polygon> polys;
    to_cgal(soup, pts, polys);
    const size_t invalid = clean_soup(pts, polys, report);
    step.advance(1);

    const double size2 = squared_size(pts);
    std::vector<Polygon> tris = triangulate(pts, polys, invalid, size2, options.what, report);
    step.advance(1);

    std::vector<char> reversed;
    const bool manifold_in = orient(pts, tris, options, report, reversed);
    step.advance(1);

    std::vector<int32_t> shell;
    std::vector<Shell> shells = find_shells(pts, tris, shell, report);
    name_shells(soup, pts, tris, shell, shells);
    if (options.orient_outward) orient_outward(pts, tris, shell, reversed, size2, shells, report);
    std::vector<char> buried;
    if (options.remove_enclosed && shells.size() > 1) {
        remove_enclosed(pts, tris, shell, shells, report);
        remove_buried_faces(pts, tris, shell, shells, buried, report);
    }
    step.advance(1);

    // The mesh's holes are rims whose every edge was a boundary edge before shells and buried faces
    // went, known by their ends' positions (the points are renumbered below). A rim cut where buried
    // faces went lies inside the union: it is neither listed as a hole nor filled (filled, its disc
    // read points inside a head beside a joined eyeball as outside, +0.76 where -1.59 is right: a
    // review's find).
    std::set<std::array<double, 6>> hole_edges;
    auto edge_at = [](const std::vector<Point>& at, size_t a, size_t b) {
        return std::array<double, 6>{at[a].x(), at[a].y(), at[a].z(), at[b].x(), at[b].y(), at[b].z()};
    };
    if (report.boundary_loops > 0) {
        for (const Rim& r : find_rims(pts, tris)) {
            for (size_t i = 0; i + 1 < r.loop.size(); ++i) hole_edges.insert(edge_at(pts, r.loop[i], r.loop[i + 1]));
            if (r.simple) hole_edges.insert(edge_at(pts, r.loop.back(), r.loop.front()));
        }
    }

    list_shells(shells, report);
    std::vector<Polygon> kept = kept_triangles(tris, shell, reversed, shells, buried, options, report);
    PMP::remove_isolated_points_in_polygon_soup(pts, kept);
    // Whole shells removed or turned keep an oriented manifold one; buried faces gone can leave two
    // fans meeting at one vertex, which CGAL splits (the windings are already right).
    if (report.buried_faces_removed > 0 && !is_oriented_manifold(kept, pts.size())) {
        const size_t before = pts.size();
        PMP::orient_polygon_soup(pts, kept);
        report.non_manifold_vertices += static_cast<int64_t>(pts.size() - before);
        report.vertices_added_by_split += static_cast<int64_t>(pts.size() - before);
    }
    if ((!manifold_in || report.buried_faces_removed > 0) && !is_oriented_manifold(kept, pts.size())) {
        throw InvalidGeometry(options.what + ": repair could not make a manifold mesh (CGAL orient_polygon_soup left a "
                              "non-manifold configuration); please report this mesh");
    }
    // The holes left (their lengths go in the report, to choose --fill-holes by), and those asked for
    // filled. A mesh with no boundary before shells and buried faces went has no hole after (2% of
    // a closed head's conversion is not spent looking).
    std::vector<Rim> rims;
    if (report.boundary_loops > 0 || report.buried_faces_removed > 0) {
        for (Rim& r : find_rims(pts, kept)) {
            bool hole = true;
            for (size_t i = 0; hole && i + 1 < r.loop.size(); ++i) hole = hole_edges.count(edge_at(pts, r.loop[i], r.loop[i + 1])) > 0;
            if (hole && r.simple) hole = hole_edges.count(edge_at(pts, r.loop.back(), r.loop.front())) > 0;
            if (hole) rims.push_back(std::move(r));
            else ++report.rims_inside_union;
        }
    }
    for (const Rim& r : rims) report.rim_lengths.push_back(r.length);
    if (options.fill_holes > 0.0) {
        report.holes_filled = fill_rims(pts, kept, rims, options.fill_holes, report.faces_added_by_fill);
        for (const Rim& r : rims) report.holes_left_open += r.length <= options.fill_holes;
        report.holes_left_open -= report.holes_filled;
    }
    if (manifold_in || report.enclosed_shells_removed > 0 || report.buried_faces_removed > 0 || report.holes_filled > 0) {
        report_triangles(options, pts, kept);
    }
    TriMesh mesh;  // vertices and faces in the soup's order
    PMP::polygon_soup_to_polygon_mesh(pts, kept, mesh);
    report.output_vertices = static_cast<int64_t>(mesh.n_vertices());
    report.output_faces = static_cast<int64_t>(mesh.n_faces());
    step.advance(2);
    return mesh;
}

}  // namespace detail
}  // namespace groom
