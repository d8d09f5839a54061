// Per-cell candidate faces for exact closest-face queries (see near_faces.h).
#include "fields/near_faces.h"

#include "fields/scalp_impl.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

namespace groom::detail {
namespace {

std::atomic<uint64_t> next_id{0};
constexpr double kLimit = double(1 << 20);  // cells per axis either side of the origin (21-bit keys)

uint64_t pack_key(int64_t ix, int64_t iy, int64_t iz)
{
    const auto field = [](int64_t v) { return uint64_t(v + (int64_t(1) << 20)) & ((uint64_t(1) << 21) - 1); };
    return field(ix) | (field(iy) << 21) | (field(iz) << 42);
}

struct D3 {
    double x, y, z;
};
inline D3 sub(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 to_d3(const float3& v) { return {v.x, v.y, v.z}; }

/// Squared distance from p to triangle (a, b, c) in double: Ericson's regions (Real-Time Collision
/// Detection 5.1.5), the same as closest_on_triangle, without its float rounding deciding between
/// two faces.
double distance2(const D3& p, const D3& a, const D3& b, const D3& c, D3* at = nullptr)
{
    const D3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        if (at) *at = a;
        return dot(ap, ap);
    }
    const D3 bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        if (at) *at = b;
        return dot(bp, bp);
    }
    D3 q;
    const double vc = d1 * d4 - d3 * d2;
    const D3 cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    const double vb = d5 * d2 - d1 * d6;
    const double va = d3 * d6 - d5 * d4;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double t = d1 / (d1 - d3);
        q = {a.x + ab.x * t, a.y + ab.y * t, a.z + ab.z * t};
    }
    else if (d6 >= 0.0 && d5 <= d6) {
        if (at) *at = c;
        return dot(cp, cp);
    }
    else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double t = d2 / (d2 - d6);
        q = {a.x + ac.x * t, a.y + ac.y * t, a.z + ac.z * t};
    }
    else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        q = {b.x + (c.x - b.x) * t, b.y + (c.y - b.y) * t, b.z + (c.z - b.z) * t};
    }
    else {
        const double denom = 1.0 / (va + vb + vc);
        const double v = vb * denom, w = vc * denom;
        q = {a.x + ab.x * v + ac.x * w, a.y + ab.y * v + ac.y * w, a.z + ab.z * v + ac.z * w};
    }
    if (at) *at = q;
    const D3 e = sub(p, q);
    return dot(e, e);
}

/// Squared distance from p to face f; `at`, when given, receives the closest point.
double face_distance2(const MeshGeometry& g, int32_t f, const D3& p, D3* at = nullptr)
{
    const auto& t = g.tris[size_t(f)];
    return distance2(p, to_d3(g.points[size_t(t[0])]), to_d3(g.points[size_t(t[1])]), to_d3(g.points[size_t(t[2])]), at);
}

/// A margin for the float rounding of distances measured at `at` over `extent`: the candidates'
/// distances come from a float closest point (MeshQuery::faces_within), a few ulps of the coordinates.
double margin(const float3& at, double extent)
{
    return 1e-5 * (std::max({std::fabs(double(at.x)), std::fabs(double(at.y)), std::fabs(double(at.z))}) + extent);
}

struct Last {
    uint64_t owner = 0;
    int64_t ix = 0, iy = 0, iz = 0;
    const void* cell = nullptr;
};

}  // namespace

NearFaces::NearFaces(const MeshGeometry& geometry, const MeshQuery& query, const float3& origin, float voxel, int cell_voxels)
    : id_(next_id.fetch_add(1, std::memory_order_relaxed) + 1), geometry_(geometry), query_(query), ox_(origin.x), oy_(origin.y),
      oz_(origin.z), side_(double(voxel) * cell_voxels), inv_side_(1.0 / (double(voxel) * cell_voxels))
{
    double area = 0.0;
    for (double a : geometry.face_areas) area += a;
    const double smallest = double(voxel) * kCellVoxels;
    enabled_ = !geometry.tris.empty() && area / double(geometry.tris.size()) >= kMinFaceArea * smallest * smallest;
}

NearFaces::~NearFaces() = default;

std::unique_ptr<NearFaces::Cell> NearFaces::make(int64_t ix, int64_t iy, int64_t iz) const
{
    auto cell = std::make_unique<Cell>();
    cell->centre = float3(float(ox_ + side_ * (double(ix) + 0.5)), float(oy_ + side_ * (double(iy) + 0.5)), float(oz_ + side_ * (double(iz) + 0.5)));
    const D3 c = to_d3(cell->centre);
    // s0: the closest point of the face the tree finds (any point of the mesh would do: every point
    // p's closest face is at most |p - s0| away).
    D3 s0;
    const double reach_c = std::sqrt(face_distance2(geometry_, query_.tree_closest_face(cell->centre), c, &s0));
    if (!(reach_c <= kMaxReachCells * side_)) return cell;
    // The half diagonal, widened for the rounding of the centre and of p's cell index.
    const double half = 0.5 * std::sqrt(3.0) * side_;
    const double m = margin(cell->centre, reach_c + side_);
    const double r = half * (1.0 + 1e-6) + m;
    std::vector<int32_t> faces;
    std::vector<double> dist;
    // Every face that can be some point's closest, or within the rounding of a query of being it
    // (the 2 m each distance below may lose, twice), and nothing farther: the patch around s0 the
    // cell can see. Listing every face within |c - s0| + 2 r instead kept half the head for a
    // cell 10 voxels out, and the cells were worth their cost only where points crowd.
    const double at[3] = {s0.x, s0.y, s0.z};
    query_.faces_seen_from(cell->centre, r, at, 4.0 * m, faces, dist);
    if (faces.size() > kMaxCandidates) return cell;
    std::vector<size_t> order(faces.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return dist[a] < dist[b] || (dist[a] == dist[b] && faces[a] < faces[b]); });
    cell->faces.reserve(faces.size());
    cell->reach.reserve(faces.size());
    // Each candidate's distance from the centre, lowered by twice the margin: once for its own
    // rounding and once for the rounding of the distances it is compared with at query time.
    for (size_t k : order) {
        cell->faces.push_back(faces[k]);
        cell->reach.push_back(dist[k] - 2.0 * m);
    }
    cell->listed = true;
    return cell;
}

const NearFaces::Cell& NearFaces::cell(int64_t ix, int64_t iy, int64_t iz) const
{
    const uint64_t key = pack_key(ix, iy, iz);
    if (const auto it = table_.find(key); it != table_.end()) return *it->second;
    // Not there: made here; the first thread to store its (identical) cell wins.
    auto made = make(ix, iy, iz);
    const auto [it, inserted] = table_.emplace(key, std::move(made));
    return *it->second;
}

int32_t NearFaces::closest_face(const float3& p) const
{
    const double x = (double(p.x) - ox_) * inv_side_, y = (double(p.y) - oy_) * inv_side_, z = (double(p.z) - oz_) * inv_side_;
    if (!enabled_) return -1;
    if (!(std::fabs(x) < kLimit && std::fabs(y) < kLimit && std::fabs(z) < kLimit)) return -1;  // also NaN
    const int64_t ix = int64_t(std::floor(x)), iy = int64_t(std::floor(y)), iz = int64_t(std::floor(z));
    // The cell this thread answered from last: consecutive queries walk along a curve, mostly
    // within one cell, and the table's lookup is then skipped.
    thread_local Last last;
    const Cell* c = nullptr;
    if (last.owner == id_ && last.ix == ix && last.iy == iy && last.iz == iz) c = static_cast<const Cell*>(last.cell);
    else {
        c = &cell(ix, iy, iz);
        last = Last{id_, ix, iy, iz, c};
    }
    if (!c->listed) return -1;
    const D3 q = to_d3(p);
    const D3 e = sub(q, to_d3(c->centre));
    const double from_centre = std::sqrt(dot(e, e));
    double best2 = INFINITY, best = INFINITY;
    int32_t face = -1;
    const size_t n = c->faces.size();
    for (size_t k = 0; k < n; ++k) {
        // No face from here on can come nearer than the best so far (nor tie it).
        if (c->reach[k] - from_centre > best) break;
        const int32_t f = c->faces[k];
        const double d2 = face_distance2(geometry_, f, q);
        if (d2 < best2 || (d2 == best2 && f < face)) {
            best2 = d2;
            best = std::sqrt(d2);
            face = f;
        }
    }
    return face;
}

NearFaces::Counts NearFaces::counts() const
{
    Counts counts;
    for (const auto& [key, cell] : table_) {
        ++counts.cells;
        counts.without_list += !cell->listed;
        counts.candidates += int64_t(cell->faces.size());
    }
    return counts;
}

}  // namespace groom::detail
