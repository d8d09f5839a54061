// The scalp's own file: the level set as a .vdb (OpenVDB's format, one float grid named "scalp"; other
// programs' level sets of other names are read too), and load_scalp, which takes either that or any
// mesh the kernel reads. The only file in fields/ that
// touches files: the .vdb needs OpenVDB, which kernel/ does not link, so this format lives here.
#include "fields/scalp_impl.h"
#include "fields/scalp_cache.h"
#include "fields/source_mesh.h"

#include "kernel/error.h"
#include "kernel/io/atomic_file.h"
#include "kernel/io/format_table.h"
#include "kernel/io/io_util.h"
#include "kernel/io/memory_files.h"
#include "kernel/io/mesh_io.h"
#include "kernel/memory_budget.h"

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <chrono>
#include <csignal>
#include <csignal>
#include <poll.h>
#include <new>
#include <sstream>
#include <filesystem>
#include <map>
#include <optional>
#include <mutex>

namespace groom {

namespace {
/// Grid metadata holding the source mesh's texture coordinates (UvMap::encode); files without it
/// (older ones, meshes without UVs, other programs' level sets) simply have no UVs.
constexpr const char* kUvMeta = "groom_uv_mesh";
/// Grid metadata holding the repaired mesh the field was built from (fields/source_mesh.h): a file
/// with it loads that mesh instead of extracting one from the zero crossing.
constexpr const char* kMeshMeta = "groom_source_mesh";
}  // namespace

void write_scalp(const ScalpField& scalp, const std::string& path)
{
    OutputBatch batch;
    write_scalp(scalp, path, batch);
    batch.commit();
}

namespace {

/// OpenVDB writes a random UUID into every file's header (io::Archive::writeHeader, with no way to
/// give one), so two runs of the same `groom scalp` differed in those 36 bytes (a trial: `cmp`-based
/// checks failed, against "the same inputs give the same bytes"). Replaced by one made from the
/// file's content after the header (two FNV-1a hashes, as a version-4 UUID's text): the same
/// content, the same UUID; other content, another. Readers use it only to tell files apart.
/// The header: magic (8 bytes), file version (4), library major and minor (4 + 4), whether grids
/// have offsets (1), then the UUID as 36 characters.
void stamp_content_uuid(std::string& file)
{
    constexpr size_t kAt = 21, kLen = 36;
    if (file.size() < kAt + kLen || file[kAt + 8] != '-' || file[kAt + 13] != '-' || file[kAt + 18] != '-' || file[kAt + 23] != '-') return;
    uint64_t h[2] = {0xcbf29ce484222325ull, 0x84222325cbf29ce4ull};
    for (size_t i = kAt + kLen; i < file.size(); ++i) {
        for (uint64_t& x : h) x = (x ^ uint8_t(file[i])) * 0x100000001b3ull;
    }
    char hex[33];
    std::snprintf(hex, sizeof hex, "%016llx%016llx", (unsigned long long)h[0], (unsigned long long)h[1]);
    hex[12] = '4';                                          // version 4
    hex[16] = "89ab"[(hex[16] >= 'a' ? hex[16] - 'a' + 10 : hex[16] - '0') & 3];  // the RFC 4122 variant
    const std::string id = std::string(hex, 8) + "-" + std::string(hex + 8, 4) + "-" + std::string(hex + 12, 4) + "-" +
                           std::string(hex + 16, 4) + "-" + std::string(hex + 20, 12);
    file.replace(kAt, kLen, id);
}

}  // namespace

void write_scalp(const ScalpField& scalp, const std::string& path, OutputBatch& batch)
{
    detail::init_openvdb();
    const ScalpField::Impl& im = scalp.impl();
    if (!im.sdf) throw InvalidParam("write_scalp: the scalp field is empty");
    // Through our atomic output (a temporary beside the target, renamed when complete) rather than
    // io::File, which writes by name through an ofstream whose errors it never checks: a full disk
    // left a truncated file and no exception, and reading the file back to find out cost as much as
    // writing it. io::Stream writes the same file format to a stream whose state we check.
    // The source mesh's texture coordinates ride along as grid metadata (fields/uv_map.h), on a
    // shallow copy: the field's own grid stays as it is.
    // So does the repaired mesh itself, when the field has it (not one extracted from a file that
    // lacked it: that would pass the extraction off as the user's mesh).
    openvdb::FloatGrid::ConstPtr grid = im.sdf;
    if (im.uv || im.mesh_exact) {
        openvdb::FloatGrid::Ptr copy = im.sdf->copy();
        if (im.uv) copy->insertMeta(kUvMeta, openvdb::StringMetadata(im.uv->encode()));
        if (im.mesh_exact) copy->insertMeta(kMeshMeta, openvdb::StringMetadata(detail::encode_source_mesh(im.geometry.points, im.geometry.tris)));
        grid = copy;
    }
    std::ostringstream bytes;
    try {
        openvdb::io::Stream(bytes).write(openvdb::GridCPtrVec{grid});
    }
    catch (const openvdb::Exception& e) {
        throw IoError(path + ": cannot write the level set (" + e.what() + ")");
    }
    std::string file = std::move(bytes).str();
    stamp_content_uuid(file);
    std::ostream& out = batch.open(path);
    out.write(file.data(), std::streamsize(file.size()));
}

namespace {

/// One grid of a .vdb as the messages list it.
struct GridEntry {
    std::string name;   ///< OpenVDB's unique name ("surface", "surface[1]" for a second of that name)
    std::string type;   ///< value type: "float", "double", "vec3s"...
    std::string cls;    ///< grid class: "level set", "fog volume", "unknown"...
    bool usable = false;  ///< a float level set, or a float grid of class unknown that is plainly one
};

/// What decode_isolated() brings back: the file's grids, which one is used (-1: none could be
/// chosen; the caller says why) and that grid re-encoded by OpenVDB (empty when none).
struct DecodedVdb {
    std::vector<GridEntry> grids;
    int chosen = -1;
    std::string grid_stream;
};

/// Whether a float grid whose class is not set is plainly a narrow-band signed distance, as
/// OpenVDB's own tools leave one: a positive background, every inactive value (tiles, voxels off
/// the band) exactly +-background, and the active values within +-background, of both signs (a
/// surface crosses the band). A density or temperature grid fails at once (background 0, or one
/// sign). Serial iterators only: it also runs in decode_isolated's forked child, where TBB must not.
bool plainly_sdf(const openvdb::FloatGrid& g)
{
    const float bg = g.background();
    if (!(std::isfinite(bg) && bg > 0.0f)) return false;
    for (auto it = g.cbeginValueOff(); it; ++it)
        if (*it != bg && *it != -bg) return false;
    bool below = false, above = false;
    for (auto it = g.cbeginValueOn(); it; ++it) {
        const float v = *it;
        if (!(std::fabs(v) <= bg * 1.001f)) return false;
        below |= v < 0.0f;
        above |= v > 0.0f;
    }
    return below && above;
}

/// A grid name as a message shows it: control characters (a newline would also break
/// decode_isolated's reply, one grid a line) as '?'.
std::string printable_name(const std::string& name)
{
    std::string out = name;
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return out;
}

/// The grids of a file for a message: "'surface' (float, level set), 'density' (float, fog volume)".
std::string list_grids(const std::vector<GridEntry>& grids)
{
    if (grids.empty()) return "no grids";
    std::string out;
    for (const GridEntry& g : grids) {
        out += (out.empty() ? "'" : ", '") + g.name + "' (" + g.type + ", " + g.cls;
        if (g.usable && g.cls != "level set") out += ", a signed distance by its values";
        out += ")";
    }
    return out;
}

/// Reads the grid of `path` that read_scalp_vdb uses (`requested`; else "scalp"; else the only
/// usable one) in a child process and brings it back re-encoded, with the file's list of grids.
/// OpenVDB's decoder trusts the sizes it reads: a flipped bit in a chunk's length makes it write past
/// a buffer (heap corruption, then an abort) before any check of ours could run, 1 in a few hundred
/// single-bit flips of a small scalp. A crash in the child is an error naming the file; the grid the child
/// read is written again by OpenVDB itself, so the stream this process decodes is consistent.
/// The child only reads and writes (no TBB, which does not survive fork()) and leaves with _exit().
DecodedVdb decode_isolated(const std::string& path, const std::string& requested)
{
    // The child may use the command's memory budget beyond what it inherits (its address space
    // starts as a copy of ours): a length field flipped to gigabytes is then a bad_alloc there, not
    // gigabytes zeroed for nothing.
    uint64_t inherited = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
        unsigned long long pages = 0;
        if (std::fscanf(f, "%llu", &pages) == 1) inherited = uint64_t(pages) * uint64_t(::sysconf(_SC_PAGESIZE));
        std::fclose(f);
    }
    const uint64_t child_limit = inherited + memory_budget();
    int fds[2];
    if (::pipe(fds) != 0) throw IoError(path + ": cannot read (pipe: " + std::strerror(errno) + ")");
    const pid_t pid = ::fork();
    if (pid < 0) {
        const int err = errno;
        ::close(fds[0]);
        ::close(fds[1]);
        throw IoError(path + ": cannot read (fork: " + std::strerror(err) + ")");
    }
    if (pid == 0) {
        ::close(fds[0]);
        if (inherited > 0) {
            rlimit rl{};
            if (::getrlimit(RLIMIT_AS, &rl) == 0 && (rl.rlim_cur == RLIM_INFINITY || rl.rlim_cur > child_limit)) {
                rl.rlim_cur = rlim_t(child_limit);
                ::setrlimit(RLIMIT_AS, &rl);
            }
        }
        std::string reply;
        try {
            // Reply: "O#grids chosen\n", a line per grid (name, type, class, usable; tab-separated),
            // then the chosen grid's stream.
            std::vector<GridEntry> grids;
            std::vector<std::string> raw_names;
            openvdb::GridBase::Ptr grid;
            int chosen = -1;
            openvdb::io::File file(path);
            // Everything now (no delayed loading): a delayed-loaded leaf of a truncated file is read
            // from the mapped file on first access, past its end.
            file.open(/*delayLoad=*/false);
            for (auto it = file.beginName(); it != file.endName(); ++it) {
                const openvdb::GridBase::ConstPtr meta = file.readGridMetadata(it.gridName());
                GridEntry g{printable_name(it.gridName()), meta->valueType(), openvdb::GridBase::gridClassToString(meta->getGridClass())};
                g.usable = g.type == "float" && meta->getGridClass() == openvdb::GRID_LEVEL_SET;
                grids.push_back(std::move(g));
                raw_names.push_back(it.gridName());
            }
            auto find = [&](const std::string& name) {
                const auto at = std::find(raw_names.begin(), raw_names.end(), name);
                return at == raw_names.end() ? -1 : int(at - raw_names.begin());
            };
            if (!requested.empty()) chosen = find(requested);
            else if ((chosen = find("scalp")) < 0) {
                // No "scalp": the only float level set, whatever its name. A float grid without a
                // class (pyopenvdb's FloatGrid(), an exporter that drops it) counts when its values
                // are plainly a signed distance; each is read whole to tell.
                int usable = 0;
                for (size_t i = 0; i < grids.size(); ++i) {
                    if (grids[i].type == "float" && grids[i].cls == "unknown") {
                        openvdb::GridBase::Ptr g = file.readGrid(raw_names[i]);
                        const auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
                        grids[i].usable = f && plainly_sdf(*f);
                        if (grids[i].usable) grid = g;  // kept: read again below otherwise
                    }
                    if (grids[i].usable) {
                        ++usable;
                        chosen = int(i);
                    }
                }
                if (usable != 1) chosen = -1;
            }
            if (chosen >= 0 && (!grid || grid->getName() != raw_names[size_t(chosen)])) grid = file.readGrid(raw_names[size_t(chosen)]);
            if (chosen < 0) grid.reset();
            file.close();
            std::ostringstream out;
            out << 'O' << grids.size() << ' ' << chosen << '\n';
            for (const GridEntry& g : grids) out << g.name << '\t' << g.type << '\t' << g.cls << '\t' << (g.usable ? 1 : 0) << '\n';
            if (grid) {
                openvdb::io::Stream stream(out);
                stream.setCompression(openvdb::io::COMPRESS_NONE);  // a pipe, not a disk: no time on compression
                stream.write(openvdb::GridCPtrVec{grid});
            }
            reply = out.str();
        }
        catch (const std::bad_alloc&) {
            reply = "M";  // over the budget: the parent says so (a user read "std::bad_alloc" as a damaged file)
        }
        catch (const std::exception& e) {
            reply = std::string("E") + e.what();
        }
        for (size_t done = 0; done < reply.size();) {
            const ssize_t n = ::write(fds[1], reply.data() + done, reply.size() - done);
            if (n <= 0) ::_exit(3);
            done += size_t(n);
        }
        ::_exit(0);
    }
    ::close(fds[1]);
    std::string reply;
    char buf[1 << 16];
    // A child that never answers (a damaged length it keeps reading toward, or a lock another thread
    // held when the process forked) must not hang the command: it gets two minutes, then is killed.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
        pollfd pfd{fds[0], POLLIN, 0};
        const int ready = left > 0 ? ::poll(&pfd, 1, int(std::min<long long>(left, 1000))) : 0;
        if (ready < 0 && errno == EINTR) continue;
        if (ready == 0) {
            if (left > 0) continue;
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
            }
            ::close(fds[0]);
            throw ParseError(path + ": corrupt .vdb file: OpenVDB's decoder did not finish reading it in 120 s; is it damaged?");
        }
        const ssize_t n = ::read(fds[0], buf, sizeof buf);
        if (n > 0) reply.append(buf, size_t(n));
        else if (n == 0 || errno != EINTR) break;
    }
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFSIGNALED(status)) {
        throw ParseError(path + ": corrupt .vdb file: OpenVDB's decoder crashed reading it (" + ::strsignal(WTERMSIG(status)) +
                         "); is it truncated or damaged?");
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || reply.empty()) {
        throw IoError(path + ": cannot read (the reading process failed)");
    }
    if (reply[0] == 'M') {
        // Out of the budget in the child: a budget too small for the file (a user's --memory 0.001
        // read as "std::bad_alloc", a damaged file), or a damaged length asking for gigabytes. A
        // grid decodes to a few times its file's size, so a budget 64 times the file (and 64 MiB
        // for the process) that ran out means damage.
        std::error_code ec;
        const double file_bytes = double(std::filesystem::file_size(path, ec));
        const double budget = double(memory_budget());
        if (!ec && budget >= 64.0 * (file_bytes + double(1 << 20))) {
            throw ParseError(path + ": not a readable .vdb file (a length inside it asks for more than the " + format_bytes(budget) +
                             " memory budget; is it damaged?)");
        }
        throw LimitExceeded(path + ": reading it needs more memory than the " + format_bytes(budget) +
                            " budget allows (--memory, GROOM_MEMORY; the file is " + format_bytes(file_bytes) + "): raise --memory");
    }
    if (reply[0] == 'E') throw ParseError(path + ": not a readable .vdb file (" + reply.substr(1) + ")");
    // The grid's stream is most of the reply: kept in place (the list cut from its front), not copied.
    DecodedVdb decoded;
    size_t at = reply.find('\n');
    size_t count = 0;
    if (at == std::string::npos || std::sscanf(reply.c_str() + 1, "%zu %d", &count, &decoded.chosen) != 2 || decoded.chosen >= int64_t(count)) {
        throw IoError(path + ": cannot read (the reading process's reply is malformed)");
    }
    for (size_t i = 0; i < count; ++i) {
        const size_t begin = at + 1;
        at = reply.find('\n', begin);
        if (at == std::string::npos) throw IoError(path + ": cannot read (the reading process's reply is malformed)");
        std::istringstream line(reply.substr(begin, at - begin));
        GridEntry g;
        std::string usable;
        std::getline(line, g.name, '\t');
        std::getline(line, g.type, '\t');
        std::getline(line, g.cls, '\t');
        std::getline(line, usable);
        g.usable = usable == "1";
        decoded.grids.push_back(std::move(g));
    }
    reply.erase(0, at + 1);
    decoded.grid_stream = std::move(reply);
    return decoded;
}

/// Everything the queries rely on, checked on what OpenVDB decoded from `path`: a corrupt file that
/// OpenVDB reads without complaint (a flipped bit in a value, the transform or a leaf's origin) is
/// refused here rather than met later as NaN distances, a huge allocation or a crash.
void check_scalp_grid(const openvdb::FloatGrid& sdf, const std::string& path, const std::string& name)
{
    const std::string where = path + ": grid '" + name + "' ";
    if (sdf.getGridClass() != openvdb::GRID_LEVEL_SET && !(sdf.getGridClass() == openvdb::GRID_UNKNOWN && plainly_sdf(sdf))) {
        throw ParseError(where + "is not a level set (class '" + openvdb::GridBase::gridClassToString(sdf.getGridClass()) +
                         "'); expected a signed distance field from `groom scalp`");
    }
    const openvdb::math::Transform& xf = sdf.transform();
    if (!xf.isLinear() || !xf.hasUniformScale()) {
        throw ParseError(where + "has a non-linear or non-uniform transform; groom needs cubic, axis-aligned voxels "
                                 "(resample it, e.g. with vdb_tool -resample)");
    }
    const openvdb::Vec3d vs = xf.voxelSize();
    const openvdb::Vec3d o = xf.indexToWorld(openvdb::Vec3d(0, 0, 0));
    if (!(std::isfinite(vs[0]) && vs[0] > 0.0 && vs[0] < 1e18) || !std::isfinite(o.x()) || !std::isfinite(o.y()) ||
        !std::isfinite(o.z())) {
        throw ParseError(where + "has voxel size " + format_number(vs[0]) + " at origin (" + format_number(o.x()) + ", " +
                         format_number(o.y()) + ", " + format_number(o.z()) +
                         "); expected a finite voxel size > 0 and a finite origin (is the file corrupt?)");
    }
    const float bg = sdf.background();
    if (!(std::isfinite(bg) && bg > 0.0f && double(bg) < 1e6 * vs[0])) {
        throw ParseError(where + "has background " + format_number(bg) + "; a level set's is its band's half width, > 0 and finite " +
                         "(is the file corrupt?)");
    }
    if (sdf.tree().leafCount() == 0 || sdf.activeVoxelCount() == 0) throw ParseError(where + "has no active voxels");
    // Index coordinates: OpenVDB's are int32; ours (BrickMap, the extracted mesh) are floats, which
    // must still resolve a voxel.
    const openvdb::CoordBBox box = sdf.evalActiveVoxelBoundingBox();
    constexpr int32_t kMaxIndex = 1 << 24;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(int64_t(box.min()[axis])) > kMaxIndex || std::abs(int64_t(box.max()[axis])) > kMaxIndex) {
            throw ParseError(where + "has active voxels at index " + std::to_string(box.min()[axis]) + " to " +
                             std::to_string(box.max()[axis]) + " on axis " + std::to_string(axis) + "; expected within +-" +
                             std::to_string(kMaxIndex) + " (is the file corrupt?)");
        }
    }
    // Every value, tiles and inactive voxels too: they are what the band's edge interpolates.
    for (auto it = sdf.cbeginValueAll(); it; ++it) {
        const float v = *it;
        if (!std::isfinite(v)) {
            const openvdb::Coord c = it.getCoord();
            throw ParseError(where + "holds a non-finite distance (" + format_number(v) + ") at voxel (" + std::to_string(c.x()) +
                             ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + "); is the file corrupt?");
        }
    }
}

/// A stored mesh belongs with its level set: it lies within the grid's active voxels (the band
/// surrounds every triangle), which metadata pasted from another file would not.
void check_source_mesh(const openvdb::FloatGrid& sdf, const detail::SourceMesh& mesh, const std::string& path)
{
    const openvdb::CoordBBox box = sdf.evalActiveVoxelBoundingBox();
    const openvdb::math::Transform& xf = sdf.transform();
    for (const float3& p : mesh.points) {
        const openvdb::Vec3d i = xf.worldToIndex(openvdb::Vec3d(p.x, p.y, p.z));
        for (int axis = 0; axis < 3; ++axis) {
            if (!(i[axis] >= box.min()[axis] - 1.0 && i[axis] <= box.max()[axis] + 1.0)) {
                throw ParseError(path + ": source mesh (grid metadata '" + kMeshMeta + "'): vertex " +
                                 std::to_string(&p - mesh.points.data()) + " at (" + format_number(p.x) + ", " + format_number(p.y) + ", " +
                                 format_number(p.z) + ") lies outside the level set's band; the mesh does not belong to this grid "
                                 "(is the file corrupt?)");
            }
        }
    }
}

}  // namespace

ScalpField read_scalp_vdb(const std::string& path, Progress* progress, const std::string& grid)
{
    detail::init_openvdb();
    if (!std::filesystem::exists(path)) throw IoError(path + ": no such file");
    DecodedVdb decoded = decode_isolated(path, grid);
    const std::string found = list_grids(decoded.grids);
    if (decoded.chosen < 0) {
        // Never suggest writing over the user's file (a trial: `groom scalp MESH -o houdini_like.vdb`,
        // offered for Houdini's own file, would have replaced it).
        if (!grid.empty()) throw InvalidParam("--scalp-grid " + grid + ": " + path + " has no grid of that name (found: " + found + ")");
        const int usable = int(std::count_if(decoded.grids.begin(), decoded.grids.end(), [](const GridEntry& g) { return g.usable; }));
        if (usable > 1) {
            throw ParseError(path + ": no grid is named 'scalp' and " + std::to_string(usable) + " are float level sets (found: " + found +
                             "); choose one with --scalp-grid NAME");
        }
        const std::string stem = std::filesystem::path(path).stem().string();
        throw ParseError(path + ": no grid is named 'scalp' and none is a float level set (found: " + found +
                         "); groom needs the head as a signed distance field: give --scalp the head's mesh instead, or make a field "
                         "from it with `groom scalp MESH -o " + stem + "_scalp.vdb`");
    }
    const std::string name = decoded.grids[size_t(decoded.chosen)].name;
    openvdb::GridBase::Ptr base;
    if (!decoded.grid_stream.empty()) {
        // A stream OpenVDB itself wrote a moment ago, with sizes that agree with its contents: safe to
        // decode here. What it holds (the values, the transform) is checked below. Moved into the
        // stream, not copied, and gone once decoded: it is as large as the grid.
        try {
            std::istringstream in(std::move(decoded.grid_stream));
            openvdb::io::Stream stream(in, /*delayLoad=*/false);
            const openvdb::GridPtrVecPtr grids = stream.getGrids();
            if (grids && !grids->empty()) base = grids->front();
        }
        catch (const std::exception& e) {
            throw ParseError(path + ": not a readable .vdb file (" + e.what() + ")");
        }
    }
    if (!base) throw IoError(path + ": cannot read (the reading process brought back no grid '" + name + "')");
    openvdb::FloatGrid::Ptr sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!sdf) throw ParseError(path + ": grid '" + name + "' holds " + base->valueType() + " values; expected a float level set");
    check_scalp_grid(*sdf, path, name);
    // A grid without a class that passed as plainly a signed distance is one from here on.
    sdf->setGridClass(openvdb::GRID_LEVEL_SET);
    std::shared_ptr<const detail::UvMap> uv;
    if (const openvdb::Metadata::ConstPtr meta = (*sdf)[kUvMeta]) {
        const auto* text = dynamic_cast<const openvdb::StringMetadata*>(meta.get());
        if (!text) throw ParseError(path + ": grid metadata '" + kUvMeta + "' holds " + meta->typeName() + "; expected a string (is the file corrupt?)");
        uv = detail::UvMap::decode(text->value(), path);
    }
    std::optional<detail::SourceMesh> source;
    if (const openvdb::Metadata::ConstPtr meta = (*sdf)[kMeshMeta]) {
        const auto* text = dynamic_cast<const openvdb::StringMetadata*>(meta.get());
        if (!text) throw ParseError(path + ": grid metadata '" + kMeshMeta + "' holds " + meta->typeName() + "; expected a string (is the file corrupt?)");
        source = detail::decode_source_mesh(text->value(), path);
        check_source_mesh(*sdf, *source, path);
    }
    // The texts are decoded: the grid need not carry them (a large mesh's are megabytes).
    sdf->removeMeta(kUvMeta);
    sdf->removeMeta(kMeshMeta);

    // Without a stored mesh (another program's file, an older groom's), the mesh for far queries and
    // sampling is the zero crossing. Adaptivity 0.2 merges flat runs of cells: on Sintel's head
    // (voxel 0.24) 15,468 triangles instead of 141,442 (the user's mesh had 5,952), `generate
    // --count 100000` from the file 2.3 s CPU instead of 6.7 s (1.8 s from the mesh), at a median
    // distance error outside the band of 0.23 voxel instead of 0.04 (99th percentile 1.8 against
    // 1.7, set by the rims). Extracted first: its size is what the estimate below needs.
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    if (!source) openvdb::tools::volumeToMesh(*sdf, points, tris, quads, 0.0, 0.2);

    // Memory estimate before the large allocations (the decoded grid is already held): the query
    // bricks (9^3 distance + gradient values per leaf, built on the first query), and the mesh's
    // geometry, AABB tree and far-field certificates, about 400 bytes a triangle, or, for an
    // extracted mesh, 500 bytes a triangle of the extraction, which the repair also goes through.
    const double leaves = double(sdf->tree().leafCount());
    const double bricks = leaves * 729.0 * double(sizeof(detail::BandValue));
    const double mesh_bytes = source ? double(source->tris.size()) * 400.0 : double(tris.size() + 2 * quads.size()) * 500.0;
    const uint64_t held = resident_bytes();
    const double estimate = double(held ? held : 40ull << 20) + bricks + mesh_bytes;
    check_memory(path + ": the scalp's query bricks and mesh (" + format_number(leaves) + " leaves of the level set)", bricks + mesh_bytes,
                 "make the scalp with a larger `voxel` (groom scalp --voxel)");

    // Which grid of another program's file was used: said in the step's label (--verbose), so a
    // file with a grid of another name is never read without a word.
    const std::string label = "load scalp" + (name == "scalp" ? std::string() : " from grid '" + name + "'" + (grid.empty() ? " (the only float level set)" : "")) +
                              " (estimated " + format_bytes(estimate) + ")";
    ProgressStep step(progress, label, 2);
    ScalpField field;
    ScalpField::Impl& im = field.impl();
    im.sdf = sdf;
    im.grid_name = name;
    im.set_transform(path);
    sdf->setName("scalp");  // to the rest of groom: a field written back out is groom's own file
    step.advance(1);
    im.uv = std::move(uv);
    if (source) {
        // The mesh `groom scalp` built the field from: every query answers as with that mesh.
        im.geometry.compute(std::move(source->points), std::move(source->tris));
        im.mesh_exact = true;
        im.query = std::make_unique<detail::MeshQuery>(im.geometry);
        step.advance(1);
        return field;
    }

    // The zero crossing, each face turned to agree with the distance's increase across it. A sign
    // flip with large |d| on both sides is the seam an open surface's sign makes beyond its rim, not
    // surface: such faces (a rise of more than 1.5 voxels over one voxel across them) are dropped.
    // Read from the grid itself: the query bricks leave voxels beside such seams out.
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
    if (soup.num_faces() == 0) throw ParseError(path + ": grid '" + name + "' has no zero crossing (no surface inside its band)");
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
    if (io::extension_of(path) == "vdb" && !params.group.empty()) {
        throw InvalidParam("--scalp-group " + params.group + ": " + path + " is a level set, not a mesh; choose the group when making it (groom scalp --group)");
    }
    if (io::extension_of(path) != "vdb" && !params.grid.empty()) {
        throw InvalidParam("--scalp-grid " + params.grid + ": " + path + " is a mesh, not a .vdb; the option picks a grid of a .vdb");
    }
    if (io::extension_of(path) != "vdb" && !is_mesh_path(path)) {
        // A typo ("head.vbd") is first of all a file that is not there: say so.
        std::error_code ec;
        const bool exists = std::filesystem::exists(path, ec);
        throw InvalidParam("`scalp` " + path + ": " + (exists ? std::string() : "no such file; ") +
                           "expected a .vdb level set from `groom scalp` or a mesh (" + io::format_list(io::kReadMesh) + ")");
    }
    // Frames of an animation load one unchanged file many times (fields/scalp_cache.h).
    return cached_scalp(path, params, [&]() -> std::shared_ptr<const ScalpField> {
        if (io::extension_of(path) == "vdb") return std::make_shared<ScalpField>(read_scalp_vdb(path, progress, params.grid));
        ScalpBuildParams named = params;
        named.source = path;
        return std::make_shared<ScalpField>(build_scalp(read_mesh(path, params.group), named, nullptr, progress));
    });
}

}  // namespace groom
