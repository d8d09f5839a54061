// PLY curves: read_ply_curves / write_ply_curves and the `comment groom ...` lines that carry attribute
// types and detail values. Apart from the mesh reader because curves need their own elements and metadata.
#include "kernel/io/detail_text.h"
#include "kernel/io/edge_chains.h"
#include "kernel/io/formats.h"
#include "kernel/io/ply_data.h"
#include "kernel/io/ply_writer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

// Curves are written the way Blender's and Open3D's PLY readers understand line sets: a `vertex`
// element (x, y, z and one property per point attribute) and an `edge` element (vertex1, vertex2)
// joining consecutive points of each curve. groom adds what those readers ignore but a lossless
// round trip needs: a `curve` element (`point_count` plus one property per curve attribute) and
// `comment groom ...` lines giving each attribute's domain and type and every detail value.
// Files without a `curve` element (from other programs) are rebuilt from the edges as chains.
namespace groom::io {

namespace ply {
namespace {

// --- groom comments: attribute types and detail values ---------------------------------------------

struct GroomComments {
    std::map<std::string, AttrType> point_types, curve_types;
    std::vector<std::pair<std::string, std::string>> details;  ///< name, "TYPE VALUE..."
};

GroomComments groom_comments(const PlyData& ply, const std::string& file)
{
    GroomComments g;
    for (const std::string& c : ply.comments) {
        TextCursor cur(c);
        if (cur.token() != "groom") continue;
        const std::string_view kind = cur.token();
        if (kind == "attribute") {
            const std::string_view dom = cur.token();
            const std::string name(cur.token());
            const auto type = attr_type_named(cur.token());
            if (!type) continue;
            (dom == "curve" ? g.curve_types : g.point_types)[name] = *type;
        }
        else if (kind == "detail") {
            const std::string name(cur.token());
            std::string_view rest = cur.rest_of_line();
            if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
            g.details.emplace_back(name, std::string(rest));
            if (g.details.size() > kMaxDetailComments) {
                throw ParseError(file + ": more than " + std::to_string(kMaxDetailComments) +
                                 " 'comment groom detail' lines (groom writes a few: a shard's tag, the units)");
            }
        }
    }
    return g;
}

void add_detail(const FileBytes& file, CurveSet& cs, const std::string& name, const std::string& spec)
{
    set_detail_from_text(cs, name, spec, file.name + ": malformed 'comment groom detail " + name + " " + spec + "'");
}

/// Turns the scalar properties of `e` (except those in `skip`) into columns on `domain`, gathering
/// row order[i] into element i. `NAME_x NAME_y NAME_z` become one float3 column.
void add_columns(const PlyElement& e, const std::map<std::string, AttrType>& types, Domain domain, std::span<const int64_t> order,
                 std::initializer_list<std::string_view> skip, CurveSet& cs)
{
    const size_t n = order.size();
    for (size_t k = 0; k < e.props.size(); ++k) {
        const PlyProperty& p = e.props[k];
        if (p.is_list || std::find(skip.begin(), skip.end(), p.name) != skip.end()) continue;
        // float3 as three consecutive properties NAME_x, NAME_y, NAME_z.
        if (p.name.size() > 2 && p.name.compare(p.name.size() - 2, 2, "_x") == 0 && k + 2 < e.props.size()) {
            const std::string base = p.name.substr(0, p.name.size() - 2);
            const PlyProperty& py = e.props[k + 1];
            const PlyProperty& pz = e.props[k + 2];
            const auto declared = types.find(base);
            if (!py.is_list && !pz.is_list && py.name == base + "_y" && pz.name == base + "_z" &&
                (declared == types.end() || declared->second == AttrType::Float3)) {
                auto dst = cs.add<float3>(domain, base);
                for (size_t i = 0; i < n; ++i)
                    dst[i] = {static_cast<float>(p.values[order[i]]), static_cast<float>(py.values[order[i]]), static_cast<float>(pz.values[order[i]])};
                k += 2;
                continue;
            }
        }
        AttrType type = is_float(p.type) ? AttrType::Float : p.type == PlyType::UInt32 ? AttrType::Int64 : AttrType::Int32;
        if (const auto it = types.find(p.name); it != types.end() && it->second != AttrType::Float3 && it->second != AttrType::String) type = it->second;
        Attribute& a = cs.attributes(domain).add(p.name, domain, type, n);
        std::visit(
            [&](auto& v) {
                using T = typename std::decay_t<decltype(v)>::value_type;
                if constexpr (std::is_arithmetic_v<T>)
                    for (size_t i = 0; i < n; ++i) v[i] = static_cast<T>(p.values[order[i]]);
            },
            a.data);
    }
}

/// PLY properties for the columns of one domain. int64 is stored as double (exact to 2^53); a
/// column holding more is left out (ply_keeps_column), never rounded.
void columns_for(const CurveSet& cs, Domain d, std::vector<Column>& cols, std::vector<std::string>& comments)
{
    for (const Attribute& a : cs.attributes(d).all()) {
        if (d == Domain::Point && a.name == attr::P) continue;
        if (!ply_keeps_column(d, a)) continue;
        if (a.type() == AttrType::String) throw InvalidParam("ply: " + std::string(domain_name(d)) + " attribute '" + a.name + "' holds strings; PLY cannot store them");
        for (char c : a.name) {
            if (c <= ' ' || c > '~') throw InvalidParam("ply: attribute name '" + a.name + "' contains spaces or non-ASCII characters");
        }
        comments.push_back("groom attribute " + std::string(domain_name(d)) + " " + a.name + " " + type_name(a.type()));
        const Attribute* ap = &a;
        switch (a.type()) {
            case AttrType::Float: cols.push_back({a.name, PlyType::Float32, [ap](size_t i) { return double(ap->values<float>()[i]); }}); break;
            case AttrType::Int32: cols.push_back({a.name, PlyType::Int32, [ap](size_t i) { return double(ap->values<int32_t>()[i]); }}); break;
            case AttrType::Int64:
                cols.push_back({a.name, PlyType::Float64, [ap](size_t i) { return double(ap->values<int64_t>()[i]); }});
                break;
            case AttrType::Float3:
                for (int k = 0; k < 3; ++k)
                    cols.push_back({a.name + "_" + "xyz"[k], PlyType::Float32, [ap, k](size_t i) { return double(ap->values<float3>()[i][k]); }});
                break;
            case AttrType::String: break;
        }
    }
}

}  // namespace
}  // namespace ply

bool ply_keeps_column(Domain, const Attribute& a)
{
    if (a.type() != AttrType::Int64) return true;
    // PLY's integers are 32-bit; a double holds every integer up to 2^53 exactly and no more (ids
    // made by hashing, as partition's, use all 63 bits).
    constexpr int64_t kExact = int64_t(1) << 53;
    for (int64_t v : a.values<int64_t>())
        if (v > kExact || v < -kExact) return false;
    return true;
}

CurveSet read_ply_curves(const FileBytes& file, bool closed_loops)
{
    using namespace ply;
    const PlyData ply = parse_ply(file);
    const PlyElement* v = ply.find("vertex");
    if (!v) throw ParseError(file.name + ": expected a 'vertex' element, found none");
    const std::vector<float3> pts = read_positions(file, *v);
    const GroomComments g = groom_comments(ply, file.name);
    const PlyElement* curve = ply.find("curve");
    const PlyElement* edge = ply.find("edge");

    std::vector<int64_t> order;  // point i of the result is vertex order[i]
    std::vector<int64_t> counts;
    bool edge_loops = false;
    if (curve && curve->find("point_count")) {
        // groom's own files: curves are consecutive runs of vertices.
        const PlyProperty* pc = curve->find("point_count");
        int64_t total = 0;
        for (double n : pc->values) {
            if (!(n >= 0 && n == std::floor(n) && n <= static_cast<double>(v->count))) {
                fail_at_line(file.name, curve->line, "curve point_count " + number_text(n) + " is not a count of 0 to " +
                                                         std::to_string(v->count) + " vertices");
            }
            counts.push_back(static_cast<int64_t>(n));
            total += counts.back();
        }
        if (total != static_cast<int64_t>(v->count)) {
            fail_at_line(file.name, curve->line, "curve point_count values sum to " + std::to_string(total) + " but element vertex has " + std::to_string(v->count));
        }
        order.resize(v->count);
        for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int64_t>(i);
    }
    else {
        if (!edge) throw ParseError(file.name + ": expected an 'edge' element (vertex1, vertex2) joining curve points, found none: not curves");
        const PlyProperty* a = edge->find("vertex1");
        const PlyProperty* b = edge->find("vertex2");
        if (!a || !b) fail_at_line(file.name, edge->line, "expected properties vertex1 and vertex2 on element edge");
        const int64_t n = static_cast<int64_t>(v->count);
        std::vector<int64_t> from(edge->count), to(edge->count);
        for (size_t e = 0; e < edge->count; ++e) {
            const double fa = a->values[e], fb = b->values[e];
            // Written so NaN and fractions (float-typed index properties) fail too, before any cast.
            if (!(fa >= 0 && fa < n && fa == std::floor(fa) && fb >= 0 && fb < n && fb == std::floor(fb))) {
                throw ParseError(file.name + ": edge " + std::to_string(e) + " joins vertex " + number_text(fa) + " and " + number_text(fb) +
                                 ": index out of range (" + std::to_string(n) + " vertices)");
            }
            from[e] = static_cast<int64_t>(fa), to[e] = static_cast<int64_t>(fb);
            if (from[e] == to[e]) throw ParseError(file.name + ": edge " + std::to_string(e) + " joins vertex " + std::to_string(from[e]) + " to itself");
        }
        EdgeChains chains = join_edge_chains(n, from, to, true, file.name, 0, "edges", closed_loops);
        order = std::move(chains.order);
        counts = std::move(chains.counts);
        // Every chain a loop of edges (Blender's closed curve): closed curves.
        bool loops = !counts.empty();
        for (size_t c = 0, at = 0; loops && c < counts.size(); at += size_t(counts[c]), ++c) {
            loops = counts[c] >= 3 && order[at] == order[at + size_t(counts[c]) - 1];
        }
        edge_loops = loops;
    }

    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < order.size(); ++i) P[i] = pts[order[i]];
    // A property named P would be a second positions column: refused by the file's name (the
    // attribute set's own message named neither the file nor the property: a trial).
    // (On the vertex element only: a curve attribute P is no clash, and groom writes one as P_x P_y P_z.)
    for (const PlyProperty& p : v->props) {
        if (p.name == attr::P) {
            fail_at_line(file.name, v->line, "element vertex has a property 'P': P is the positions (x, y, z); rename the property");
        }
    }
    add_columns(*v, g.point_types, Domain::Point, order, {"x", "y", "z"}, cs);
    if (curve && curve->find("point_count") && curve->count == counts.size()) {
        std::vector<int64_t> identity(counts.size());
        for (size_t c = 0; c < identity.size(); ++c) identity[c] = static_cast<int64_t>(c);
        add_columns(*curve, g.curve_types, Domain::Curve, identity, {"point_count"}, cs);
    }
    for (const auto& [name, spec] : g.details) add_detail(file, cs, name, spec);
    if (edge_loops) set_closed(cs, true);
    return cs;
}

std::string write_ply_curves(const CurveSet& curves, PlyEncoding encoding)
{
    using namespace ply;
    std::vector<Column> vcols, ccols;
    std::vector<std::string> comments;
    auto P = curves.positions();
    vcols.push_back({"x", PlyType::Float32, [P](size_t i) { return double(P[i].x); }});
    vcols.push_back({"y", PlyType::Float32, [P](size_t i) { return double(P[i].y); }});
    vcols.push_back({"z", PlyType::Float32, [P](size_t i) { return double(P[i].z); }});
    columns_for(curves, Domain::Point, vcols, comments);
    const auto offsets = curves.offsets();
    ccols.push_back({"point_count", PlyType::Int32, [offsets](size_t c) { return double(offsets[c + 1] - offsets[c]); }});
    columns_for(curves, Domain::Curve, ccols, comments);

    PlyWriter w(encoding);
    w.begin({"groom " GROOM_VERSION " curves: edge joins consecutive points of a curve (root to tip);",
             "groom element curve: point_count and per-curve attributes; float3 X is X_x X_y X_z"});
    for (const std::string& c : comments) w.comment(c);
    for (const Attribute& a : curves.attributes(Domain::Detail).all()) {
        const std::string spec = "groom detail " + a.name + " " + detail_value_text(a, "ply");
        w.comment(spec);
    }
    std::vector<int32_t> ea, eb;
    for (size_t c = 0; c < curves.num_curves(); ++c) {
        const IndexRange r = curves.points_of(c);
        for (int64_t i = r.begin; i + 1 < r.end; ++i) {
            ea.push_back(static_cast<int32_t>(i));
            eb.push_back(static_cast<int32_t>(i + 1));
        }
    }
    if (curves.num_points() > static_cast<size_t>(INT32_MAX)) throw InvalidParam("ply: more than 2^31 points");
    w.element("vertex", curves.num_points(), vcols);
    w.element("edge", ea.size(), {{"vertex1", PlyType::Int32, [&ea](size_t e) { return double(ea[e]); }},
                                   {"vertex2", PlyType::Int32, [&eb](size_t e) { return double(eb[e]); }}});
    w.element("curve", curves.num_curves(), ccols);
    return w.finish();
}

}  // namespace groom::io
