#include "fields/far_field.h"

#include "fields/scalp_impl.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

namespace groom::detail {

namespace {

// Cells of 2^kStartLevel voxels are tried first, then split down to 2^kMinLevel: on Sintel's head,
// hair points near the scalp are mostly certified by cells of 1 and 2 voxels.
constexpr int kStartLevel = 3;
constexpr int kMinLevel = 0;
// Cell coordinates are packed in 20 bits each: points beyond 2^19 voxels from the grid's origin
// (about 2,000 times a head at the default voxel) go to the exact query.
constexpr double kLimit = double(1 << 19);
constexpr float kSplit = -1.0f;  ///< Certificate::m of a cell that failed and has smaller cells
constexpr float kExact = -2.0f;  ///< Certificate::m of a smallest cell that failed

// The first level's dense block: the mesh's box in cells of that level and this many more each way
// (hair hangs beyond the head: on Sintel every curled point of 100,000 hairs lies within 4), unless
// that makes more than kDenseMax cells (32 MiB of slots at most, only the ones reached in memory).
constexpr int64_t kDenseMargin = 8;
constexpr int64_t kDenseMax = int64_t(1) << 22;

// A slot: 0 until its cell is examined; then bits of Certificate::dc above bits of
// Certificate::m, except for a split cell, whose m is kSplit and whose upper half is the index of
// its Split (its dc is its faces' distance).
uint64_t pack(float dc, float m)
{
    uint32_t lo, hi;
    std::memcpy(&lo, &m, sizeof lo);
    std::memcpy(&hi, &dc, sizeof hi);
    return uint64_t(hi) << 32 | lo;
}

float slot_m(uint64_t slot)
{
    const uint32_t lo = uint32_t(slot);
    float m;
    std::memcpy(&m, &lo, sizeof m);
    return m;
}

float slot_dc(uint64_t slot)
{
    const uint32_t hi = uint32_t(slot >> 32);
    float dc;
    std::memcpy(&dc, &hi, sizeof dc);
    return dc;
}

uint64_t pack_key(int level, int64_t ix, int64_t iy, int64_t iz)
{
    constexpr int64_t kOffset = int64_t(1) << 19;
    return (uint64_t(1) << 63) | (uint64_t(level) << 60) | (uint64_t(ix + kOffset) << 40) | (uint64_t(iy + kOffset) << 20) |
           uint64_t(iz + kOffset);
}

/// Distinguishes fields in each thread's memory of the last cell (an address can be reused).
std::atomic<uint64_t> next_id{0};

double max_abs(double a, double b, double c) { return std::max({std::fabs(a), std::fabs(b), std::fabs(c)}); }

/// Double precision for the certificate's plane tests (the mesh is float; its planes tested exactly enough).
struct D3 {
    double x = 0, y = 0, z = 0;
    D3() = default;
    D3(double x, double y, double z) : x(x), y(y), z(z) {}
    explicit D3(const float3& p) : x(p.x), y(p.y), z(p.z) {}
    D3 operator-(const D3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    D3 operator-() const { return {-x, -y, -z}; }
    D3 cross(const D3& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
    D3 unit() const
    {
        const double l = std::sqrt(x * x + y * y + z * z);
        return l > 0.0 ? D3(x / l, y / l, z / l) : D3();
    }
};

}  // namespace

FarField::FarField(const MeshGeometry& geometry, const MeshQuery& query, const float3& origin, float voxel)
    : id_(next_id.fetch_add(1, std::memory_order_relaxed) + 1), geometry_(geometry), query_(query), ox_(origin.x), oy_(origin.y), oz_(origin.z), voxel_(voxel), inv_voxel_(1.0 / double(voxel))
{
    // What the certificates ask of every face and vertex, once: per edge k of face f (v_k -> v_k+1)
    // its unit direction, its outward normal within f and within the face across it; per vertex the
    // unit directions of its edges.
    const size_t nf = geometry.tris.size(), nv = geometry.points.size();
    const auto unit = [&](int32_t from, int32_t to) { return normalize(geometry.points[to] - geometry.points[from]); };
    edge_dir_.resize(nf * 3);
    edge_out_.resize(nf * 3);
    edge_other_out_.assign(nf * 3, float3());
    for (size_t f = 0; f < nf; ++f) {
        for (int k = 0; k < 3; ++k) {
            const int32_t a = geometry.tris[f][k], b = geometry.tris[f][(k + 1) % 3];
            edge_dir_[f * 3 + k] = unit(a, b);
            edge_out_[f * 3 + k] = normalize(cross(edge_dir_[f * 3 + k], geometry.face_normals[f]));
            for (int32_t i = geometry.vertex_face_offsets[a]; i < geometry.vertex_face_offsets[a + 1]; ++i) {
                const int32_t g = geometry.vertex_faces[i];
                const auto& tg = geometry.tris[g];
                if (size_t(g) != f && (tg[0] == b || tg[1] == b || tg[2] == b)) {
                    edge_other_out_[f * 3 + k] = normalize(cross(unit(b, a), geometry.face_normals[g]));
                }
            }
        }
    }
    // A sphere around each face: a face farther than a cell's reach is skipped without measuring it.
    face_centre_.resize(nf);
    face_radius_.resize(nf);
    for (size_t f = 0; f < nf; ++f) {
        const float3 &a = geometry.points[geometry.tris[f][0]], &b = geometry.points[geometry.tris[f][1]], &c = geometry.points[geometry.tris[f][2]];
        face_centre_[f] = (a + b + c) / 3.0f;
        face_radius_[f] = std::max({distance(face_centre_[f], a), distance(face_centre_[f], b), distance(face_centre_[f], c)}) * (1.0f + 1e-5f) +
                          1e-6f * std::max({std::fabs(face_centre_[f].x), std::fabs(face_centre_[f].y), std::fabs(face_centre_[f].z)});
    }
    ring_offsets_.assign(nv + 1, 0);
    std::vector<int32_t> ring;
    for (size_t a = 0; a < nv; ++a) {
        ring.clear();
        for (int32_t i = geometry.vertex_face_offsets[a]; i < geometry.vertex_face_offsets[a + 1]; ++i) {
            for (const int32_t b : geometry.tris[geometry.vertex_faces[i]]) {
                if (size_t(b) != a) ring.push_back(b);
            }
        }
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
        for (const int32_t b : ring) ring_dirs_.push_back(unit(int32_t(a), b));
        ring_offsets_[a + 1] = int32_t(ring_dirs_.size());
    }
    if (nv > 0) {
        const double side = voxel_ * double(1 << kStartLevel);
        const float3 lo = geometry.bounds_lo, hi = geometry.bounds_hi;
        const double los[3] = {(lo.x - ox_) / side, (lo.y - oy_) / side, (lo.z - oz_) / side};
        const double his[3] = {(hi.x - ox_) / side, (hi.y - oy_) / side, (hi.z - oz_) / side};
        double cells = 1.0;
        for (int k = 0; k < 3; ++k) {
            const double a = std::floor(los[k]) - double(kDenseMargin), b = std::floor(his[k]) + double(kDenseMargin);
            cells *= std::isfinite(a) && std::isfinite(b) ? b - a + 1.0 : 1e30;
            dense_lo_[k] = std::isfinite(a) ? int64_t(std::clamp(a, -kLimit, kLimit)) : 0;
            dense_n_[k] = std::isfinite(a) && std::isfinite(b) ? int64_t(std::clamp(b - a + 1.0, 0.0, kLimit)) : 0;
        }
        if (cells <= double(kDenseMax)) {
            dense_.reset(static_cast<uint64_t*>(std::calloc(size_t(cells), sizeof(uint64_t))));
            if (!dense_) throw std::bad_alloc();
        }
    }
}

void FarField::FreeDense::operator()(uint64_t* p) const { std::free(p); }

FarField::~FarField() = default;

FarField::Certificate FarField::certify(int level, int64_t ix, int64_t iy, int64_t iz, const Faces* parent,
                                        std::unique_ptr<Faces>* kept) const
{
    const double side = voxel_ * double(int64_t(1) << level), half = 0.5 * side;
    const double cx = ox_ + side * (double(ix) + 0.5), cy = oy_ + side * (double(iy) + 0.5), cz = oz_ + side * (double(iz) + 0.5);
    const float3 cf(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(cz));
    // Every point of the cell is within r of cf.
    const double ex = double(cf.x) - cx, ey = double(cf.y) - cy, ez = double(cf.z) - cz;
    const double r = std::sqrt(3.0) * half + std::sqrt(ex * ex + ey * ey + ez * ez);
    // |d| at the centre: from the exact query for a cell of the first level; a smaller cell starts
    // from its parent's (plus the distance between the centres) and measures its own among the
    // faces near it, which are among its parent's (no tree search below the first level).
    float dc = 0.0f;
    double upper = 0.0, offset = 0.0;
    float3 s0;  // the surface point nearest the centre
    if (!parent) {
        int32_t face = -1;
        dc = query_.signed_distance(cf, s0, face);
        if (!std::isfinite(dc)) return Certificate{0.0f, kExact};
        upper = std::fabs(double(dc));
    }
    else {
        const double qx = double(cf.x) - parent->center.x, qy = double(cf.y) - parent->center.y, qz = double(cf.z) - parent->center.z;
        offset = std::sqrt(qx * qx + qy * qy + qz * qz);
        upper = (double(parent->distance) + offset) * (1.0 + 1e-6) + 1e-6 * max_abs(cx, cy, cz);
    }
    // Float rounding of the exact query (its closest point, its dot with the pseudo-normal) is a few
    // ulps of the coordinates involved: planes must clear the cell by well more than that.
    const double scale = max_abs(cx, cy, cz) + upper + side;
    const double margin = 1e-5 * scale;
    // Every point's closest point is within |d_c| + 2 r of the centre. Gathered a little wider:
    // the cell's children look for theirs among these.
    const double gather = (upper + 2.0 * r) * (1.0 + 1e-3) + 8.0 * margin;
    // Per-thread scratch (certify does not nest): a certificate is a few microseconds, and four
    // vectors' allocations were a visible share of it.
    thread_local std::vector<int32_t> faces;
    thread_local std::vector<double> face_distance;
    faces.clear();
    face_distance.clear();
    if (parent && offset + gather <= parent->radius) {
        const double gather2 = gather * gather * (1.0 + 1e-12);
        for (const int32_t f : parent->faces) {
            const float3& m = face_centre_[f];
            const double mx = double(m.x) - cf.x, my = double(m.y) - cf.y, mz = double(m.z) - cf.z;
            const double far = gather + face_radius_[f];
            if (mx * mx + my * my + mz * mz > far * far) continue;
            const auto& t = geometry_.tris[f];
            Feature feature;
            const float3 q = closest_on_triangle(cf, geometry_.points[t[0]], geometry_.points[t[1]], geometry_.points[t[2]], feature);
            const double qx = double(q.x) - cf.x, qy = double(q.y) - cf.y, qz = double(q.z) - cf.z;
            const double d2 = qx * qx + qy * qy + qz * qz;
            if (d2 > gather2) continue;  // certainly sqrt(d2) > gather, decided without the root
            const double d = std::sqrt(d2);
            if (d > gather) continue;
            faces.push_back(f);
            face_distance.push_back(d);
        }
    }
    else if (!parent) {
        // The faces that can be closest to a point of the cell's ball, a superset of those the
        // tests below keep (the bisector test there is over the box, with a smaller slack): far
        // out, the ball of `gather` holds much of the head, and listing it was most of a cell.
        const double at[3] = {s0.x, s0.y, s0.z};
        query_.faces_seen_from(cf, r, at, 4.0 * margin, faces, face_distance);
    }
    else {
        query_.faces_within(cf, gather, faces, &face_distance);
    }
    double distance = upper;
    if (parent) {
        distance = std::numeric_limits<double>::infinity();
        size_t nearest = 0;
        for (size_t i = 0; i < faces.size(); ++i) {
            if (face_distance[i] < distance) {
                distance = face_distance[i];
                nearest = i;
            }
        }
        if (!faces.empty()) {
            const auto& t = geometry_.tris[faces[nearest]];
            Feature feature;
            s0 = closest_on_triangle(cf, geometry_.points[t[0]], geometry_.points[t[1]], geometry_.points[t[2]], feature);
        }
    }
    if (!std::isfinite(distance)) return Certificate{0.0f, kExact};
    const Certificate fail{float(distance), level > kMinLevel ? kSplit : kExact};
    // A point of the surface near the centre: every point p of the cell has |d(p)| <= |p - s0|.
    double corner_reach[8];
    for (int i = 0; i < 8; ++i) {
        const double qx = cx + ((i & 1) ? half : -half) - s0.x, qy = cy + ((i & 2) ? half : -half) - s0.y,
                     qz = cz + ((i & 4) ? half : -half) - s0.z;
        corner_reach[i] = std::sqrt(qx * qx + qy * qy + qz * qz) + 2.0 * margin;
    }
    // A point's closest point is within |p - s0| of it, so within the farthest corner's reach + r of
    // the centre (|p - s0| is convex: the corners bound it); never more than |d_c| + 2 r.
    double reach = 0.0;
    for (const double c : corner_reach) reach = std::max(reach, c);
    // A face none of whose points can be nearer than s0 to any point p of the cell is nobody's
    // closest face there, nor are its edges and vertices (they are its points): beyond_bisector
    // over the box (the bisector's linear form least at a corner) with its centroid and radius and
    // the farthest corner's reach. Near the scalp this keeps the faces around s0 a cell can see,
    // where the sphere of |d_c| + 2 r kept every face within it (half of the faces the
    // certificates examined on Sintel's curl, perf). Dropped here once, for the tests below and
    // for the children.
    {
        const double sx = s0.x, sy = s0.y, sz = s0.z;
        const double cs2 = (cx - sx) * (cx - sx) + (cy - sy) * (cy - sy) + (cz - sz) * (cz - sz);
        size_t w = 0;
        for (size_t i = 0; i < faces.size(); ++i) {
            const float3& m = face_centre_[faces[i]];
            const double rho = face_radius_[faces[i]];
            const double mx = double(m.x) - cx, my = double(m.y) - cy, mz = double(m.z) - cz;
            const double at = mx * mx + my * my + mz * mz - cs2;  // |c - m|^2 - |c - s0|^2
            const double spread = 2.0 * half * (std::fabs(double(m.x) - sx) + std::fabs(double(m.y) - sy) + std::fabs(double(m.z) - sz));
            // Rounding of the terms is far below this slack (double over float coordinates).
            const double rounding = 1e-9 * (mx * mx + my * my + mz * mz + cs2 + scale * scale) + margin * (rho + reach);
            if (beyond_bisector(at, spread, rho, reach, rounding)) continue;
            faces[w] = faces[i];
            face_distance[w] = face_distance[i];
            ++w;
        }
        faces.resize(w);
        face_distance.resize(w);
    }
    if (kept && level > kMinLevel) {
        // Kept for the children in case this cell fails: the faces that can be closest to some
        // point of this cell, so to some point of each child (a child's own closest faces, the
        // nearest to its centre among them, are all here; its grandchildren's too).
        auto& k = *kept;
        k = std::make_unique<Faces>();
        k->center = cf;
        k->distance = float(distance);
        k->radius = gather;
        k->faces = faces;
    }
    if (!(distance > 0.0)) return fail;
    const double radius = (std::min(distance + 2.0 * r, reach + r)) * (1.0 + 1e-5) + margin;
    // The box's extent along a unit direction u, measured from q: [lo, hi] of dot(p - q, u).
    const auto range = [&](const float3& q, const D3& u, double& lo, double& hi) {
        const double at = (cx - q.x) * u.x + (cy - q.y) * u.y + (cz - q.z) * u.z;
        const double spread = half * (std::fabs(u.x) + std::fabs(u.y) + std::fabs(u.z)) + margin;
        lo = at - spread;
        hi = at + spread;
    };
    // A feature whose plane (through q, normal n) keeps the whole cell farther than s0 is nobody's
    // closest feature there: |p - s0| - |plane distance| is convex, so the corners decide.
    const auto dominated = [&](const float3& q, const float3& n) {
        const double at = (cx - q.x) * n.x + (cy - q.y) * n.y + (cz - q.z) * n.z;
        for (int i = 0; i < 8; ++i) {
            const double v = at + ((i & 1) ? half : -half) * n.x + ((i & 2) ? half : -half) * n.y + ((i & 4) ? half : -half) * n.z;
            if (!(std::fabs(v) > corner_reach[i]) || (v > 0.0) != (at > 0.0)) return false;
        }
        return true;
    };
    struct Vote {
        float3 q, n;
        int side;
        double least;
    };
    thread_local std::vector<Vote> votes;
    votes.clear();
    int seen_sides = 0;  // bit 0: a feature says outside, bit 1: inside
    // One feature that may be the closest to some point of the cell: the cell must lie on one side
    // of its plane (through q, normal n), and it must not be an open rim, unless it is dominated.
    const auto one_side = [&](const float3& q, const float3& n, bool rim) {
        if (!(length_squared(n) > 0.5f)) return false;
        double lo, hi;
        range(q, D3(n), lo, hi);
        const int s = lo >= margin ? 1 : hi <= -margin ? -1 : 0;
        if (rim || s == 0) {
            const bool ok = s != 0 && dominated(q, n);
            return ok;
        }
        votes.push_back(Vote{q, n, s, s > 0 ? lo : -hi});
        seen_sides |= s > 0 ? 1 : 2;
        return true;
    };
    // The regions of the mesh's features (Ericson's regions of the closest point on a triangle,
    // intersected over the faces that share the feature, since a closest point is the closest
    // point of each of them), each tested against the whole cell: a feature whose region misses the
    // cell, or that lies farther than `radius`, is nobody's closest feature there.
    const double radius2 = radius * radius;
    const auto beyond = [&](const float3& q, const float3& u) {  // the whole cell has dot(p - q, u) > 0
        double lo, hi;
        range(q, D3(u), lo, hi);
        return lo > 0.0;
    };
    // Each vertex once: marked in a per-thread table by this call's generation.
    thread_local std::vector<uint32_t> stamp;
    thread_local uint32_t generation = 0;
    if (stamp.size() < geometry_.points.size() || ++generation == 0) {
        stamp.assign(std::max(stamp.size(), geometry_.points.size()), 0);
        generation = 1;
    }
    thread_local std::vector<int32_t> vertices;
    vertices.clear();
    for (size_t i = 0; i < faces.size(); ++i) {
        if (face_distance[i] > radius) continue;
        const int32_t f = faces[i];
        const auto& t = geometry_.tris[f];
        const size_t f3 = size_t(f) * 3;
        // The face itself: points whose projection falls inside it (its prism).
        if (!beyond(geometry_.points[t[0]], edge_out_[f3]) && !beyond(geometry_.points[t[1]], edge_out_[f3 + 1]) &&
            !beyond(geometry_.points[t[2]], edge_out_[f3 + 2]) && !one_side(geometry_.points[t[0]], geometry_.face_normals[f], false)) {
            return fail;
        }
        for (int k = 0; k < 3; ++k) {
            const int32_t a = t[k], b = t[(k + 1) % 3];
            if (stamp[a] != generation) {
                stamp[a] = generation;
                vertices.push_back(a);
            }
            // Each edge once: from the face that has it as a -> b with a < b, or from its only face.
            const float3& other = edge_other_out_[f3 + k];
            const bool rim = geometry_.boundary_edge[f3 + k];
            if (!rim && a > b) continue;
            const float3 &pa = geometry_.points[a], &pb = geometry_.points[b];
            const float3& e = edge_dir_[f3 + k];
            const double ab = double(e.x) * (double(pb.x) - pa.x) + double(e.y) * (double(pb.y) - pa.y) + double(e.z) * (double(pb.z) - pa.z);
            const double along = std::clamp((cx - pa.x) * e.x + (cy - pa.y) * e.y + (cz - pa.z) * e.z, 0.0, ab);
            const double qx = pa.x + e.x * along - cx, qy = pa.y + e.y * along - cy, qz = pa.z + e.z * along - cz;
            if (qx * qx + qy * qy + qz * qz > radius2) continue;
            if (beyond(pa, -e) || beyond(pb, e) || beyond(pa, -edge_out_[f3 + k]) || (!rim && beyond(pa, -other))) continue;
            if (!one_side(pa, geometry_.edge_normals[f3 + k], rim)) return fail;
        }
    }
    for (const int32_t a : vertices) {
        const float3& pa = geometry_.points[a];
        const double qx = pa.x - cx, qy = pa.y - cy, qz = pa.z - cz;
        if (qx * qx + qy * qy + qz * qz > radius2) continue;
        // The vertex's region: no edge from it leads toward the point.
        bool region = true;
        for (int32_t i = ring_offsets_[a]; region && i < ring_offsets_[a + 1]; ++i) region = !beyond(pa, ring_dirs_[i]);
        if (region && !one_side(pa, geometry_.vertex_normals[a], geometry_.boundary_vertex[a])) return fail;
    }
    // Features that disagree: those that cannot be closest anywhere in the cell do not count.
    if (seen_sides == 3) {
        seen_sides = 0;
        size_t w = 0;
        for (const Vote& v : votes) {
            if (dominated(v.q, v.n)) continue;
            votes[w++] = v;
            seen_sides |= v.side > 0 ? 1 : 2;
        }
        votes.resize(w);
    }
    if (seen_sides != 1 && seen_sides != 2) return fail;
    const int sign = seen_sides == 1 ? 1 : -1;
    double least = std::numeric_limits<double>::infinity();
    for (const Vote& v : votes) least = std::min(least, v.least);
    // The centre's own exact answer, where there is one, must agree (it does whenever the argument
    // above holds; a mesh whose float normals disagree with its geometry is left to the exact query).
    if (!parent && (dc < 0.0f) != (sign < 0)) return fail;
    return Certificate{float(sign < 0 ? -distance : distance), float(least)};
}

uint64_t FarField::slot_value(int level, int64_t ix, int64_t iy, int64_t iz, const Faces* parent, std::unique_ptr<Faces>& kept) const
{
    const Certificate c = certify(level, ix, iy, iz, parent, &kept);
    if (c.m != kSplit) {
        kept.reset();
        // All-zero bits mean "not examined": a certificate {0, 0} bounds nothing, as kExact does.
        const uint64_t v = pack(c.dc, c.m);
        return v != 0 ? v : pack(0.0f, kExact);
    }
    const auto it = splits_.emplace_back();
    it->faces = std::move(*kept);
    kept.reset();
    return uint64_t(it - splits_.begin()) << 32 | (pack(0.0f, kSplit) & 0xffffffffu);
}

uint64_t FarField::resolve(uint64_t& slot, int level, int64_t ix, int64_t iy, int64_t iz, const Faces* parent) const
{
    const uint64_t seen = __atomic_load_n(&slot, __ATOMIC_ACQUIRE);
    if (seen != 0) return seen;
    std::unique_ptr<Faces> kept;
    const uint64_t mine = slot_value(level, ix, iy, iz, parent, kept);
    uint64_t expected = 0;
    // The Split (if any) is complete before the release makes its index visible.
    if (__atomic_compare_exchange_n(&slot, &expected, mine, false, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) return mine;
    // Another thread stored the same answer first; a Split made here is left unused, emptied.
    if (slot_m(mine) == kSplit) std::vector<int32_t>().swap(splits_[size_t(mine >> 32)].faces.faces);
    return expected;
}

uint64_t FarField::first_level(int64_t ix, int64_t iy, int64_t iz) const
{
    const uint64_t dx = uint64_t(ix - dense_lo_[0]), dy = uint64_t(iy - dense_lo_[1]), dz = uint64_t(iz - dense_lo_[2]);
    if (dense_ && dx < uint64_t(dense_n_[0]) && dy < uint64_t(dense_n_[1]) && dz < uint64_t(dense_n_[2])) {
        return resolve(dense_[(dx * uint64_t(dense_n_[1]) + dy) * uint64_t(dense_n_[2]) + dz], kStartLevel, ix, iy, iz, nullptr);
    }
    const uint64_t key = pack_key(kStartLevel, ix, iy, iz);
    if (const auto it = table_.find(key); it != table_.end()) return it->second;
    std::unique_ptr<Faces> kept;
    const uint64_t mine = slot_value(kStartLevel, ix, iy, iz, nullptr, kept);
    const auto [it, inserted] = table_.emplace(key, mine);
    if (!inserted && slot_m(mine) == kSplit) std::vector<int32_t>().swap(splits_[size_t(mine >> 32)].faces.faces);
    return it->second;
}

bool FarField::voxel_of(const float3& p, int64_t v[3]) const
{
    const double x = (double(p.x) - ox_) * inv_voxel_, y = (double(p.y) - oy_) * inv_voxel_, z = (double(p.z) - oz_) * inv_voxel_;
    if (!(std::fabs(x) < kLimit && std::fabs(y) < kLimit && std::fabs(z) < kLimit)) return false;  // also NaN
    v[0] = int64_t(std::floor(x)), v[1] = int64_t(std::floor(y)), v[2] = int64_t(std::floor(z));
    return true;
}

uint64_t FarField::locate(int64_t vx, int64_t vy, int64_t vz, int& level) const
{
    // The cell this thread answered from last: consecutive queries walk along a curve, mostly
    // within one cell, and the walk down the levels is then skipped.
    thread_local Last last;
    level = last.level;
    uint64_t slot = last.slot;
    if (!(last.owner == id_ && (vx >> level) == last.ix && (vy >> level) == last.iy && (vz >> level) == last.iz)) {
        level = kStartLevel;
        slot = first_level(vx >> level, vy >> level, vz >> level);
        while (slot_m(slot) == kSplit && level > kMinLevel) {
            Split& split = splits_[size_t(slot >> 32)];
            --level;
            const int child = int((vx >> level) & 1) | int((vy >> level) & 1) << 1 | int((vz >> level) & 1) << 2;
            slot = resolve(split.children[child], level, vx >> level, vy >> level, vz >> level, &split.faces);
        }
        last = Last{id_, level, vx >> level, vy >> level, vz >> level, slot};
    }
    return slot;
}

float FarField::bound(const float3& p) const
{
    // The voxel; a cell of level L is the voxel's coordinates shifted right by L (floor(x / 2^L)).
    int64_t v[3];
    if (!voxel_of(p, v)) return 0.0f;
    return certified_lower(v, &p);
}

float FarField::voxel_lower(int64_t vx, int64_t vy, int64_t vz) const
{
    if (!(std::max({std::llabs(vx), std::llabs(vy), std::llabs(vz)}) < int64_t(kLimit) - 1)) return 0.0f;
    const int64_t v[3] = {vx, vy, vz};
    return certified_lower(v, nullptr);
}

float FarField::certified_lower(const int64_t v[3], const float3* p) const
{
    int level = 0;
    const uint64_t slot = locate(v[0], v[1], v[2], level);
    const float m = slot_m(slot), dc = slot_dc(slot);
    if (m < 0.0f) return 0.0f;
    const int64_t ix = v[0] >> level, iy = v[1] >> level, iz = v[2] >> level;
    const double side = voxel_ * double(int64_t(1) << level);
    const float3 cf(float(ox_ + side * (double(ix) + 0.5)), float(oy_ + side * (double(iy) + 0.5)), float(oz_ + side * (double(iz) + 0.5)));
    // The way from the cell's centre and the largest coordinate: p's own, or, for the whole voxel,
    // their largest over its corners (both are convex in the point).
    double reach = 0.0, coordinate = 0.0;
    const auto take = [&](double x, double y, double z) {
        const double dx = x - cf.x, dy = y - cf.y, dz = z - cf.z;
        reach = std::max(reach, std::sqrt(dx * dx + dy * dy + dz * dz));
        coordinate = std::max(coordinate, max_abs(x, y, z));
    };
    if (p) {
        take(p->x, p->y, p->z);
    }
    else {
        for (int k = 0; k < 8; ++k) take(ox_ + voxel_ * double(v[0] + (k & 1)), oy_ + voxel_ * double(v[1] + ((k >> 1) & 1)), oz_ + voxel_ * double(v[2] + ((k >> 2) & 1)));
        // A point counted in this voxel lies in it up to the rounding of its index (a relative
        // 1e-16 of its coordinates): a millionth of the voxel covers that many times over.
        reach += 1e-6 * voxel_;
        coordinate += 1e-6 * voxel_;
    }
    double lower = std::max(std::fabs(double(dc)) - reach, double(m));
    // Stay clear of the float rounding of the distance the exact query would return.
    lower -= 1e-5 * (coordinate + std::fabs(double(dc)) + side);
    if (!(lower > 0.0)) return 0.0f;
    return float(dc < 0.0f ? -lower : lower);
}

void FarField::first_level_box(int64_t lo[3], int64_t n[3]) const
{
    for (int k = 0; k < 3; ++k) lo[k] = dense_lo_[k], n[k] = dense_n_[k];
}

FarField::Counts FarField::counts() const
{
    Counts c;
    const auto count = [&c](uint64_t slot) {
        if (slot == 0) return;
        const float m = slot_m(slot);
        if (m == kSplit) ++c.split;
        else if (m == kExact) ++c.exact;
        else ++c.certified;
    };
    if (dense_) {
        const int64_t n = dense_n_[0] * dense_n_[1] * dense_n_[2];
        for (int64_t i = 0; i < n; ++i) count(__atomic_load_n(&dense_[i], __ATOMIC_ACQUIRE));
    }
    for (const auto& [key, slot] : table_) count(slot);
    for (const Split& split : splits_) {
        for (const uint64_t& child : split.children) count(__atomic_load_n(&child, __ATOMIC_ACQUIRE));
    }
    return c;
}

}  // namespace groom::detail
