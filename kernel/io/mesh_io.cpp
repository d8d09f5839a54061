#include "kernel/io/mesh_io.h"

#include "kernel/io/atomic_file.h"
#include "kernel/io/formats.h"

namespace groom {

bool is_mesh_path(const std::string& path)
{
    const std::string ext = io::extension_of(path);
    return ext == "obj" || ext == "ply" || ext == "off" || ext == "stl";
}

PolygonSoup read_mesh(const std::string& path)
{
    if (!is_mesh_path(path)) {
        throw IoError(path + ": unknown mesh format '." + io::extension_of(path) + "' (expected .obj, .ply, .off, .stl)");
    }
    const io::FileBytes file = io::read_all(path);
    if (file.data.empty()) throw ParseError(file.name + ": file is empty (expected a mesh)");
    const std::string ext = io::extension_of(path);
    if (ext == "obj") return io::read_obj_mesh(file);
    if (ext == "ply") return io::read_ply_mesh(file);
    if (ext == "off") return io::read_off(file);
    return io::read_stl(file);
}

void write_mesh(const PolygonSoup& soup, const std::string& path)
{
    const std::string ext = io::extension_of(path);
    if (ext != "obj" && ext != "ply") throw InvalidParam(path + ": meshes are written as .obj or .ply (got '." + ext + "')");
    for (int32_t i : soup.face_indices) {
        if (i < 0 || static_cast<size_t>(i) >= soup.points.size()) {
            throw InvalidGeometry("writing " + path + ": face index " + std::to_string(i) + " out of range (" +
                                  std::to_string(soup.points.size()) + " vertices)");
        }
    }
    const std::string bytes = ext == "obj" ? io::write_obj_mesh(soup) : io::write_ply_mesh(soup);
    AtomicOutput out(path);
    out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.commit();
}

}  // namespace groom
