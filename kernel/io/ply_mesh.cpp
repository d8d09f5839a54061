// PLY meshes: a `vertex` element (x, y, z) and a `face` element with a list property of vertex indices.
// Apart from the curves because a mesh needs none of the curve elements or groom comments.
#include "kernel/io/formats.h"
#include "kernel/io/ply_data.h"
#include "kernel/io/ply_writer.h"

#include <cmath>

namespace groom::io {

PolygonSoup read_ply_mesh(const FileBytes& file)
{
    using namespace ply;
    const PlyData ply = parse_ply(file);
    const PlyElement* v = ply.find("vertex");
    if (!v) throw ParseError(file.name + ": expected a 'vertex' element, found none");
    const PlyElement* f = ply.find("face");
    if (!f) throw ParseError(file.name + ": expected a 'face' element, found none: not a mesh");
    const PlyProperty* idx = f->find("vertex_indices");
    if (!idx) idx = f->find("vertex_index");
    if (!idx || !idx->is_list) fail_at_line(file.name, f->line, "expected a list property 'vertex_indices' on element face");
    PolygonSoup soup;
    soup.points = read_positions(file, *v);
    std::vector<int32_t> face;
    for (size_t r = 0; r < f->count; ++r) {
        face.clear();
        for (int64_t k = idx->list_offsets[r]; k < idx->list_offsets[r + 1]; ++k) {
            const double i = idx->values[k];
            if (!(i >= 0 && i < static_cast<double>(soup.points.size()) && i == std::floor(i))) {  // NaN and fractions fail too
                throw ParseError(file.name + ": face " + std::to_string(r) + " uses vertex " + number_text(i) + ", out of range (" +
                                 std::to_string(soup.points.size()) + " vertices)");
            }
            face.push_back(static_cast<int32_t>(i));
        }
        soup.add_face(face);
    }
    return soup;
}

std::string write_ply_mesh(const PolygonSoup& soup)
{
    using namespace ply;
    PlyWriter w(PlyEncoding::Binary);
    w.begin({"groom " GROOM_VERSION " mesh"});
    const auto& P = soup.points;
    w.element("vertex", P.size(), {{"x", PlyType::Float32, [&P](size_t i) { return double(P[i].x); }},
                                   {"y", PlyType::Float32, [&P](size_t i) { return double(P[i].y); }},
                                   {"z", PlyType::Float32, [&P](size_t i) { return double(P[i].z); }}});
    w.list_element("face", "vertex_indices", soup);
    return w.finish();
}

}  // namespace groom::io
