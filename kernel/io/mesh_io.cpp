#include "kernel/io/mesh_io.h"

#include "kernel/io/atomic_file.h"
#include "kernel/io/format_table.h"
#include "kernel/io/io_util.h"

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
