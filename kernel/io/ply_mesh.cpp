// PLY meshes: a `vertex` element (x, y, z) and a `face` element with a list property of vertex indices.
// Apart from the curves because a mesh needs none of the curve elements or groom comments.
#include "kernel/io/formats.h"
#include "kernel/io/ply_data.h"
#include "kernel/io/ply_writer.h"

#include <cmath>

namespace groom::io {

namespace {

/// Texture coordinates: per vertex as u/v, s/t or texture_u/texture_v (the names exporters use:
/// Blender, MeshLab, Open3D), or per face corner as a float list `texcoord` (u0 v0 u1 v1 ...,
/// MeshLab's face-varying form), which wins when both are present.
void read_uvs(const FileBytes& file, const ply::PlyElement& v, const ply::PlyElement& f, PolygonSoup& soup)
{
    const ply::PlyProperty* corner = f.find("texcoord");
    if (corner && corner->is_list) {
        for (size_t r = 0; r < f.count; ++r) {
            const int64_t n = corner->list_offsets[r + 1] - corner->list_offsets[r];
            const int64_t corners = soup.face_offsets[r + 1] - soup.face_offsets[r];
            if (n != 2 * corners) {
                throw ParseError(file.name + ": face " + std::to_string(r) + " has " + std::to_string(n) + " texcoord values; expected 2 per corner (" +
                                 std::to_string(2 * corners) + ")");
            }
        }
        soup.uvs.reserve(corner->values.size());
        for (double x : corner->values) {
            if (!std::isfinite(x)) throw ParseError(file.name + ": a face's texcoord is not finite (NaN or inf)");
            soup.uvs.push_back(float(x));
        }
        soup.face_uv_indices.resize(soup.face_indices.size());
        for (size_t i = 0; i < soup.face_uv_indices.size(); ++i) soup.face_uv_indices[i] = int32_t(i);
        return;
    }
    const char* names[][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const auto& [un, vn] : names) {
        const ply::PlyProperty* pu = v.find(un);
        const ply::PlyProperty* pv = v.find(vn);
        if (!pu || !pv || pu->is_list || pv->is_list) continue;
        soup.uvs.resize(2 * v.count);
        for (size_t i = 0; i < v.count; ++i) {
            if (!std::isfinite(pu->values[i]) || !std::isfinite(pv->values[i])) {
                throw ParseError(file.name + ": vertex " + std::to_string(i) + " has a non-finite texture coordinate (" + un + ", " + vn + ")");
            }
            soup.uvs[2 * i] = float(pu->values[i]);
            soup.uvs[2 * i + 1] = float(pv->values[i]);
        }
        soup.face_uv_indices = soup.face_indices;  // per vertex: each corner's pair is its vertex's
        return;
    }
}

}  // namespace

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
    read_uvs(file, *v, *f, soup);
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
