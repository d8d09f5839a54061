// Wavefront OBJ: `v` positions, `l` polylines (curves) and `f` faces (meshes). An `l` record of 3 or
// more points is one curve, root first; two-point records are joined into chains (Blender writes one
// per edge). A soup keeps every `f` record as one face, optionally only those of one `o`/`g` name.
#include "kernel/curve_set_edit.h"
#include "kernel/io/detail_text.h"
#include "kernel/io/edge_chains.h"
#include "kernel/io/formats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <ostream>

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
    // Names in force: the object's (`o`) then the groups' (`g`, several allowed); a new `o` clears the groups.
    std::string object;
    std::vector<std::string> groups;
    std::map<std::vector<std::string>, int32_t> name_ids;
    obj.names.emplace_back();
    name_ids[{}] = 0;
    int32_t current_names = 0;
    auto update_names = [&] {
        std::vector<std::string> set;
        if (!object.empty()) set.push_back(object);
        set.insert(set.end(), groups.begin(), groups.end());
        const auto [it, fresh] = name_ids.try_emplace(set, int32_t(obj.names.size()));
        if (fresh) obj.names.push_back(set);
        current_names = it->second;
    };
    auto rest_names = [&] {
        std::vector<std::string> v;
        for (std::string_view t = cur.token(); !t.empty() && t.front() != '#'; t = cur.token()) v.emplace_back(t);
        return v;
    };
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
                if (!isfinite(p)) fail_at_line(file.name, cur.line(), "vertex coordinate is not finite (NaN, inf, or past float's range of 3.4e38)");
                obj.points.push_back(p);
            }
            else if (key == "l") {
                take_indices("line", false);
                if (record.empty()) fail_at_line(file.name, cur.line(), "expected vertex indices after 'l', found end of line");
                obj.line_indices.insert(obj.line_indices.end(), record.begin(), record.end());
                obj.line_offsets.push_back(static_cast<int64_t>(obj.line_indices.size()));
                obj.line_lines.push_back(cur.line());
            }
            else if (key == "f") {
                take_indices("face", true);
                if (record.empty()) fail_at_line(file.name, cur.line(), "expected vertex indices after 'f', found end of line");
                if (record.size() < 3) {
                    // Not a polygon: counted as a degenerate face it vanished into the repair report unnamed.
                    fail_at_line(file.name, cur.line(), "expected a face of 3 or more vertex indices, found " + std::to_string(record.size()) +
                                                          " (an edge is an 'l' record)");
                }
                if (any_uv) obj.faces.add_face(record, uv_record);
                else obj.faces.add_face(record);
                obj.face_names.push_back(current_names);
            }
            else if (key == "o") {
                const std::vector<std::string> v = rest_names();
                object.clear();
                for (const std::string& t : v) object += (object.empty() ? "" : " ") + t;  // an object name may hold spaces
                groups.clear();
                update_names();
            }
            else if (key == "g") {
                groups = rest_names();
                update_names();
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
            else if (key == "vn" || key == "vp" || key == "s" || key == "usemtl" ||
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

CurveSet read_obj_curves(const FileBytes& file, bool closed_loops)
{
    ObjData obj = parse_obj(file);
    if (obj.line_offsets.size() == 1 && obj.faces.num_faces() > 0) {
        throw ParseError(file.name + ": expected curves ('l' polylines), found only faces ('f', " +
                         std::to_string(obj.faces.num_faces()) + " of them): this is a mesh");
    }
    const size_t n = obj.line_offsets.size() - 1;
    // Two-point records are edges, joined where they share a vertex; the others are whole curves.
    std::vector<int64_t> from, to, edge_record;
    for (size_t r = 0; r < n; ++r) {
        if (obj.line_offsets[r + 1] - obj.line_offsets[r] != 2) continue;
        const int64_t a = obj.line_indices[size_t(obj.line_offsets[r])], b = obj.line_indices[size_t(obj.line_offsets[r]) + 1];
        if (a == b) fail_at_line(file.name, obj.line_lines[r], "'l' record joins vertex " + std::to_string(a + 1) + " to itself");
        from.push_back(a), to.push_back(b), edge_record.push_back(int64_t(r));
    }
    const EdgeChains chains = join_edge_chains(int64_t(obj.points.size()), from, to, false, file.name, 1, "two-point 'l' records (edges)", closed_loops);
    // Only edges (Blender's files): curves in the order of their vertices, which is the order the
    // exporter had them in (it writes the edges themselves in another order). With whole records
    // too: each curve where its first record is in the file. Files groom writes (no shared
    // vertices, vertices in curve order) read back curve for curve either way.
    struct Piece {
        int64_t record;
        const int32_t* indices32;   // a whole record, or
        const int64_t* indices64;   // a chain
        int64_t count;
    };
    std::vector<Piece> pieces;
    for (size_t r = 0; r < n; ++r) {
        const int64_t k = obj.line_offsets[r + 1] - obj.line_offsets[r];
        if (k != 2) pieces.push_back({int64_t(r), obj.line_indices.data() + obj.line_offsets[r], nullptr, k});
    }
    for (size_t c = 0, at = 0; c < chains.counts.size(); at += size_t(chains.counts[c]), ++c) {
        pieces.push_back({edge_record[size_t(chains.first_edge[c])], nullptr, chains.order.data() + at, chains.counts[c]});
    }
    if (from.size() < n) std::stable_sort(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return x.record < y.record; });
    std::vector<int64_t> counts(pieces.size());
    for (size_t c = 0; c < pieces.size(); ++c) counts[c] = pieces[c].count;
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    size_t i = 0;
    // Every curve a loop (a record back to its first vertex, a closed chain of edges): closed curves.
    bool loops = !pieces.empty();
    for (const Piece& piece : pieces) {
        auto index = [&](int64_t j) { return piece.indices32 ? int64_t(piece.indices32[j]) : piece.indices64[j]; };
        for (int64_t j = 0; j < piece.count; ++j) P[i++] = obj.points[size_t(index(j))];
        loops = loops && piece.count >= 3 && index(0) == index(piece.count - 1);
    }
    // Detail values groom wrote as comments (a --shard part's tag), each at the start of a line.
    constexpr std::string_view kDetail = "# groom detail ";
    const std::string_view text = file.data;
    // Lines counted on from the last comment, not from the file's start (200,000 comments took
    // 224 s: a trial); and a bound, since each name is looked up among those before it.
    size_t counted_to = 0, lines_before = 0, comments = 0;
    for (size_t at = text.find(kDetail); at != std::string_view::npos; at = text.find(kDetail, at + 1)) {
        if (at > 0 && text[at - 1] != '\n') continue;
        lines_before += size_t(std::count(text.begin() + std::ptrdiff_t(counted_to), text.begin() + std::ptrdiff_t(at), '\n'));
        counted_to = at;
        if (++comments > kMaxDetailComments) {
            fail_at_line(file.name, lines_before + 1, "more than " + std::to_string(kMaxDetailComments) +
                                                          " '# groom detail' comments (groom writes a few: a shard's tag, the units)");
        }
        const size_t end = std::min(text.find('\n', at), text.size());
        std::string_view line = text.substr(at + kDetail.size(), end - at - kDetail.size());
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const size_t space = line.find(' ');
        const std::string name(line.substr(0, space));
        const std::string_view value = space == std::string_view::npos ? std::string_view() : line.substr(space + 1);
        const size_t number = lines_before + 1;
        set_detail_from_text(cs, name, value, file.name + ":" + std::to_string(number) + ": malformed '" + std::string(kDetail) + std::string(line) + "'");
    }
    set_closed(cs, loops);  // the records say which curves are loops, not a comment (a trial's `closed 1` closed an open one)
    return cs;
}

namespace {

/// The text of write_obj_curves; with `to`, all but the returned tail is written there as it is
/// made (io_util.h's TextSpill).
std::string obj_curves_text(const CurveSet& given, bool closed, std::ostream* to)
{
    // Closed loops: each point once, the record back to its first vertex (as USD periodic).
    closed = closed || is_closed(given);
    const CurveSet opened = closed ? without_closing_points(given) : CurveSet();
    const CurveSet& curves = closed ? opened : given;
    std::string out;
    out.reserve(to ? (size_t(5) << 20) : curves.num_points() * 36 + curves.num_curves() * 8 + 128);
    const TextSpill spill{out, to};
    out += "# groom curves: " + std::to_string(curves.num_curves()) + " curves, " + std::to_string(curves.num_points()) +
           " points (OBJ keeps positions, and detail values in these comments)\n";
    // (A name with spaces cannot be one comment word: left out, as format_table's obj_keeps tells the command.)
    for (const Attribute& a : curves.attributes(Domain::Detail).all()) {
        if (plain_detail_name(a.name)) out += "# groom detail " + a.name + " " + detail_value_text(a, "obj") + "\n";
    }
    for (const float3& p : curves.positions()) {
        spill();
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
        spill();
        out += 'l';
        for (int64_t i = r.begin; i < r.end; ++i) {
            out += ' ';
            append_number(out, i + 1);
        }
        if (closed && r.size() > 1) {
            out += ' ';
            append_number(out, r.begin + 1);
        }
        out += '\n';
    }
    return out;
}

}  // namespace

std::string write_obj_curves(const CurveSet& curves, bool closed) { return obj_curves_text(curves, closed, nullptr); }

void stream_obj_curves(const CurveSet& curves, bool closed, std::ostream& to)
{
    const std::string rest = obj_curves_text(curves, closed, &to);
    to.write(rest.data(), static_cast<std::streamsize>(rest.size()));
}

PolygonSoup read_obj_mesh(const FileBytes& file, const std::string& group)
{
    ObjData obj = parse_obj(file);
    if (obj.faces.num_faces() == 0 && obj.line_offsets.size() > 1) {
        throw ParseError(file.name + ": expected a mesh ('f' faces), found only polylines ('l'): these are curves");
    }
    // The faces' object and group names, as the repair report's parts (names[0] is "none given").
    std::vector<std::string> part_names;
    for (const auto& set : obj.names) {
        std::string name;
        for (const std::string& t : set) name += (name.empty() ? "" : ", ") + t;
        part_names.push_back(std::move(name));
    }
    const bool named = obj.names.size() > 1;
    if (group.empty()) {
        obj.faces.points = std::move(obj.points);
        if (named) {
            obj.faces.part_names = std::move(part_names);
            obj.faces.face_part = std::move(obj.face_names);
        }
        return std::move(obj.faces);
    }
    std::vector<char> wanted(obj.names.size(), 0);
    for (size_t k = 0; k < obj.names.size(); ++k) wanted[k] = std::find(obj.names[k].begin(), obj.names[k].end(), group) != obj.names[k].end();
    // Only the vertices the chosen faces use, renumbered: the other parts' vertices would be
    // isolated points in the soup.
    PolygonSoup soup;
    std::vector<int32_t> new_index(obj.points.size(), -1);
    std::vector<int32_t> face;
    // The texture coordinates stay as they are (the chosen faces' corners index into them).
    if (obj.faces.has_uvs()) soup.uvs = obj.faces.uvs;
    for (size_t f = 0; f < obj.faces.num_faces(); ++f) {
        if (!wanted[size_t(obj.face_names[f])]) continue;
        face.clear();
        for (int32_t v : obj.faces.face(f)) {
            if (new_index[size_t(v)] < 0) {
                new_index[size_t(v)] = int32_t(soup.points.size());
                soup.points.push_back(obj.points[size_t(v)]);
            }
            face.push_back(new_index[size_t(v)]);
        }
        if (obj.faces.has_uvs()) {
            const int64_t b = obj.faces.face_offsets[f];
            soup.add_face(face, std::span<const int32_t>(obj.faces.face_uv_indices.data() + b, face.size()));
        }
        else {
            soup.add_face(face);
        }
        if (named) soup.face_part.push_back(obj.face_names[f]);
    }
    if (named) soup.part_names = std::move(part_names);
    if (soup.num_faces() == 0) {
        std::vector<std::string> all;
        for (const auto& set : obj.names)
            for (const std::string& name : set)
                if (std::find(all.begin(), all.end(), name) == all.end()) all.push_back(name);
        std::string list;
        for (size_t k = 0; k < all.size() && k < 20; ++k) list += (list.empty() ? "" : ", ") + ("'" + all[k] + "'");
        if (all.size() > 20) list += " and " + std::to_string(all.size() - 20) + " more";
        throw ParseError(file.name + ": no faces in an object or group named '" + group + "' (" +
                         (all.empty() ? std::string("the file has no 'o' or 'g' records") : "the file has " + list) + ")");
    }
    return soup;
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
