// Building the scalp level set (the .vdb file is fields/scalp_file.cpp). The distance is computed unsigned by OpenVDB's
// meshToVolume, which also returns each voxel's closest polygon; we then sign every band voxel by the
// angle-weighted pseudo-normal of its closest feature. Unlike flood-fill signing this is right for
// open scalp patches and busts open at the neck, where the inside "leaks" to the outside.
#include "fields/scalp_impl.h"

#include "kernel/error.h"
#include "kernel/memory_budget.h"

#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <sstream>

namespace groom {

void detail::init_openvdb()
{
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

void ScalpBuildParams::validate() const
{
    if (!(voxel_size >= 0.0f) || !std::isfinite(voxel_size)) {
        throw InvalidParam("scalp: `voxel` must be > 0 (got " + format_number(voxel_size) + "); omit it for an automatic size");
    }
    if (!(band_voxels >= 1.0f && band_voxels <= 64.0f)) {
        throw InvalidParam("scalp: `band` must be in [1, 64] voxels (got " + format_number(band_voxels) + ")");
    }
    if (!(fill_holes >= 0.0f) || !std::isfinite(fill_holes)) {
        throw InvalidParam("scalp: `fill_holes` must be a length >= 0, scene units (got " + format_number(fill_holes) +
                           "); 0 fills none");
    }
}

void ScalpField::Impl::set_transform(const std::string& what)
{
    const openvdb::math::Transform& xf = sdf->transform();
    const openvdb::Vec3d o = xf.indexToWorld(openvdb::Vec3d(0, 0, 0));
    const double h = xf.voxelSize()[0];
    const openvdb::Vec3d probe = xf.indexToWorld(openvdb::Vec3d(1, 2, 3));
    const openvdb::Vec3d expect = o + openvdb::Vec3d(1, 2, 3) * h;
    if (!xf.isLinear() || !xf.hasUniformScale() || !(h > 0.0) || (probe - expect).length() > 1e-6 * h * 4.0) {
        throw ParseError(what + ": grid '" + sdf->getName() + "' has a rotated, sheared or non-uniform transform; groom needs cubic, "
                                "axis-aligned voxels (resample it, e.g. with vdb_tool -resample)");
    }
    voxel = static_cast<float>(h);
    inv_voxel = static_cast<float>(1.0 / h);
    origin = float3(float(o.x()), float(o.y()), float(o.z()));
    band_voxels = static_cast<float>(sdf->background() / h);
}

namespace {

/// One brick per leaf, in the manager's order (brick i is leaf i).
template <class Manager>
void allocate_bricks(detail::BrickMap& band, const Manager& leaves)
{
    std::vector<openvdb::Coord> origins(leaves.leafCount());
    for (size_t i = 0; i < origins.size(); ++i) origins[i] = leaves.leaf(i).origin();
    band.allocate(origins);
}

}  // namespace

void ScalpField::Impl::fill_band_from_sdf() const
{
    // Gradient by central differences where both neighbours are in the band; at its edge, where one
    // is missing, by the second-order one-sided difference (3 v0 - 4 v1 + v2) / 2h into the band
    // (first order only where that too runs out). The first-order difference there turned the
    // normal up to 0.24 degrees on a sphere at h = R/60, against 0.13. An axis with neither
    // neighbour (a voxel the band's dilation reached alone) has no derivative at all: its component
    // is left 0 and the voxel's gradient 0, which interpolation averages in without turning the
    // normal (a 0 there had tilted it by up to 30 degrees: a unit vector missing a component).
    // Made unit where it is a distance gradient (|g| near 1); a smaller one (a sign seam, a thin
    // sheet) is kept as it is, so queries see its length and fall back to the mesh.
    //
    // Seams. A signed distance changes by at most h between neighbouring voxels; more is a jump of
    // the sign away from the surface: the 1/2 surface of the winding number across an opening (an
    // eye socket, the neck), or where the closest face flips between sheets of overlapping shells
    // that disagree on inside (a jacket over a body). Interpolated across, the field reads anything
    // between the two sides, and what it reads depends on where the voxels fall, that is on the
    // mesh's pose (up to 3 voxels of difference and sign changes 2.5 voxels from the surface on
    // makehuman, ICT and the ponytail head). Voxels beside such a jump are taken out of the query
    // bricks (NaN distance and gradient), so queries there fall back to the exact mesh, which
    // answers the same in any pose. The grid itself (and the .vdb) keeps them.
    const float inv2h = 0.5f * inv_voxel;
    const float jump = 1.2f * voxel;
    std::atomic<int64_t> seams{0};
    openvdb::tree::LeafManager<const openvdb::FloatTree> leaves(sdf->tree());
    allocate_bricks(band_, leaves);
    leaves.foreach([&](const openvdb::FloatTree::LeafNodeType& leaf, size_t i) {
        openvdb::tree::ValueAccessor<const openvdb::FloatTree, false> acc(sdf->tree());
        constexpr int kLast = openvdb::FloatTree::LeafNodeType::DIM - 1;
        detail::BandValue* brick = band_.brick(i);
        // Neighbours inside this leaf are read from its buffer; only those across its faces probe the tree.
        auto probe = [&](const openvdb::Coord& at, int local, float& v) {
            return local >= 0 && local <= kLast ? leaf.probeValue(at, v) : acc.probeValue(at, v);
        };
        for (auto it = leaf.cbeginValueOn(); it; ++it) {
            const openvdb::Coord c = it.getCoord();
            const float v0 = *it;
            float g[3] = {0.0f, 0.0f, 0.0f};
            bool lonely = false, seam = false;
            for (int axis = 0; axis < 3; ++axis) {
                const int local = c[axis] & kLast;
                auto at = [&](int step) {
                    openvdb::Coord q = c;
                    q[axis] += step;
                    return q;
                };
                float vl = 0.0f, vh = 0.0f, v2 = 0.0f;
                const bool l = probe(at(-1), local - 1, vl);
                const bool r = probe(at(1), local + 1, vh);
                seam |= (l && std::fabs(v0 - vl) > jump) || (r && std::fabs(vh - v0) > jump);
                if (l && r) g[axis] = (vh - vl) * inv2h;
                else if (r) g[axis] = probe(at(2), local + 2, v2) ? (4.0f * vh - 3.0f * v0 - v2) * inv2h : (vh - v0) * 2.0f * inv2h;
                else if (l) g[axis] = probe(at(-2), local - 2, v2) ? (3.0f * v0 - 4.0f * vl + v2) * inv2h : (v0 - vl) * 2.0f * inv2h;
                else lonely = true;
            }
            float3 n(g[0], g[1], g[2]);
            if (lonely) n = float3();
            else if (length_squared(n) > 0.25f) n = normalize(n);
            const openvdb::Coord l = c - leaf.origin();
            const float nan = std::numeric_limits<float>::quiet_NaN();
            brick[detail::BrickMap::index(l.x(), l.y(), l.z())] = seam ? detail::BandValue{nan, nan, nan, nan} : detail::BandValue{v0, n.x, n.y, n.z};
            if (seam) seams.fetch_add(1, std::memory_order_relaxed);
        }
    });
    band_.fill_borders();
    seam_voxels_ = seams.load();
}

namespace {

/// The voxel size and the bytes its band is estimated to need.
struct VoxelChoice {
    double h = 0.0;
    double bytes = 0.0;
};

/// The voxel size (the given one, else the bounding-box diagonal / 256), refused with a suggestion
/// when the band would need more memory than the budget, and refused outright for a mesh whose size
/// overflows float (the voxel would be inf and every distance NaN) or that lies so far from the
/// origin that float positions there cannot tell neighbouring voxels apart.
/// The size and placement checks of choose_voxel (below) on any set of points, returning the
/// diagonal. Run on the raw soup before the repair too: far from the origin, float rounding makes
/// every small triangle degenerate, and "no face left" would hide the real cause.
double check_extent(std::span<const float3> points, const ScalpBuildParams& params)
{
    Bounds3 box;
    for (const float3& p : points) box.extend(p);
    // In double: the float diagonal of a mesh 1e20 across overflows (its square does).
    const double dx = double(box.hi.x) - double(box.lo.x), dy = double(box.hi.y) - double(box.lo.y),
                 dz = double(box.hi.z) - double(box.lo.z);
    const double diag = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(diag > 0.0)) throw InvalidGeometry(params.source + ": the mesh has no extent (all vertices at one point)");
    // Squared distances between points of the mesh are taken in float everywhere (queries, repair):
    // they must not overflow. 1e18 leaves a factor of 100 below FLT_MAX.
    constexpr double kMaxExtent = 1.0e18;
    if (!(diag <= kMaxExtent)) {
        throw InvalidGeometry(params.source + ": the mesh is " + format_number(diag) + " units across (bounds " + format_number(box.lo.x) + ", " +
                              format_number(box.lo.y) + ", " + format_number(box.lo.z) + " to " + format_number(box.hi.x) + ", " +
                              format_number(box.hi.y) + ", " + format_number(box.hi.z) + "); the largest size groom handles is " +
                              format_number(kMaxExtent) + " (distances would overflow float): scale it down");
    }
    const double h = params.voxel_size > 0.0f ? params.voxel_size : diag / 256.0;
    double far = 0.0;
    for (const double c : {box.lo.x, box.lo.y, box.lo.z, box.hi.x, box.hi.y, box.hi.z}) far = std::max(far, std::fabs(c));
    // A float holds 24 bits: 2^24 voxels from the origin, neighbouring voxel centres round to one
    // position (and OpenVDB's int32 coordinates are not far beyond).
    constexpr double kMaxVoxelsFromOrigin = double(1 << 24);
    if (far / h > kMaxVoxelsFromOrigin) {
        throw InvalidGeometry(params.source + ": the mesh lies " + format_number(far) + " units from the origin, " + format_number(far / h) +
                              " voxels of " + format_number(h) + "; float positions cannot resolve a voxel beyond " +
                              format_number(kMaxVoxelsFromOrigin) + " voxels: move the mesh near the origin or use a larger `voxel`");
    }
    return diag;
}

VoxelChoice choose_voxel(std::span<const float3> points, std::span<const std::array<int32_t, 3>> tris, const ScalpBuildParams& params)
{
    const double diag = check_extent(points, params);
    const double h = params.voxel_size > 0.0f ? params.voxel_size : diag / 256.0;

    // Memory estimate before allocating anything: the band holds about area / h^2 * 2 * band voxels
    // (+ 8 per triangle for small triangles' leaves), each costing the distance, its polygon index
    // and meshToVolume's temporaries, and, once queried, the query bricks (distance and gradient,
    // 9^3 per leaf). On top: what the process already holds (libraries, the mesh just read) and
    // 16 MiB of threads' and the repair's working memory. Measured peaks per voxel of this count
    // over the nine meshes of ../shared/datasets at their default voxel and a quarter of it (README,
    // `groom scalp`): 20-35 bytes for `groom scalp`, 51-88 for a command that queries the field.
    double area = 0.0;
    for (const auto& t : tris) area += 0.5 * double(length(cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]])));
    const double band = params.band_voxels;
    const double voxels = area / (h * h) * 2.0 * (band + 0.5) + 512.0 * double(tris.size()) / 64.0;
    const double per_voxel = params.for_queries ? 72.0 : 26.0;
    const uint64_t held = resident_bytes();
    // The budget bounds what the level set allocates, as every op's check_memory bounds its output
    // (kernel/memory_budget.h); what the process already holds and the threads' working memory are
    // part of the estimate shown, not of what is compared (they were, and then no voxel fitted a
    // small budget: the advice read "--voxel 2000" for a 35-unit head).
    const double working = double(16ull << 20);
    const double bytes = double(held ? held : 40ull << 20) + working + voxels * per_voxel;
    const double adds = voxels * per_voxel;  // the level set's own share, which the voxel size sets
    const double extent_voxels = diag / h;
    const double budget = double(params.memory_budget ? params.memory_budget : memory_budget());
    if (!(adds <= budget) || extent_voxels > 1.0e6) {
        // The voxels' part scales with 1 / h^2.
        const double room = budget;
        const double suggest = room > 0.0 ? h * std::sqrt(std::max(voxels * per_voxel / room, 1.0)) * 1.1 : h * 1e3;
        const double suggest2 = std::max(suggest, diag / 1.0e6 * 1.1);
        throw LimitExceeded("scalp: voxel size " + format_number(h) + " needs about " + format_number(adds / double(1ull << 30)) +
                            " GiB for the level set (" + format_number(voxels) + " voxels), over the " +
                            format_number(budget / double(1ull << 30)) + " GiB budget (`memory`); use `voxel` " +
                            format_number(suggest2) + " or larger (the mesh is " + format_number(diag) + " units across)");
    }
    // After the budget (whose advice names a workable voxel). OpenVDB refuses a transform whose scale
    // determinant is below 3e-15 (ArithmeticError "Non-zero scale values required", thrown inside
    // meshToVolume's tasks, which ended the process): h^3 must stay above that.
    constexpr float kMinVoxel = 2.0e-5f;  // float: --voxel 2e-5 is a float
    if (!(h >= double(kMinVoxel))) {
        throw InvalidGeometry(params.source + ": voxel size " + format_number(h) + (params.voxel_size > 0.0f ? "" : " (automatic)") +
                              " is below " + format_number(kMinVoxel) + ", the smallest OpenVDB's transforms take (the mesh is " +
                              format_number(diag) + " units across): scale the mesh up" +
                              (params.voxel_size > 0.0f ? " or use a larger `voxel`" : ""));
    }
    return {h, bytes};
}

/// The automatic voxel (the whole mesh's diagonal / 256) refused when a part far from the head makes
/// it too coarse for the head. Refused rather than warned about: inside and outside then flip near
/// the head's thin parts (the default head plus one triangle 400 units away, 10x the head: 23 of
/// 4,000 points in its box change sign; 3,000 away: 1,183), a wrong answer every command would give
/// silently, and a warning raised here would not reach a command that converts `--scalp MESH` on
/// the fly. The fix is one option (any given `voxel` skips this check).
/// "The head" is the kept shell of the largest area; it must span at least kMinHeadVoxels voxels
/// along its diagonal, a quarter of what it would get alone: the real heads in ../shared/datasets
/// span 212 to 256 (the largest shell at least 1/1.21 of the mesh's diagonal; 1/2.4 for Sintel's
/// eyelash cards, which are no head).
void check_automatic_voxel(const RepairReport& report, double h, const ScalpBuildParams& params)
{
    constexpr double kMinHeadVoxels = 64.0;
    if (params.voxel_size > 0.0f) return;
    std::vector<const RepairReport::Shell*> kept;
    for (const RepairReport::Shell& s : report.shell_list)
        if (!s.removed) kept.push_back(&s);
    if (kept.size() < 2) return;
    const RepairReport::Shell& head = *kept.front();  // the list is largest area first
    auto diagonal = [](const RepairReport::Shell& s) {
        const double dx = double(s.hi[0]) - s.lo[0], dy = double(s.hi[1]) - s.lo[1], dz = double(s.hi[2]) - s.lo[2];
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    const double head_diag = diagonal(head);
    if (head_diag / h >= kMinHeadVoxels) return;
    // The shells reaching out of the head's box, and the one reaching farthest from its centre.
    double centre[3];
    for (int i = 0; i < 3; ++i) centre[i] = 0.5 * (double(head.lo[i]) + head.hi[i]);
    int64_t outside = 0, outside_faces = 0;
    const RepairReport::Shell* farthest = nullptr;
    double farthest_reach = -1.0;
    for (size_t k = 1; k < kept.size(); ++k) {
        const RepairReport::Shell& s = *kept[k];
        bool inside = true;
        double reach2 = 0.0;
        for (int i = 0; i < 3; ++i) {
            inside &= s.lo[i] >= head.lo[i] && s.hi[i] <= head.hi[i];
            const double r = std::max(std::fabs(s.lo[i] - centre[i]), std::fabs(s.hi[i] - centre[i]));
            reach2 += r * r;
        }
        if (inside) continue;
        ++outside;
        outside_faces += s.faces;
        if (std::sqrt(reach2) > farthest_reach) farthest_reach = std::sqrt(reach2), farthest = &s;
    }
    if (!farthest) return;  // every other shell lies within the head's box: the head sets the voxel
    auto point = [](const float* v) { return format_number(v[0]) + ", " + format_number(v[1]) + ", " + format_number(v[2]); };
    throw InvalidGeometry(
        params.source + ": the automatic voxel size " + format_number(h) + " (the mesh's diagonal / 256) is too coarse for the head: its "
        "largest shell (" + std::to_string(head.faces) + " faces, " + format_number(head_diag) + " units across) spans only " +
        format_number(head_diag / h) + " voxels, under the " + format_number(kMinHeadVoxels) +
        " that keep inside and outside right at its thin parts, because " + std::to_string(outside) + " other shell" +
        (outside == 1 ? "" : "s") + " (" + std::to_string(outside_faces) + " face" + (outside_faces == 1 ? "" : "s") +
        ") " + (outside == 1 ? "reaches" : "reach") + " out of its box, the farthest (" + std::to_string(farthest->faces) + " face" + (farthest->faces == 1 ? "" : "s") +
        ", bounds " + point(farthest->lo) + " to " + point(farthest->hi) + ") " + format_number(farthest_reach) +
        " units from the head's centre; give `voxel` " + format_number(head_diag / 256.0) +
        " (the head's own diagonal / 256), keep only the head's faces with `group` (OBJ), or delete that part from the mesh");
}

/// meshToVolume's unsigned narrow band (world units) and, in `index_grid`, each voxel's closest
/// triangle.
/// Lets a meshToVolume that is no longer wanted stop at its next check. (Cancelling its task group
/// instead leaked its per-thread voxelization trees: LeakSanitizer, OpenVDB 10.)
struct StopFlag : openvdb::util::NullInterrupter {
    std::atomic<bool> stop{false};
    bool wasInterrupted(int = -1) override { return stop.load(std::memory_order_relaxed); }
};

openvdb::FloatGrid::Ptr unsigned_band(std::span<const float3> points, std::span<const std::array<int32_t, 3>> tris, double h,
                                      double band, openvdb::Int32Grid& index_grid, StopFlag& interrupter)
{
    // meshToVolume takes the mesh in index space (voxel units).
    std::vector<openvdb::Vec3s> index_points(points.size());
    const float inv_h = float(1.0 / h);
    for (size_t i = 0; i < points.size(); ++i) {
        index_points[i] = openvdb::Vec3s(points[i].x * inv_h, points[i].y * inv_h, points[i].z * inv_h);
    }
    std::vector<openvdb::Vec3I> faces(tris.size());
    for (size_t i = 0; i < faces.size(); ++i) faces[i] = openvdb::Vec3I(tris[i][0], tris[i][1], tris[i][2]);
    const openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(h);
    const openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> adapter(index_points, faces);
    return openvdb::tools::meshToVolume<openvdb::FloatGrid>(interrupter, adapter, *xform, float(band), float(band),
                                                            openvdb::tools::UNSIGNED_DISTANCE_FIELD, &index_grid);
}

}  // namespace

ScalpField build_scalp(const PolygonSoup& soup, const ScalpBuildParams& params, RepairReport* report_out, Progress* progress)
{
    params.validate();
    if (!soup.points.empty()) check_extent(soup.points, params);
    detail::init_openvdb();
    const double band = params.band_voxels;
    detail::RepairOptions options;
    options.flip = params.flip;
    options.remove_enclosed = params.remove_enclosed_shells;
    options.fill_holes = params.fill_holes;
    options.what = params.source;

    // meshToVolume needs only the final positions and faces: started as soon as the repair has them,
    // it runs beside the rest of the repair (CGAL's orientation of a messy soup), the OpenMesh
    // conversion and the mesh geometry, serial work that otherwise left a core idle.
    struct Early {
        double h = 0.0, bytes = 0.0, budget = 0.0;
        std::vector<float3> points;
        std::vector<std::array<int32_t, 3>> tris;
        openvdb::Int32Grid::Ptr index;
        openvdb::FloatGrid::Ptr sdf;
        StopFlag stop;
    } early;
    tbb::task_group background;
    std::optional<MemoryNote> note;  // what an allocation failure in the band is reported as
    options.on_triangles = [&](std::vector<float3> points, std::vector<std::array<int32_t, 3>> tris) {
        if (early.index) {  // the faces changed (shells removed): stop the band of the old ones
            early.stop.stop = true;
            background.wait();
            early.stop.stop = false;
            early.sdf.reset();
        }
        const VoxelChoice choice = choose_voxel(points, tris, params);
        early.h = choice.h;
        early.bytes = choice.bytes;
        early.budget = double(params.memory_budget ? params.memory_budget : memory_budget());
        note.reset();
        note.emplace("scalp: building the level set at voxel size " + format_number(early.h) + " (estimated " + format_bytes(early.bytes) +
                     "); use a larger `voxel`");
        early.points = std::move(points);
        early.tris = std::move(tris);
        early.index = openvdb::Int32Grid::create(static_cast<openvdb::Int32>(openvdb::util::INVALID_IDX));  // as meshToVolume expects
        background.run([&early, band] {
            // meshToVolume's own TBB tasks allocate the band: a failed allocation there (the estimate
            // fitted the budget, the machine did not) comes back through this task group's wait().
            // Turned into an error naming the voxel here, where the estimate is known.
            try {
                early.sdf = unsigned_band(early.points, early.tris, early.h, band, *early.index, early.stop);
            }
            catch (const std::bad_alloc&) {
                early.sdf.reset();
                early.index.reset();
                throw LimitExceeded("scalp: out of memory building the level set at voxel size " + format_number(early.h) +
                                    " (estimated " + format_bytes(early.bytes) + ", within the " +
                                    format_bytes(early.budget) +
                                    " budget but more than this process could allocate); use a larger `voxel` or lower `memory`");
            }
        });
    };
    RepairReport report;
    ScalpField field;
    ScalpField::Impl& im = field.impl();
    try {
        const TriMesh mesh = detail::repair_soup(soup, options, report, progress);
        check_automatic_voxel(report, early.h, params);
        im.geometry.compute(mesh);
        im.query = std::make_unique<detail::MeshQuery>(im.geometry);
        // Open rims are signed by the winding number: built here, it too runs beside meshToVolume.
        // Rims are the holes not filled, and those cut where buried faces went.
        if (report.rim_lengths.size() > size_t(report.holes_filled) || report.rims_inside_union > 0) im.query->winding();
    }
    catch (...) {
        early.stop.stop = true;
        try {
            background.wait();
        }
        catch (...) {  // the repair's error is the one to report
        }
        throw;
    }
    if (report_out) *report_out = report;
    const detail::MeshGeometry& geo = im.geometry;

    // The estimate in the label: `--verbose` shows it beside the time.
    const std::string label = "signed distance (estimated " + format_bytes(early.bytes) + ")";
    ProgressStep step(progress, label, 3);
    background.wait();
    // The repair reports its final triangles in every path; the band is of exactly those faces.
    if (!early.sdf || early.tris.size() != geo.tris.size()) {
        throw std::logic_error("build_scalp: the repair did not report the mesh's triangles");
    }
    const double h = early.h;
    const openvdb::FloatGrid::Ptr sdf = early.sdf;
    const openvdb::Int32Grid::Ptr index_grid = early.index;
    step.advance(1);

    // Sign (and recompute exactly) every band voxel from its closest polygon's pseudo-normal, or, where
    // the closest feature is an open boundary (a hole's rim), by the generalized winding number.
    const detail::MeshQuery& query = *im.query;
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(sdf->tree());
    const openvdb::Int32Tree& index_tree = index_grid->tree();
    // meshToVolume measures every voxel within sqrt(3)/2 voxels of a triangle against that triangle
    // (its voxelizer floods out from the triangle to exactly that distance), so where the distance it
    // found is below that, its polygon is the closest: the walk is needed only farther out, where
    // the band was grown from neighbours' polygons. (Skipping it there changed no sign and no
    // distance by more than float rounding on nefertiti and Lee Perry-Smith; 20% of the pass.)
    const float exact_within = 0.85f * float(h);
    leaves.foreach([&](openvdb::FloatTree::LeafNodeType& leaf, size_t) {
        // The index grid has the same leaves (meshToVolume fills both together): one lookup per leaf.
        const openvdb::Int32Tree::LeafNodeType* idx = index_tree.probeConstLeaf(leaf.origin());
        if (!idx) return;
        for (auto it = leaf.beginValueOn(); it; ++it) {
            const openvdb::Coord c = it.getCoord();
            int32_t f = idx->getValue(it.pos());
            if (f < 0 || size_t(f) >= geo.tris.size()) continue;
            const float3 p(float(c.x() * h), float(c.y() * h), float(c.z() * h));
            if (!(std::fabs(*it) < exact_within)) f = geo.refine_closest_face(p, f);
            float3 closest;
            bool boundary = false;
            const float d = geo.signed_distance_to_face(p, f, closest, &boundary);
            it.setValue(query.sign_fixed(p, d, boundary, false));
        }
    });
    // The walk can stop at a face that is only locally closest (a fold, a crease): the voxel then
    // holds the distance to that face, more than the true one, which shows as neighbours differing
    // by more than a voxel with no change of sign (40 voxels of nefertiti's 326,000, 0.3 voxel too
    // far; they read as seams and cost the head its 1-Lipschitz flag). Both ends of such a pair are
    // measured again exactly against the whole mesh.
    {
        const float jump = 1.2f * float(h);
        std::vector<openvdb::Coord> suspects;
        std::mutex found;
        leaves.foreach([&](const openvdb::FloatTree::LeafNodeType& leaf, size_t) {
            openvdb::tree::ValueAccessor<const openvdb::FloatTree, false> acc(sdf->tree());
            std::vector<openvdb::Coord> mine;
            for (auto it = leaf.cbeginValueOn(); it; ++it) {
                for (int axis = 0; axis < 3; ++axis) {
                    openvdb::Coord n = it.getCoord();
                    n[axis] += 1;
                    float v = 0.0f;
                    if (acc.probeValue(n, v) && (v < 0.0f) == (*it < 0.0f) && std::fabs(v - *it) > jump) {
                        mine.push_back(it.getCoord());
                        mine.push_back(n);
                    }
                }
            }
            if (mine.empty()) return;
            const std::lock_guard<std::mutex> lock(found);
            suspects.insert(suspects.end(), mine.begin(), mine.end());
        });
        // Sorted and measured before any is written: the same values for any thread count.
        std::sort(suspects.begin(), suspects.end());
        suspects.erase(std::unique(suspects.begin(), suspects.end()), suspects.end());
        std::vector<float> exact(suspects.size());
        for (size_t i = 0; i < suspects.size(); ++i) {
            const openvdb::Coord& c = suspects[i];
            float3 closest;
            int32_t face = -1;
            exact[i] = query.signed_distance(float3(float(c.x() * h), float(c.y() * h), float(c.z() * h)), closest, face);
        }
        openvdb::tree::ValueAccessor<openvdb::FloatTree> acc(sdf->tree());
        for (size_t i = 0; i < suspects.size(); ++i) acc.setValueOnly(suspects[i], exact[i]);
    }
    // Inactive tiles and voxels take the sign of their active neighbours (inside = -band * h), as
    // viewers expect of a level set; queries never trust them (they fall back to the mesh).
    openvdb::tools::signedFloodFill(sdf->tree());
    step.advance(1);
    sdf->setName("scalp");
    sdf->setGridClass(openvdb::GRID_LEVEL_SET);
    sdf->insertMeta("creator", openvdb::StringMetadata("groom scalp " GROOM_VERSION));
    sdf->insertMeta("groom_band_voxels", openvdb::FloatMetadata(float(band)));
    im.sdf = sdf;
    im.set_transform("scalp");
    // The band's gradients (built on the first query) come from the distances alone, exactly as when
    // this grid is read back from its .vdb: a scalp answers the same whether given as a mesh or as
    // the file made from it. (Exact gradients from the closest points measured 0.057 against 0.067
    // voxels mean projection error on nefertiti, not worth two answers for one scalp.)
    im.mesh_exact = true;
    // Texture coordinates on the user's own triangles (fields/uv_map.h), for roots' UVs.
    im.uv = detail::UvMap::from_soup(soup);
    step.advance(1);
    return field;
}

}  // namespace groom
