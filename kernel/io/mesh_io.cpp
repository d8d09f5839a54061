#include "kernel/io/mesh_io.h"

#include "kernel/io/atomic_file.h"
#include "kernel/io/format_table.h"
#include "kernel/io/formats.h"
#include "kernel/io/io_util.h"

#include <algorithm>

namespace groom {

bool is_mesh_path(const std::string& path)
{
    const io::Format* f = io::format_of_path(path);
    return f && f->can(io::kReadMesh);
}

PolygonSoup read_mesh(const std::string& path)
{
    const io::Format& fmt = io::format_for(path, io::kReadMesh, "mesh");
    const io::FileBytes file = io::read_all(path);
    if (file.data.empty()) throw ParseError(file.name + ": file is empty (expected a mesh)");
    return fmt.read_mesh(file);
}

PolygonSoup read_mesh(const std::string& path, const std::string& group)
{
    if (group.empty()) return read_mesh(path);
    const io::Format& fmt = io::format_for(path, io::kReadMesh, "mesh");
    if (fmt.extension != "obj") {
        throw InvalidParam("--group " + group + ": only OBJ meshes have named groups ('o' and 'g' records); " + path + " is not an .obj");
    }
    const io::FileBytes file = io::read_all(path);
    if (file.data.empty()) throw ParseError(file.name + ": file is empty (expected a mesh)");
    return io::read_obj_mesh(file, group);
}

std::vector<MeshGroup> read_mesh_groups(const std::string& path)
{
    const io::Format& fmt = io::format_for(path, io::kReadMesh, "mesh");
    if (fmt.extension != "obj") return {};
    const io::ObjData obj = io::parse_obj(io::read_all(path));
    std::vector<int64_t> per_set(obj.names.size(), 0);
    for (int32_t k : obj.face_names) ++per_set[size_t(k)];
    std::vector<MeshGroup> out;
    for (size_t k = 0; k < obj.names.size(); ++k) {
        for (const std::string& name : obj.names[k]) {
            auto it = std::find_if(out.begin(), out.end(), [&](const MeshGroup& g) { return g.name == name; });
            if (it == out.end()) it = out.insert(out.end(), MeshGroup{name, 0});
            it->faces += per_set[k];
        }
    }
    return out;
}

void write_mesh(const PolygonSoup& soup, const std::string& path)
{
    const io::Format& fmt = io::format_for(path, io::kWriteMesh, "mesh", {}, /*error_is_param=*/true);
    for (int32_t i : soup.face_indices) {
        if (i < 0 || static_cast<size_t>(i) >= soup.points.size()) {
            throw InvalidGeometry("writing " + path + ": face index " + std::to_string(i) + " out of range (" +
                                  std::to_string(soup.points.size()) + " vertices)");
        }
    }
    const std::string bytes = fmt.write_mesh(soup);
    AtomicOutput out(path);
    out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.commit();
}

}  // namespace groom
