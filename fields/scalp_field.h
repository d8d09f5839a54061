// ScalpField: the scalp as an OpenVDB signed-distance level set plus the repaired mesh it came from.
// Built from any mesh a user has (repair in fields/mesh_repair.cpp, report in fields/mesh_repair.h),
// or loaded from a .vdb written by `groom scalp`. OpenVDB, OpenMesh and CGAL stay behind a pimpl so
// ops/ and cli/ compile without their headers.
//
// Queries are const and thread-safe (they only read; the query layout of the band, BrickMap, the
// mesh's AABB tree and the far field's certificates are each built on first use). Inside the narrow
// band they interpolate the grid; outside it they answer exactly from the mesh through a CGAL AABB
// tree, so every point in space gets a correct answer, except distance_within, which answers points
// certified to be far enough out (or in) with a bound, without the search.
#pragma once

#include "fields/mesh_repair.h"
#include "fields/surface.h"
#include "kernel/polygon_soup.h"
#include "kernel/progress.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace groom {

class OutputBatch;  // kernel/io/atomic_file.h

struct ScalpBuildParams {
    float voxel_size = 0.0f;      ///< scene units; 0 = automatic (bounding-box diagonal / 256)
    float band_voxels = 3.0f;     ///< narrow-band half width in voxels; 1..64
    bool flip = false;            ///< treat the mesh as inside out (after automatic orientation)
    /// Bytes; larger grids are refused with a suggested voxel size. 0 = the command's budget
    /// (kernel/memory_budget.h: --memory, else half the machine's memory).
    uint64_t memory_budget = 0;
    bool remove_enclosed_shells = true;   ///< drop shells lying inside a larger one (eyes, teeth)
    /// Close the mesh's open rims up to this length, scene units (eye sockets, a mouth; not the
    /// neck): 0 = none. `groom scalp --fill-holes`.
    float fill_holes = 0.0f;
    /// The field will be queried (every command but `groom scalp`, which only writes it): its query
    /// bricks, built on the first query, count in the memory estimate.
    bool for_queries = true;
    std::string source = "scalp";         ///< names the mesh (its file) in messages
    /// An OBJ mesh: only the faces of the object (`o`) or group (`g`) of this name (the head, not
    /// its eyes, teeth or hair proxies); empty = every face. Not for a .vdb (already one surface).
    std::string group;
    /// A .vdb: the grid to use (--scalp-grid); empty = the grid named "scalp", else the file's only
    /// float level set (read_scalp_vdb). Not for a mesh.
    std::string grid;
    void validate() const;        ///< throws InvalidParam naming the option, value and range
};

/// One sampled root on the scalp.
struct SurfaceSample {
    float3 position;
    float3 normal;      ///< unit outward normal of the field at `position`
    int32_t face = -1;  ///< triangle of the repaired mesh it was drawn on
};

class ScalpField final : public Surface {
public:
    ScalpField();
    ~ScalpField() override;
    ScalpField(ScalpField&&) noexcept;
    ScalpField& operator=(ScalpField&&) noexcept;

    /// Signed distance (scene units; negative inside). Trilinear in the band, exact from the mesh outside
    /// it and where the band's gradient is short (a crease or a feature thinner than the voxels), as query().
    float distance(const float3& p) const override;
    /// Unit outward normal: the normalised gradient of the distance (central differences of the grid,
    /// interpolated trilinearly over the cell's voxels that are in the band, so it reaches a voxel
    /// beyond where the distance itself is interpolated; (p - closest) / distance from the mesh
    /// farther out).
    float3 normal(const float3& p) const override;
    /// Projection onto the surface: p - d * n from one trilinear sample in the band; exact closest
    /// point on the mesh outside it.
    float3 closest_point(const float3& p) const override;
    /// Signed distance, unit normal and closest point in one call (cheaper than three).
    float query(const float3& p, float3& normal, float3& closest) const override;
    /// query(), with the closest face outside the band found among candidates kept per cell
    /// (fields/near_faces.h) instead of by an AABB-tree search: cells of 2 voxels at level 0, twice
    /// that per level up to kDenseLevels - 1. Several times faster per point where many points share
    /// cells (hair: 2M points of 62,500 hairs on Sintel, 47 a 2-voxel cell; points spread through
    /// the head's box, about 30 a 4-voxel cell), slower where they do not (each cell costs a tree
    /// search and a walk of the tree for the faces it can see). The same answers as query()
    /// except at ties between faces (a shared edge or vertex): the same closest point to float
    /// rounding. Which one a command calls must not depend on timing (the bytes would).
    static constexpr int kDenseLevels = 3;
    float query_dense(const float3& p, float3& normal, float3& closest, int level = 0) const;
    /// The side of query_dense's cells at `level`, scene units (for a caller counting points per cell).
    float dense_cell_size(int level = 0) const;
    /// distance(p) in the band and wherever it is below `reach`; outside the band, where a cell of
    /// space around p is certified to lie on one side of the scalp at least `reach` away, that
    /// bound instead (fields/far_field.h): no exact mesh search, and the same answer as distance(p)
    /// to every comparison with a threshold in (-reach, reach].
    float distance_within(const float3& p, float reach) const override;
    /// From p's voxel's byte (fields/clear_cells.h): the voxel's lower bound of distance_within,
    /// worked out on the first question in it, compared with `need`.
    bool known_clear(const float3& p, float need) const override;

    /// False when the band holds a seam (neighbouring voxels differing by more than 1.2 voxels):
    /// an open mesh's rims, overlapping shells that disagree on inside.
    bool lipschitz() const override;
    /// The 75th percentile of |distance| at the repaired mesh's vertices and triangle centroids
    /// (points on the mesh, where the exact answer is 0), at most half a voxel; worked out on the
    /// first call. A hair's half width on Lee Perry-Smith is 0.0007, and laid on the field at the
    /// default voxel (0.05) 7.9% of its edge hairs' points were under the scan's skin by more than
    /// that (a trial, measured against a field at a fifth the voxel); lifted by the median none
    /// were but 0.16%, by the 75th percentile none, the hair 0.0037 above the fine field (0.2 mm).
    float surface_tolerance() const override;

    /// True when the mesh had texture coordinates (OBJ `vt`, PLY u/v, s/t or texcoord), kept in
    /// the .vdb `groom scalp` writes. surface_uv: the UV at the closest point of the user's mesh
    /// (fields/uv_map.h; seams answered by the lowest-numbered triangle).
    bool has_uvs() const override;
    bool surface_uv(const float3& p, float& u, float& v) const override;

    float voxel_size() const;
    float band_voxels() const;
    /// Voxels stored in the narrow band (the level set's active voxels).
    int64_t active_voxels() const;
    /// Band voxels beside a jump of the distance (an open mesh's rims, shells that disagree on
    /// inside), left out of the interpolated band; 0 exactly when lipschitz().
    int64_t seam_voxels() const;
    Bounds3 bounds() const;
    /// True when built from a mesh or loaded from a .vdb that carries it (every .vdb `groom scalp`
    /// writes); false when the mesh was extracted from a loaded .vdb's zero crossing (exact to
    /// about a voxel rather than to the original mesh).
    bool has_source_mesh() const;
    /// The name of the grid the field was read from ("scalp" for groom's own .vdb and for a field
    /// built from a mesh; another program's, e.g. "surface", when read_scalp_vdb picked it).
    const std::string& grid_name() const;
    /// The repaired triangle mesh the queries fall back to (oriented outward).
    PolygonSoup mesh() const;
    int64_t num_faces() const;

    /// `count` points area-uniformly distributed over the part of the scalp within `radius` of
    /// `center` (radius <= 0: the whole surface). Deterministic for a given seed and independent of
    /// the thread count: sample i is drawn from Rng(seed, i). Returns fewer (possibly none) only
    /// when the ball holds no surface.
    std::vector<SurfaceSample> sample_ball(const float3& center, float radius, int64_t count, uint64_t seed) const;
    /// The same over the faces with face_mask[f] != 0 (size num_faces()). Throws InvalidParam on a size mismatch.
    std::vector<SurfaceSample> sample_faces(std::span<const uint8_t> face_mask, int64_t count, uint64_t seed) const;

    struct Impl;
    Impl& impl() { return *impl_; }
    const Impl& impl() const { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

/// Repairs `soup` (see RepairReport) and converts it to a narrow-band level set named "scalp".
/// Throws InvalidGeometry (empty mesh, NaN, index out of range, nothing left after repair, a mesh
/// whose size overflows float or that lies too far from the origin for float positions to resolve
/// a voxel), InvalidParam (bad params) or LimitExceeded (the grid would exceed params.memory_budget,
/// or allocating it failed; the message gives the estimate and suggests a voxel size).
ScalpField build_scalp(const PolygonSoup& soup, const ScalpBuildParams& params = {}, RepairReport* report = nullptr,
                       Progress* progress = nullptr);

/// Writes the level set (grid "scalp", class level set, half-float off) to a .vdb file atomically:
/// readable by vdb_print, pyopenvdb and Houdini. Throws IoError.
void write_scalp(const ScalpField& scalp, const std::string& path);
/// The same into `batch` (kernel/io/atomic_file.h), renamed into place with the command's other outputs.
void write_scalp(const ScalpField& scalp, const std::string& path, OutputBatch& batch);

/// Reads a float level set from a .vdb (groom's, vdb_tool's, Houdini's, pyopenvdb's). The grid used:
/// `grid` when given (InvalidParam when the file has no grid of that name); else the one named
/// "scalp" (what `groom scalp` writes); else the file's only float level set, whatever its name
/// (vdb_tool's "mesh2ls_NAME", Houdini's "surface"): a float grid of class level set, or of class
/// unknown whose values are plainly a narrow-band signed distance (every inactive value +-background,
/// active values within +-background of both signs). Several such grids, or none, is a ParseError
/// listing the file's grids (name, value type, class) and the way on (--scalp-grid NAME; the head's
/// mesh). grid_name() tells which was used. The mesh for
/// far queries and sampling is the repaired mesh `groom scalp` stores in the grid's metadata
/// "groom_source_mesh" (then every answer is the mesh's, to the bit), else, for other programs' and
/// older groom's files, one extracted from the zero crossing (adaptive, within about a voxel). What OpenVDB decodes is checked
/// before use (a truncated or corrupt file is a ParseError naming it, never a crash): one float grid
/// of class level set, a linear transform with uniform, finite, positive voxels, a finite positive
/// background, a tree with active voxels whose values and index bounds are sane. Throws IoError /
/// ParseError / InvalidParam.
ScalpField read_scalp_vdb(const std::string& path, Progress* progress = nullptr, const std::string& grid = {});

/// Loads the scalp for any command's --scalp: a .vdb (read_scalp_vdb, `params.grid`), a
/// mesh converted on the fly with `params`, or a field stored in memory under "mem:NAME" (see
/// store_memory_scalp). Throws ParseError/IoError/InvalidParam/InvalidGeometry.
std::shared_ptr<const ScalpField> load_scalp(const std::string& path, const ScalpBuildParams& params = {}, Progress* progress = nullptr);

/// A field a program embedding groom (the Python module) passes to a command as "mem:NAME" in
/// place of a scalp file (kernel/io/memory_files.h does the same for curves).
void store_memory_scalp(const std::string& path, std::shared_ptr<const ScalpField> scalp);
void erase_memory_scalp(const std::string& path);

}  // namespace groom
