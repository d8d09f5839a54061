// FarField: what the scalp field knows about a point outside its narrow band without searching
// the mesh for its closest point: the sign of the distance and a lower bound on its size. Most
// callers only ask "is this point at least `need` outside?" (keep_outside, cull, braid's
// clearance), and before this every point past the band's 3 voxels paid an exact AABB-tree search
// for that answer (70% of `groom generate` on Sintel's head, perf; 0.4 s a point at 1e20).
//
// Space is cut into cubic cells aligned with the level set's voxels, 8 voxels first, split into
// eight down to 1 voxel where a cell cannot be certified. A cell's certificate holds for every
// point p of the cell (c its centre, r its half diagonal, d_c the distance at c, s0 the closest
// surface point of c):
//   - the exact query's sign at p. That sign is the angle-weighted pseudo-normal's (Baerentzen &
//     Aanaes 2005) at p's closest feature (face, edge or vertex), or the winding number's where that
//     feature lies on an open rim (MeshQuery). Every feature that can be closest to a point of the
//     cell is examined: it lies within |d_c| + 2 r of c (and within r of the farthest corner's
//     distance to s0), and its region (Ericson's region of the closest point on a triangle,
//     intersected over the faces that share the feature) meets the cell. Each such feature must
//     have the whole cell on one side of its pseudo-normal's plane, the same side for all, and must
//     not be a rim; a feature farther from every point than s0 (decided at the corners, where
//     |p - s0| minus a plane distance is largest) cannot be closest and is not counted.
//   - |d(p)| >= max(|d_c| - |p - c|, m): the distance is 1-Lipschitz, and no point of the cell is
//     nearer than m to the plane of any feature that can be closest.
// This is the exact query's own rule, so open meshes answer as they always did. (The level set's
// inactive tiles carry a sign too, from OpenVDB's signedFloodFill, but on a mesh with openings,
// Sintel's bust among them, flood fill leaks through them and disagrees with the exact rule.)
// A cell of the first level starts from an exact query at its centre and the tree's faces near
// it; a smaller cell starts from its parent's distance and faces, with no tree search.
//
// Certificates are computed on first use and kept lock-free: the first level's in a block indexed
// by cell coordinates around the mesh (a hash table beyond it), smaller cells' in their parent's
// eight children; each is a pure function of its cell, so answers do not depend on the order or
// the thread that computed them.
#pragma once

#include "fields/cell_key_hash.h"
#include "kernel/math/vec.h"

#include <tbb/concurrent_unordered_map.h>
#include <tbb/concurrent_vector.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace groom::detail {

struct MeshGeometry;
class MeshQuery;

class FarField {
public:
    /// `origin` and `voxel`: the level set's index-to-world mapping (cells are aligned with its voxels).
    FarField(const MeshGeometry& geometry, const MeshQuery& query, const float3& origin, float voxel);
    ~FarField();
    FarField(const FarField&) = delete;
    FarField& operator=(const FarField&) = delete;

    /// A signed value L with the sign of the exact signed distance at p and 0 < |L| <= |distance|
    /// (clear of the float rounding of that distance), or 0 when p's cell has no certificate (on
    /// the surface, beside a fold or an open rim; or p not finite or beyond 2^19 voxels of the
    /// grid's origin, where the exact query answers).
    float bound(const float3& p) const;

    /// The voxel holding p, as bound() counts it (floor of the index coordinates, in double);
    /// false where bound() answers 0 for being too far or not finite.
    bool voxel_of(const float3& p, int64_t v[3]) const;
    /// A value with the sign of bound() and at most its size at every point of the voxel
    /// [v, v + 1]^3 (index coordinates), or 0 where the voxel's cell has no certificate (or some
    /// point of it gets bound() 0). Certifies the cell on first use, as bound() does.
    float voxel_lower(int64_t vx, int64_t vy, int64_t vz) const;
    /// The first level's cells (8 voxels) over the mesh's box and 8 cells round it, where their
    /// slots need no hashing: cells [lo, lo + n) per axis (n = 0 for an empty mesh).
    void first_level_box(int64_t lo[3], int64_t n[3]) const;

    /// Cells examined so far, per outcome (for tests and benchmarks).
    struct Counts {
        int64_t certified = 0, split = 0, exact = 0;
    };
    Counts counts() const;

private:
    struct Certificate {
        float dc;  ///< distance at the cell centre, signed by the cell's sign (unsigned where m < 0)
        float m;   ///< lower bound of |d| over the cell from the planes; < 0: no certificate (see .cpp)
    };
    /// The faces near a cell that failed, for its children: every face within `radius` of `center`.
    struct Faces {
        float3 center;
        float distance;  ///< |d| at `center`
        double radius;
        std::vector<int32_t> faces;
    };
    /// A cell that failed and is split into eight: its faces, and its children's slots.
    struct Split {
        Faces faces;
        uint64_t children[8] = {};  ///< slots (see .cpp), read and written atomically
    };
    struct Last {
        uint64_t owner = 0;  ///< id_ of the field
        int level = 0;
        int64_t ix = 0, iy = 0, iz = 0;
        uint64_t slot = 0;
    };
    /// `parent`: the faces near the enclosing cell (which failed), or null for the first level.
    /// `kept`, when given: receives this cell's faces for its children.
    Certificate certify(int level, int64_t ix, int64_t iy, int64_t iz, const Faces* parent, std::unique_ptr<Faces>* kept) const;
    /// The slot's value for the cell: a certificate, or a split cell's Split. Computed on first use.
    uint64_t slot_value(int level, int64_t ix, int64_t iy, int64_t iz, const Faces* parent, std::unique_ptr<Faces>& kept) const;
    /// The cell's slot, filled on first use by a compare-exchange (the first thread's answer is kept;
    /// every thread computes the same one).
    uint64_t resolve(uint64_t& slot, int level, int64_t ix, int64_t iy, int64_t iz, const Faces* parent) const;
    /// The slot of a first-level cell: in the dense block around the mesh, else in the hash table.
    uint64_t first_level(int64_t ix, int64_t iy, int64_t iz) const;
    /// The slot of the smallest examined cell holding voxel v, and its level (walking down the
    /// splits, certifying on first use); the last answer per thread is kept.
    uint64_t locate(int64_t vx, int64_t vy, int64_t vz, int& level) const;
    /// bound()'s value at p, or with p null a value at most bound()'s size at every point of voxel v.
    float certified_lower(const int64_t v[3], const float3* p) const;

    uint64_t id_;
    const MeshGeometry& geometry_;
    const MeshQuery& query_;
    double ox_, oy_, oz_, voxel_, inv_voxel_;
    std::vector<float3> edge_dir_, edge_out_, edge_other_out_;  ///< per face * 3 + k
    std::vector<float3> face_centre_;                            ///< per face: centroid
    std::vector<float> face_radius_;                             ///< per face: reach of its vertices from the centroid
    std::vector<int32_t> ring_offsets_;                          ///< per vertex + 1
    std::vector<float3> ring_dirs_;                              ///< unit directions of each vertex's edges
    // The first level's slots over the mesh's box and a margin, indexed without hashing (the hash
    // table's find was 12% of `groom curl --scalp` on Sintel, perf): zero pages from calloc, so only
    // the cells queries reach take memory. Cells outside it go to the hash table, insert-only and
    // growing with what the queries reach (an open-addressing table of fixed size overflowed on
    // 200,000 points spread over nefertiti's head); lookups take no lock.
    struct FreeDense {
        void operator()(uint64_t* p) const;
    };
    std::unique_ptr<uint64_t[], FreeDense> dense_;
    int64_t dense_lo_[3] = {0, 0, 0}, dense_n_[3] = {0, 0, 0};
    mutable tbb::concurrent_unordered_map<uint64_t, uint64_t, CellKeyHash> table_;
    /// Split cells' faces and children, never moved once made (slots hold their index).
    mutable tbb::concurrent_vector<Split> splits_;
};

}  // namespace groom::detail
