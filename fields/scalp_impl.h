// Internals of ScalpField shared by the fields/*.cpp that build, load and query it. Includes
// OpenVDB, OpenMesh and CGAL: never include this outside fields/.
#pragma once

#include "fields/brick_map.h"
#include "fields/clear_cells.h"
#include "fields/far_field.h"
#include "fields/mesh_repair.h"
#include "fields/near_faces.h"
#include "fields/scalp_field.h"
#include "fields/uv_map.h"
#include "fields/winding_number.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <openvdb/openvdb.h>

#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace groom {

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

namespace detail {

/// Which part of a triangle a closest point lies on: the face interior, edge k (v_k -> v_k+1) or vertex k.
enum class Feature : uint8_t { Face, Edge0, Edge1, Edge2, Vertex0, Vertex1, Vertex2 };

/// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5) and the
/// feature it lies on, which selects the pseudo-normal that signs the distance.
float3 closest_on_triangle(const float3& p, const float3& a, const float3& b, const float3& c, Feature& feature);

/// Whether no point within `rho` of a centre m can be nearer than s0 (a point of the mesh) to any
/// point p of a region, so that no face inside that sphere is the closest face of any p there.
/// Points of the sphere are at least |p - m| - rho from p, so none is nearer when
/// |p - m| > |p - s0| + rho for every p; squared, with |p - s0| <= `reach` over the region, that
/// holds when |p - m|^2 - |p - s0|^2 > 2 rho reach + rho^2. The left side is linear in p (the
/// bisector plane of m and s0): the caller gives its value at the region's centre, `at`, and the
/// most it falls below that over the region, `spread` (at a box's corner, or over a ball), plus
/// `rounding` for the float rounding of its terms (far_field.cpp over a cell's box,
/// MeshQuery::faces_seen_from over a ball).
inline bool beyond_bisector(double at, double spread, double rho, double reach, double rounding)
{
    return at - spread > 2.0 * rho * reach + rho * rho + rounding;
}

/// Flat, cache-friendly copy of the repaired mesh with angle-weighted pseudo-normals
/// (Baerentzen & Aanaes 2005): the sign of the distance to the closest point c on feature F is
/// sign(dot(p - c, N_F)), exact for closed and open oriented meshes alike.
struct MeshGeometry {
    std::vector<float3> points;
    std::vector<std::array<int32_t, 3>> tris;
    std::vector<float3> face_normals;    ///< unit, per face
    std::vector<float3> edge_normals;    ///< unit, per face * 3 + k (edge v_k -> v_k+1)
    std::vector<float3> vertex_normals;  ///< unit, angle weighted
    std::vector<double> face_areas;
    std::vector<uint8_t> boundary_edge;    ///< per face * 3 + k: edge has no second face
    std::vector<uint8_t> boundary_vertex;  ///< per vertex: on a hole's or rim's boundary
    float3 bounds_lo, bounds_hi;

    void compute(const TriMesh& mesh);
    /// The same from bare arrays (a mesh stored in a .vdb, fields/source_mesh.h; compute(TriMesh)
    /// goes through it too): a face's corners in the order given, each edge side's opposite face the
    /// one holding the reversed edge, a vertex on the boundary when an edge at it has no second face
    /// or it has no face at all. `tris` must be an oriented manifold (each directed edge once), as
    /// decode_source_mesh() checks.
    void compute(std::vector<float3> points, std::vector<std::array<int32_t, 3>> tris);
    std::vector<int32_t> vertex_face_offsets;  ///< #vertices+1: faces around vertex v are
    std::vector<int32_t> vertex_faces;         ///< vertex_faces[vertex_face_offsets[v] .. [v+1])

    float3 pseudo_normal(int32_t face, Feature feature) const;
    /// From a face near p's closest face, walks to neighbouring faces (sharing a vertex) while they
    /// are closer; returns the local closest face. meshToVolume's polygon index is only near-exact at
    /// the band's edge; this makes every voxel exact.
    int32_t refine_closest_face(const float3& p, int32_t face) const;
    /// Signed distance and closest point to face `f`; `on_boundary` tells whether the closest
    /// feature is a boundary edge or vertex, where the pseudo-normal sign is only local.
    float signed_distance_to_face(const float3& p, int32_t f, float3& closest, bool* on_boundary = nullptr) const;
};

/// Exact queries against the mesh (CGAL AABB tree), for points outside the narrow band.
class MeshQuery {
public:
    explicit MeshQuery(const MeshGeometry& geometry);
    ~MeshQuery();
    /// Signed distance; writes the closest point and its face. A point more than kFarRadii
    /// bounding-sphere radii from the mesh is answered through its stand-in on the same ray at that
    /// distance (the closest point, the sign), with the distance measured in double from p itself:
    /// there the answer is the same to float rounding, and CGAL's exact predicates, which fail
    /// their filters ever more often as p goes out (0.4 s a query at 1e20), stay cheap.
    float signed_distance(const float3& p, float3& closest, int32_t& face) const;
    static constexpr double kFarRadii = 4096.0;
    /// The signed distance and closest point from p's closest face `face` found some other way
    /// (fields/near_faces.h): the pseudo-normal's sign, the winding number's at an open rim, as above.
    float signed_distance_to(const float3& p, int32_t face, float3& closest) const;
    /// The face the tree finds closest to p (finite p; no stand-in, no sign).
    int32_t tree_closest_face(const float3& p) const;
    /// Every face with a point within `radius` of `center` (scene units), in the tree's order, and
    /// with `distances`, each one's distance from `center` (float rounding of its closest point).
    void faces_within(const float3& center, double radius, std::vector<int32_t>& faces, std::vector<double>* distances = nullptr) const;
    /// The faces that can be the closest face of some point p of the ball of radius `r` around
    /// `center`, or come within `slack` of being it: every face with a point t where
    /// |p - t| <= |p - s0| + slack for some such p, `s0` being a point of the mesh (any face
    /// nearer to p than s0 is). Found by walking the tree past the boxes that cannot hold one (see
    /// the .cpp), where faces_within(center, |center - s0| + 2 r + slack) lists every face of a
    /// ball that, far out, holds most of the head. Each with its distance from `center` (float
    /// rounding of its closest point, as faces_within). A superset of those faces, never a subset.
    void faces_seen_from(const float3& center, double r, const double s0[3], double slack, std::vector<int32_t>& faces,
                         std::vector<double>& distances) const;
    /// Inside test by the generalized winding number (> 1/2): robust through the holes of a nearly
    /// closed head (eye sockets, mouth, neck), where a rim's pseudo-normal points anywhere.
    /// `exact_near_half`: decide by the exact sum where the estimate is within 0.03 of 1/2, so the
    /// answer does not depend on the estimate's tree (on the mesh's pose).
    bool inside_by_winding(const float3& p, bool exact_near_half) const;
    /// Pseudo-normal sign, replaced by the winding number when the closest feature is a boundary.
    float sign_fixed(const float3& p, float d, bool on_boundary, bool exact_near_half) const;
    /// The winding number of the mesh, built on first use (thread-safe): only open meshes need it.
    const WindingNumber& winding() const;

private:
    struct Tree;
    /// The tree, built on first use (thread-safe): `groom scalp` signs almost every voxel from
    /// meshToVolume's polygon index and rarely needs it, so building it up front cost every conversion.
    const Tree& tree() const;
    static std::unique_ptr<Tree> build(const MeshGeometry& geometry);
    const MeshGeometry& geometry_;
    mutable std::once_flag built_;
    mutable std::unique_ptr<Tree> tree_;
    mutable std::once_flag winding_built_;
    mutable std::unique_ptr<WindingNumber> winding_;
};

/// Repairs a soup into an oriented, manifold triangle mesh (fields/mesh_repair.cpp).
struct RepairOptions {
    bool orient_outward = true;   ///< closed shells: normals outwards (signed volume)
    bool remove_enclosed = true;  ///< drop shells entirely inside another shell
    bool flip = false;            ///< reverse everything at the end
    double fill_holes = 0.0;      ///< close open rims up to this length (scene units); 0 = none
    std::string what = "mesh";    ///< names the input in messages
    /// Called with the triangles' positions in the face order of the mesh returned, as soon as
    /// those are final: before CGAL's orientation when the soup needs it (that is slow, and only
    /// turns windings and duplicates vertices in place), else before the OpenMesh conversion; and
    /// called again, with the remaining faces, if enclosed shells or buried faces are then removed or holes filled (the earlier
    /// call's faces are void). Lets the distance field start while the repair runs. May throw,
    /// which aborts the repair.
    std::function<void(std::vector<float3> points, std::vector<std::array<int32_t, 3>> triangles)> on_triangles;
};
TriMesh repair_soup(const PolygonSoup& soup, const RepairOptions& options, RepairReport& report, Progress* progress);

/// True when the polygons are triangles forming an oriented manifold (each directed edge used at
/// most once, one fan of faces around every vertex): what polygon_soup_to_polygon_mesh needs.
bool is_oriented_manifold(const std::vector<std::vector<size_t>>& tris, size_t num_points);

/// Throws unless every coordinate is finite and every index in range.
void validate_soup(const PolygonSoup& soup, const std::string& what);

/// openvdb::initialize(), once per process (grid types must be registered before reading a file).
void init_openvdb();

}  // namespace detail

struct ScalpField::Impl {
    openvdb::FloatGrid::Ptr sdf;         ///< "scalp": signed distance, GRID_LEVEL_SET
    /// The grid's name in the .vdb it was read from ("scalp" for groom's own files and for a field
    /// built from a mesh; another program's: "surface", "mesh2ls_head"...). `sdf` itself is renamed
    /// "scalp", so a field written back out is groom's own again.
    std::string grid_name = "scalp";
    float voxel = 0.0f, inv_voxel = 0.0f;
    float3 origin;                       ///< world position of index (0,0,0)
    float band_voxels = 3.0f;            ///< half width in voxels
    detail::MeshGeometry geometry;
    std::unique_ptr<detail::MeshQuery> query;
    bool mesh_exact = true;              ///< false when the mesh was extracted from a loaded .vdb
    /// surface_tolerance(), worked out once.
    mutable std::once_flag tolerance_once;
    mutable float tolerance = 0.0f;
    /// The source mesh's texture coordinates (null when it had none), from the mesh or the .vdb's
    /// grid metadata "groom_uv_mesh" (fields/scalp_file.cpp).
    std::shared_ptr<const detail::UvMap> uv;

    /// Trilinear distance and gradient at p when all 8 surrounding voxels are in the band.
    bool sample(const float3& p, float& d, float3& grad) const
    {
        detail::BandValue v;
        if (!band().sample((p.x - origin.x) * inv_voxel, (p.y - origin.y) * inv_voxel, (p.z - origin.z) * inv_voxel, v)) return false;
        d = v.d;
        grad = float3(v.nx, v.ny, v.nz);
        return true;
    }
    /// The band's outward normal at p: the trilinear gradient over whichever of the 8 surrounding
    /// voxels are in the band, where that is a distance gradient (length above 1/2; shorter at a
    /// sign seam or where most of the cell is outside the band). Reaches about a voxel farther out
    /// than sample(), where the mesh's own normal is a facet's (up to 0.64 degrees off a finely
    /// tessellated sphere at h = R/60, and 1.9 off the zero-crossing mesh of a loaded .vdb).
    bool band_normal(const float3& p, float3& n) const
    {
        float gx, gy, gz;
        if (!band().gradient((p.x - origin.x) * inv_voxel, (p.y - origin.y) * inv_voxel, (p.z - origin.z) * inv_voxel, gx, gy, gz))
            return false;
        const float3 g(gx, gy, gz);
        if (!(length_squared(g) > 0.25f)) return false;
        n = normalize(g);
        return true;
    }
    /// The world <-> index mapping from `sdf`'s transform. Throws for unsupported transforms.
    void set_transform(const std::string& what);
    /// The distance and its unit gradient, laid out for queries; built from `sdf` on first use
    /// (thread-safe): `groom scalp` only writes the grid and never pays for it.
    const detail::BrickMap& band() const
    {
        std::call_once(band_built_, [this] { fill_band_from_sdf(); });
        return band_;
    }

    /// Signs and bounds outside the band (fields/far_field.h), made on first use (thread-safe).
    const detail::FarField& far() const
    {
        std::call_once(far_built_, [this] { far_ = std::make_unique<detail::FarField>(geometry, *query, origin, voxel); });
        return *far_;
    }

    /// Per voxel, a lower bound of distance_within over the voxel (fields/clear_cells.h), made on
    /// first use (thread-safe); null when the mesh's box is too large to index.
    const detail::ClearCells* clear_cells() const
    {
        std::call_once(clear_built_, [this] { make_clear_cells(); });
        return clear_.get();
    }
    /// What ClearCells keeps for voxel [v, v + 1]^3: a positive lower bound of distance_within at
    /// every point of it, or 0 where none is known.
    float voxel_lower(int64_t vx, int64_t vy, int64_t vz) const;

    /// Candidate closest faces per cell outside the band (fields/near_faces.h), made on first use:
    /// cells of NearFaces::kCellVoxels << level voxels, level in [0, ScalpField::kDenseLevels).
    const detail::NearFaces& near(int level = 0) const
    {
        std::call_once(near_built_[level], [this, level] {
            near_[level] = std::make_unique<detail::NearFaces>(geometry, *query, origin, voxel, detail::NearFaces::kCellVoxels << level);
        });
        return *near_[level];
    }
    /// The exact signed distance, closest point and face from the mesh: with `level` >= 0, the face
    /// from near(level)'s candidates, or from the AABB tree where p's cell keeps none; else from the
    /// tree. The same answer either way, to float rounding at ties between faces (fields/near_faces.h).
    float exact_distance(const float3& p, float3& closest, int32_t& face, int level = -1) const
    {
        face = level >= 0 ? near(level).closest_face(p) : -1;
        if (face < 0) return query->signed_distance(p, closest, face);
        return query->signed_distance_to(p, face, closest);
    }

    /// Voxels beside a jump of the distance (see fill_band_from_sdf), left out of the query bricks.
    /// 0 means the band is 1-Lipschitz: no opening's seam and no sheets disagreeing on inside.
    int64_t seam_voxels() const
    {
        band();
        return seam_voxels_;
    }

private:
    /// Fills `band_` from `sdf` alone, gradients by central differences: the same whether the grid
    /// was just built or read from a .vdb.
    void fill_band_from_sdf() const;
    mutable std::once_flag band_built_;
    mutable detail::BrickMap band_;
    mutable int64_t seam_voxels_ = 0;
    mutable std::once_flag far_built_;
    mutable std::unique_ptr<detail::FarField> far_;
    void make_clear_cells() const;
    mutable std::once_flag clear_built_;
    mutable std::unique_ptr<detail::ClearCells> clear_;
    mutable std::once_flag near_built_[kDenseLevels];
    mutable std::unique_ptr<detail::NearFaces> near_[kDenseLevels];
};

}  // namespace groom
