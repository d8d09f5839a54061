// NearFaces: the exact closest face of the scalp's mesh for points outside the narrow band, found
// among a short list of candidates kept per cell of space instead of by a CGAL AABB-tree search
// (`groom probe` of 2M hair points on Sintel spent 60% of its time in that search, perf; about
// 1.7 us a point).
//
// Space is cut into cubes of kCellVoxels voxels aligned with the level set. For a cell with centre
// c and half diagonal r, let D be the distance from c to any one face (an upper bound of the
// distance d(c); the AABB tree's answer at c). Every point p of the cell has its closest face within
// d(p) <= D + r of p, so within D + 2r of c: the cell keeps every face within D + 2r of c (with a
// margin for rounding), sorted by distance from c. A query scans them in that order, measures each
// in double and stops once a face's distance from c, less |p - c|, exceeds the best found.
//
// The answer is the face with the smallest double-precision distance, the lowest index among exact
// ties, over the whole mesh (the candidates hold every face that can come within the margin of the
// best): a pure function of p, the same for any cell layout, order or thread count. The AABB tree
// picked the same face except where two faces tie to double rounding (a shared edge or vertex:
// the same closest point, up to float rounding of its computation from the other face).
//
// The list is cut to the faces that can be closest to some point of the cell (MeshQuery::
// faces_seen_from: the patch around the centre's closest point that the cell can see), so a cell
// far out keeps a short list too, and bigger cells pay off where points are sparse: `groom probe`
// picks the cell size from how its points crowd (kCellVoxels for hair, larger for points spread
// through a box).
//
// Cells are made on first use and kept in a lock-free table. A cell farther than kMaxReachCells
// cells from the mesh, or whose list would exceed kMaxCandidates, keeps no list: its points go to
// the tree. So does every point when the mesh's faces are small for the cells (mean area below
// kMinFaceArea faces of a kCellVoxels cell): the mesh a .vdb gives, its level set's zero crossing,
// has 24 times Sintel's faces; there the lists ran to hundreds of faces, and 2M hair points took
// 10% longer than the tree alone.
#pragma once

#include "fields/cell_key_hash.h"
#include "kernel/math/vec.h"

#include <tbb/concurrent_unordered_map.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace groom::detail {

struct MeshGeometry;
class MeshQuery;

class NearFaces {
public:
    static constexpr int kCellVoxels = 2;  ///< the smallest cells, for points as crowded as hair
    static constexpr double kMaxReachCells = 24.0;
    static constexpr size_t kMaxCandidates = 256;
    static constexpr double kMinFaceArea = 0.5;

    /// Cells of `cell_voxels` voxels (kCellVoxels times a power of two).
    NearFaces(const MeshGeometry& geometry, const MeshQuery& query, const float3& origin, float voxel, int cell_voxels = kCellVoxels);
    ~NearFaces();
    NearFaces(const NearFaces&) = delete;
    NearFaces& operator=(const NearFaces&) = delete;

    /// The closest face of the mesh to p (see above), or -1 where p's cell keeps no list (p not
    /// finite, beyond 2^20 cells of the origin, or too far out): the caller asks the tree.
    int32_t closest_face(const float3& p) const;

    /// Cells made so far, and how many of them keep no list (for tests and benchmarks).
    struct Counts {
        int64_t cells = 0, without_list = 0, candidates = 0;
    };
    Counts counts() const;

private:
    struct Cell {
        float3 centre;
        std::vector<int32_t> faces;   ///< sorted by distance from the centre, then index
        std::vector<double> reach;    ///< each one's distance from the centre, less the rounding margin
        bool listed = false;          ///< false: no list, ask the tree
    };
    const Cell& cell(int64_t ix, int64_t iy, int64_t iz) const;
    std::unique_ptr<Cell> make(int64_t ix, int64_t iy, int64_t iz) const;

    uint64_t id_;
    bool enabled_ = false;
    const MeshGeometry& geometry_;
    const MeshQuery& query_;
    double ox_, oy_, oz_, side_, inv_side_;
    mutable tbb::concurrent_unordered_map<uint64_t, std::unique_ptr<Cell>, CellKeyHash> table_;
};

}  // namespace groom::detail
