// The scalp's own file: the level set as a .vdb (OpenVDB's format, one float grid named "scalp"), and
// load_scalp, which takes either that or any mesh the kernel reads. The only file in fields/ that
// touches files: the .vdb needs OpenVDB, which kernel/ does not link, so this format lives here.
#include "fields/scalp_impl.h"

#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/format_table.h"
#include "kernel/io/io_util.h"
#include "kernel/io/memory_files.h"
#include "kernel/io/mesh_io.h"

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <mutex>

namespace groom {

void write_scalp(const ScalpField& scalp, const std::string& path)
{
    detail::init_openvdb();
    const ScalpField::Impl& im = scalp.impl();
    if (!im.sdf) throw InvalidParam("write_scalp: the scalp field is empty");
    // Through our atomic output (a temporary beside the target, renamed when complete) rather than
    // io::File, which writes by name through an ofstream whose errors it never checks: a full disk
    // left a truncated file and no exception, and reading the file back to find out cost as much as
    // writing it. io::Stream writes the same file format to a stream whose state we check.
    try {
        AtomicOutput out(path);
        openvdb::io::Stream(out.stream()).write(openvdb::GridCPtrVec{im.sdf});
        out.commit();
    }
    catch (const openvdb::Exception& e) {
        throw IoError(path + ": cannot write the level set (" + e.what() + ")");
    }
}

ScalpField read_scalp_vdb(const std::string& path, Progress* progress)
{
    detail::init_openvdb();
    if (!std::filesystem::exists(path)) throw IoError(path + ": no such file");
    openvdb::GridBase::Ptr base;
    std::string names;
    try {
        openvdb::io::File file(path);
        file.open();
        for (auto it = file.beginName(); it != file.endName(); ++it) names += (names.empty() ? "" : ", ") + it.gridName();
        if (file.hasGrid("scalp")) base = file.readGrid("scalp");
        file.close();
    }
    catch (const openvdb::Exception& e) {
        throw ParseError(path + ": not a readable .vdb file (" + e.what() + ")");
    }
    if (!base) {
        throw ParseError(path + ": no grid named 'scalp' (found: " + (names.empty() ? std::string("no grids") : names) +
                         "); make one with `groom scalp MESH -o " + std::filesystem::path(path).filename().string() + "`");
    }
    openvdb::FloatGrid::Ptr sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!sdf) throw ParseError(path + ": grid 'scalp' holds " + base->valueType() + " values; expected a float level set");
    if (sdf->getGridClass() != openvdb::GRID_LEVEL_SET) {
        throw ParseError(path + ": grid 'scalp' is not a level set (class '" + openvdb::GridBase::gridClassToString(sdf->getGridClass()) +
                         "'); expected a signed distance field from `groom scalp`");
    }
    if (sdf->activeVoxelCount() == 0) throw ParseError(path + ": grid 'scalp' has no active voxels");

    ProgressStep step(progress, "load scalp", 2);
    ScalpField field;
    ScalpField::Impl& im = field.impl();
    im.sdf = sdf;
    im.set_transform(path);
    step.advance(1);

    // The mesh for far queries and sampling: the zero crossing, each face turned to agree with the
    // distance's increase across it. A sign flip with large |d| on both sides is the seam an open
    // surface's sign makes beyond its rim, not surface: such faces (a rise of more than 1.5 voxels
    // over one voxel across them) are dropped. Read from the grid itself: the query bricks leave
    // voxels beside such seams out.
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*sdf, points, tris, quads, 0.0, 0.0);
    PolygonSoup soup;
    soup.points.reserve(points.size());
    for (const auto& p : points) soup.points.emplace_back(p.x(), p.y(), p.z());
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> grid_sample(*sdf);
    auto value = [&](const float3& p) { return float(grid_sample.wsSample(openvdb::Vec3d(p.x, p.y, p.z))); };
    auto add = [&](std::initializer_list<int32_t> idx) {
        std::vector<int32_t> f(idx);
        const float3 &a = soup.points[f[0]], &b = soup.points[f[1]], &c = soup.points[f[2]];
        const float3 centroid = (a + b + c) / 3.0f;
        const float3 step_n = normalize(cross(b - a, c - a)) * (0.5f * im.voxel);
        const float dl = value(centroid - step_n), dh = value(centroid + step_n);
        if (std::fabs(dh - dl) / im.voxel > 1.5f) return;
        if (dh < dl) std::reverse(f.begin(), f.end());
        soup.add_face(f);
    };
    for (const auto& t : tris) add({int32_t(t[0]), int32_t(t[1]), int32_t(t[2])});
    for (const auto& q : quads) {
        add({int32_t(q[0]), int32_t(q[1]), int32_t(q[2])});
        add({int32_t(q[0]), int32_t(q[2]), int32_t(q[3])});
    }
    if (soup.num_faces() == 0) throw ParseError(path + ": grid 'scalp' has no zero crossing (no surface inside its band)");
    detail::RepairOptions options;
    options.orient_outward = false;
    options.remove_enclosed = false;
    options.what = path;
    RepairReport report;
    const TriMesh mesh = detail::repair_soup(soup, options, report, nullptr);
    im.geometry.compute(mesh);
    im.mesh_exact = false;
    im.query = std::make_unique<detail::MeshQuery>(im.geometry);
    step.advance(1);
    return field;
}

namespace {

struct MemoryScalps {
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<const ScalpField>, std::less<>> fields;
};

MemoryScalps& memory_scalps()
{
    static MemoryScalps m;
    return m;
}

}  // namespace

void store_memory_scalp(const std::string& path, std::shared_ptr<const ScalpField> scalp)
{
    MemoryScalps& m = memory_scalps();
    const std::lock_guard lock(m.mutex);
    m.fields.insert_or_assign(path, std::move(scalp));
}

void erase_memory_scalp(const std::string& path)
{
    MemoryScalps& m = memory_scalps();
    const std::lock_guard lock(m.mutex);
    m.fields.erase(path);
}

std::shared_ptr<const ScalpField> load_scalp(const std::string& path, const ScalpBuildParams& params, Progress* progress)
{
    if (is_memory_path(path)) {
        MemoryScalps& m = memory_scalps();
        const std::lock_guard lock(m.mutex);
        const auto it = m.fields.find(path);
        if (it == m.fields.end()) throw IoError(path + ": no scalp stored under this name");
        return it->second;
    }
    if (io::extension_of(path) == "vdb") return std::make_shared<ScalpField>(read_scalp_vdb(path, progress));
    if (!is_mesh_path(path)) {
        throw InvalidParam("`scalp` " + path + ": expected a .vdb level set from `groom scalp` or a mesh (" + io::format_list(io::kReadMesh) + ")");
    }
    return std::make_shared<ScalpField>(build_scalp(read_mesh(path), params, nullptr, progress));
}

}  // namespace groom
