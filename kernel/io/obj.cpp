// Wavefront OBJ: `v` positions, `l` polylines (curves) and `f` faces (meshes). One `l` record is
// one curve, root first; a soup keeps every `f` record as one face.
#include "kernel/io/formats.h"

#include <cmath>
#include <limits>

namespace groom::io {

namespace {

/// Resolves one OBJ index token ("7", "-2", "7/3", "7//1", "7/3/1") against `num_points` vertices
/// defined so far. Positive indices may point forward (checked at the end of the file).
int64_t resolve_index(const FileBytes& file, size_t line, std::string_view token, size_t num_points)
{
    const std::string_view head = token.substr(0, token.find('/'));
    if (head.empty()) fail_at_line(file.name, line, "expected a vertex index, found " + describe_found(token));
    int64_t i = 0;
    if (!parse_int(head, i)) fail_at_line(file.name, line, "expected a vertex index, found " + describe_found(token));
    if (i == 0) fail_at_line(file.name, line, "vertex index 0 is invalid (OBJ indices start at 1)");
    if (i < 0) {
        const int64_t abs = static_cast<int64_t>(num_points) + i;
        if (abs < 0) {
            fail_at_line(file.name, line, "relative vertex index " + std::to_string(i) + " reaches before the first vertex (" +
                                              std::to_string(num_points) + " vertices defined so far)");
        }
        return abs;
    }
    return i - 1;
}

struct Pending {
    size_t line;
    int64_t index;
};

/// The texture-coordinate index of a face corner token ("7/3" or "7/3/1" -> 2; "7", "7//1" -> -1),
/// resolved like vertex indices against the `vt` records so far (forward ones checked at the end).
int64_t resolve_uv_index(const FileBytes& file, size_t line, std::string_view token, size_t num_uvs)
{
    const size_t slash = token.find('/');
    if (slash == std::string_view::npos) return -1;
    std::string_view t = token.substr(slash + 1);
    t = t.substr(0, t.find('/'));
    if (t.empty()) return -1;
    int64_t i = 0;
    if (!parse_int(t, i)) fail_at_line(file.name, line, "expected a texture coordinate index after '/', found " + describe_found(token));
    if (i == 0) fail_at_line(file.name, line, "texture coordinate index 0 is invalid (OBJ indices start at 1)");
    if (i < 0) {
        const int64_t abs = static_cast<int64_t>(num_uvs) + i;
        if (abs < 0) {
            fail_at_line(file.name, line, "relative texture coordinate index " + std::to_string(i) + " reaches before the first 'vt' (" +
                                              std::to_string(num_uvs) + " defined so far)");
        }
        return abs;
    }
    if (i - 1 >= std::numeric_limits<int32_t>::max()) fail_at_line(file.name, line, "texture coordinate index " + std::to_string(i) + " exceeds 2^31");
    return i - 1;
}

}  // namespace

ObjData parse_obj(const FileBytes& file)
{
    ObjData obj;
    TextCursor cur(file.data);
    std::vector<Pending> forward;  // indices past the vertices defined so far, checked at the end
    std::vector<int32_t> record, uv_record;
    std::vector<Pending> forward_uv;
    bool any_uv = false;
    // Texture coordinates are read for faces only: a curve's `l i/vt` keeps ignoring them.
    auto take_indices = [&](const char* what, bool face) {
        record.clear();
        uv_record.clear();
        for (std::string_view t = cur.token(); !t.empty() && t.front() != '#'; t = cur.token()) {
            if (face) {
                const int64_t uv = resolve_uv_index(file, cur.line(), t, obj.faces.uvs.size() / 2);
                if (uv >= static_cast<int64_t>(obj.faces.uvs.size() / 2)) forward_uv.push_back({cur.line(), uv});
                any_uv = any_uv || uv >= 0;
                uv_record.push_back(static_cast<int32_t>(uv));
            }
            const int64_t i = resolve_index(file, cur.line(), t, obj.points.size());
            if (i >= std::numeric_limits<int32_t>::max()) {
                fail_at_line(file.name, cur.line(), std::string(what) + " index " + std::to_string(i + 1) + " exceeds 2^31");
            }
            if (i >= static_cast<int64_t>(obj.points.size())) forward.push_back({cur.line(), i});
            record.push_back(static_cast<int32_t>(i));
        }
    };
    if (!file.data.empty()) {
        do {
            const std::string_view key = cur.token();
            if (key.empty() || key.front() == '#') continue;
            if (key == "v") {
                float3 p;
                for (int k = 0; k < 3; ++k) {
                    const std::string_view t = cur.token();
                    if (!parse_float(t, p[k])) {
                        fail_at_line(file.name, cur.line(), "expected 3 vertex coordinates, found " + describe_found(t));
                    }
                }
                if (!isfinite(p)) fail_at_line(file.name, cur.line(), "vertex coordinate is not finite (NaN or inf)");
                obj.points.push_back(p);
            }
            else if (key == "l") {
                take_indices("line", false);
                if (record.empty()) fail_at_line(file.name, cur.line(), "expected vertex indices after 'l', found end of line");
                obj.line_indices.insert(obj.line_indices.end(), record.begin(), record.end());
                obj.line_offsets.push_back(static_cast<int64_t>(obj.line_indices.size()));
            }
            else if (key == "f") {
                take_indices("face", true);
                if (record.empty()) fail_at_line(file.name, cur.line(), "expected vertex indices after 'f', found end of line");
                if (any_uv) obj.faces.add_face(record, uv_record);
                else obj.faces.add_face(record);
            }
            else if (key == "vt") {
                // u [v [w]]: v defaults to 0 (the OBJ spec); w is dropped.
                float uv[2] = {0.0f, 0.0f};
                for (int k = 0; k < 2; ++k) {
                    const std::string_view t = cur.token();
                    if (k == 1 && (t.empty() || t.front() == '#')) break;
                    if (!parse_float(t, uv[k]) || !std::isfinite(uv[k])) {
                        fail_at_line(file.name, cur.line(), "expected a finite texture coordinate u [v], found " + describe_found(t));
                    }
                }
                obj.faces.uvs.push_back(uv[0]);
                obj.faces.uvs.push_back(uv[1]);
            }
            else if (key == "vn" || key == "vp" || key == "o" || key == "g" || key == "s" || key == "usemtl" ||
                     key == "mtllib" || key == "p" || key == "curv" || key == "cstype" || key == "deg" || key == "mg") {
                // Not geometry we keep.
            }
            else {
                fail_at_line(file.name, cur.line(),
                             "expected an OBJ record (v, l, f, vt, vn, o, g, s, usemtl, mtllib, #), found " + describe_found(key));
            }
        } while (cur.next_line());
    }
    for (const Pending& p : forward_uv) {
        if (p.index >= static_cast<int64_t>(obj.faces.uvs.size() / 2)) {
            fail_at_line(file.name, p.line, "texture coordinate index " + std::to_string(p.index + 1) + " out of range (" +
                                                std::to_string(obj.faces.uvs.size() / 2) + " 'vt' records)");
        }
    }
    for (const Pending& p : forward) {
        if (p.index >= static_cast<int64_t>(obj.points.size())) {
            fail_at_line(file.name, p.line, "vertex index " + std::to_string(p.index + 1) + " out of range (" +
                                                std::to_string(obj.points.size()) + " vertices)");
        }
    }
    return obj;
}

CurveSet read_obj_curves(const FileBytes& file)
{
    ObjData obj = parse_obj(file);
    if (obj.line_offsets.size() == 1 && obj.faces.num_faces() > 0) {
        throw ParseError(file.name + ": expected curves ('l' polylines), found only faces ('f', " +
                         std::to_string(obj.faces.num_faces()) + " of them): this is a mesh");
    }
    const size_t n = obj.line_offsets.size() - 1;
    std::vector<int64_t> counts(n);
    for (size_t c = 0; c < n; ++c) counts[c] = obj.line_offsets[c + 1] - obj.line_offsets[c];
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < obj.line_indices.size(); ++i) P[i] = obj.points[obj.line_indices[i]];
    return cs;
}

std::string write_obj_curves(const CurveSet& curves)
{
    std::string out;
    out.reserve(curves.num_points() * 36 + curves.num_curves() * 8 + 128);
    out += "# groom curves: " + std::to_string(curves.num_curves()) + " curves, " + std::to_string(curves.num_points()) +
           " points (OBJ keeps positions only)\n";
    for (const float3& p : curves.positions()) {
        out += "v ";
        append_number(out, p.x);
        out += ' ';
        append_number(out, p.y);
        out += ' ';
        append_number(out, p.z);
        out += '\n';
    }
    for (size_t c = 0; c < curves.num_curves(); ++c) {
        const IndexRange r = curves.points_of(c);
        if (r.empty()) continue;  // OBJ cannot hold an empty polyline
        out += 'l';
        for (int64_t i = r.begin; i < r.end; ++i) {
            out += ' ';
            append_number(out, i + 1);
        }
        out += '\n';
    }
    return out;
}

PolygonSoup read_obj_mesh(const FileBytes& file)
{
    ObjData obj = parse_obj(file);
    if (obj.faces.num_faces() == 0 && obj.line_offsets.size() > 1) {
        throw ParseError(file.name + ": expected a mesh ('f' faces), found only polylines ('l'): these are curves");
    }
    obj.faces.points = std::move(obj.points);
    return std::move(obj.faces);
}

std::string write_obj_mesh(const PolygonSoup& soup)
{
    std::string out;
    out.reserve(soup.points.size() * 36 + soup.face_indices.size() * 8 + 64);
    out += "# groom mesh: " + std::to_string(soup.points.size()) + " vertices, " + std::to_string(soup.num_faces()) + " faces\n";
    for (const float3& p : soup.points) {
        out += "v ";
        append_number(out, p.x);
        out += ' ';
        append_number(out, p.y);
        out += ' ';
        append_number(out, p.z);
        out += '\n';
    }
    for (size_t f = 0; f < soup.num_faces(); ++f) {
        out += 'f';
        for (int32_t i : soup.face(f)) {
            out += ' ';
            append_number(out, i + 1);
        }
        out += '\n';
    }
    return out;
}

}  // namespace groom::io
