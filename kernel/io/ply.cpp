// PLY (ASCII, binary little- and big-endian) for curves and meshes.
//
// Curves are written the way Blender's and Open3D's PLY readers understand line sets: a `vertex`
// element (x, y, z and one property per point attribute) and an `edge` element (vertex1, vertex2)
// joining consecutive points of each curve. groom adds what those readers ignore but a lossless
// round trip needs: a `curve` element (`point_count` plus one property per curve attribute) and
// `comment groom ...` lines giving each attribute's domain and type and every detail value.
// Files without a `curve` element (from other programs) are rebuilt from the edges as chains.
#include "kernel/io/formats.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <optional>

namespace groom::io {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLE, BinaryBE };

std::optional<PlyType> ply_type(std::string_view s)
{
    static const std::map<std::string_view, PlyType> types{
        {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},   {"uint8", PlyType::UInt8},
        {"short", PlyType::Int16},   {"int16", PlyType::Int16},     {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},
        {"int", PlyType::Int32},     {"int32", PlyType::Int32},     {"uint", PlyType::UInt32},   {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64}, {"float64", PlyType::Float64}};
    const auto it = types.find(s);
    if (it == types.end()) return std::nullopt;
    return it->second;
}

size_t size_of(PlyType t)
{
    switch (t) {
        case PlyType::Int8:
        case PlyType::UInt8: return 1;
        case PlyType::Int16:
        case PlyType::UInt16: return 2;
        case PlyType::Int32:
        case PlyType::UInt32:
        case PlyType::Float32: return 4;
        case PlyType::Float64: return 8;
    }
    return 0;
}

bool is_float(PlyType t) { return t == PlyType::Float32 || t == PlyType::Float64; }

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;
    bool is_list = false;
    PlyType count_type = PlyType::UInt8;
    std::vector<double> values;         ///< scalars: one per row; lists: every item, rows by offsets
    std::vector<int64_t> list_offsets;  ///< lists only: #rows + 1
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    size_t line = 0;  ///< header line declaring it
    std::vector<PlyProperty> props;
    const PlyProperty* find(std::string_view n) const
    {
        for (const PlyProperty& p : props)
            if (p.name == n) return &p;
        return nullptr;
    }
};

struct PlyData {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<std::string> comments;
    std::vector<PlyElement> elements;
    const PlyElement* find(std::string_view n) const
    {
        for (const PlyElement& e : elements)
            if (e.name == n) return &e;
        return nullptr;
    }
};

template <class T> T load(const char* p, bool swap)
{
    T v;
    std::memcpy(&v, p, sizeof v);
    if (swap) {
        char b[sizeof v];
        std::memcpy(b, &v, sizeof v);
        std::reverse(b, b + sizeof v);
        std::memcpy(&v, b, sizeof v);
    }
    return v;
}

double load_scalar(const char* p, PlyType t, bool swap)
{
    switch (t) {
        case PlyType::Int8: return static_cast<int8_t>(*p);
        case PlyType::UInt8: return static_cast<uint8_t>(*p);
        case PlyType::Int16: return load<int16_t>(p, swap);
        case PlyType::UInt16: return load<uint16_t>(p, swap);
        case PlyType::Int32: return load<int32_t>(p, swap);
        case PlyType::UInt32: return load<uint32_t>(p, swap);
        case PlyType::Float32: return load<float>(p, swap);
        case PlyType::Float64: return load<double>(p, swap);
    }
    return 0;
}

PlyData parse_ply(const FileBytes& file)
{
    const std::string_view text = file.data;
    PlyData ply;
    TextCursor cur(text);
    if (cur.token() != "ply") fail_at_line(file.name, 1, "expected 'ply' magic on the first line, found " + describe_found(text.substr(0, text.find('\n'))));
    bool have_format = false, ended = false;
    while (cur.next_line()) {
        const std::string_view key = cur.token();
        if (key == "end_header") {
            ended = true;
            break;
        }
        if (key.empty()) continue;
        if (key == "format") {
            const std::string_view f = cur.token();
            if (f == "ascii") ply.format = PlyFormat::Ascii;
            else if (f == "binary_little_endian") ply.format = PlyFormat::BinaryLE;
            else if (f == "binary_big_endian") ply.format = PlyFormat::BinaryBE;
            else fail_at_line(file.name, cur.line(), "expected format ascii, binary_little_endian or binary_big_endian, found " + describe_found(f));
            have_format = true;
        }
        else if (key == "comment" || key == "obj_info") {
            std::string_view rest = cur.rest_of_line();
            if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
            if (key == "comment") ply.comments.emplace_back(rest);
        }
        else if (key == "element") {
            PlyElement e;
            e.name = std::string(cur.token());
            const std::string_view n = cur.token();
            int64_t count = 0;
            if (e.name.empty() || !parse_int(n, count) || count < 0) {
                fail_at_line(file.name, cur.line(), "expected 'element NAME COUNT', found count " + describe_found(n));
            }
            e.count = static_cast<uint64_t>(count);
            e.line = cur.line();
            ply.elements.push_back(std::move(e));
        }
        else if (key == "property") {
            if (ply.elements.empty()) fail_at_line(file.name, cur.line(), "expected 'element' before 'property'");
            PlyProperty p;
            std::string_view t = cur.token();
            if (t == "list") {
                p.is_list = true;
                const std::string_view ct = cur.token();
                const auto c = ply_type(ct);
                if (!c || is_float(*c)) fail_at_line(file.name, cur.line(), "expected an integer list count type, found " + describe_found(ct));
                p.count_type = *c;
                t = cur.token();
            }
            const auto pt = ply_type(t);
            if (!pt) fail_at_line(file.name, cur.line(), "expected a PLY type (char uchar short ushort int uint float double), found " + describe_found(t));
            p.type = *pt;
            p.name = std::string(cur.token());
            if (p.name.empty()) fail_at_line(file.name, cur.line(), "expected a property name, found end of line");
            ply.elements.back().props.push_back(std::move(p));
        }
        else {
            fail_at_line(file.name, cur.line(), "expected a PLY header keyword (format, comment, element, property, end_header), found " + describe_found(key));
        }
    }
    if (!ended) fail_at_line(file.name, cur.line(), "expected 'end_header', found end of file");
    if (!have_format) throw ParseError(file.name + ": PLY header has no 'format' line");
    cur.next_line();
    size_t pos = cur.offset();
    if (cur.at_end()) pos = text.size();

    if (ply.format == PlyFormat::Ascii) {
        for (PlyElement& e : ply.elements) {
            // At least one byte per value: a count beyond the file size is refused before allocating.
            check_claimed_count(file.name, e.name + " rows", e.count, std::max<size_t>(e.props.size(), 1), text.size() - pos, pos);
            for (PlyProperty& p : e.props) {
                if (p.is_list) p.list_offsets.reserve(e.count + 1), p.list_offsets.push_back(0);
                else p.values.reserve(e.count);
            }
            for (uint64_t r = 0; r < e.count; ++r) {
                for (PlyProperty& p : e.props) {
                    auto number = [&](bool integer) {
                        const std::string_view t = cur.token_any_line();
                        double v = 0;
                        if (!parse_double(t, v) || (integer && v != std::floor(v))) {
                            fail_at_line(file.name, cur.line(), "expected " + std::string(integer ? "an integer" : "a number") + " for " + e.name + " " +
                                                                    std::to_string(r) + " property '" + p.name + "', found " +
                                                                    (t.empty() ? std::string("end of file") : describe_found(t)));
                        }
                        return v;
                    };
                    if (!p.is_list) {
                        p.values.push_back(number(!is_float(p.type)));
                        continue;
                    }
                    const double n = number(true);
                    if (n < 0 || n > static_cast<double>(text.size())) fail_at_line(file.name, cur.line(), "list length " + std::to_string(n) + " is out of range");
                    for (int64_t k = 0; k < static_cast<int64_t>(n); ++k) p.values.push_back(number(!is_float(p.type)));
                    p.list_offsets.push_back(static_cast<int64_t>(p.values.size()));
                }
            }
        }
        return ply;
    }

    const bool swap = (ply.format == PlyFormat::BinaryBE) != (std::endian::native == std::endian::big);
    for (PlyElement& e : ply.elements) {
        size_t row_min = 0;
        for (const PlyProperty& p : e.props) row_min += p.is_list ? size_of(p.count_type) : size_of(p.type);
        check_claimed_count(file.name, e.name + " rows", e.count, std::max<size_t>(row_min, 1), text.size() - pos, pos);
        for (PlyProperty& p : e.props) {
            if (p.is_list) p.list_offsets.reserve(e.count + 1), p.list_offsets.push_back(0);
            else p.values.reserve(e.count);
        }
        for (uint64_t r = 0; r < e.count; ++r) {
            for (PlyProperty& p : e.props) {
                auto need = [&](size_t bytes) {
                    if (bytes > text.size() - pos) {
                        fail_at_byte(file.name, pos, "truncated: expected " + std::to_string(bytes) + " bytes for " + e.name + " " + std::to_string(r) +
                                                         " property '" + p.name + "', found " + std::to_string(text.size() - pos));
                    }
                };
                if (!p.is_list) {
                    need(size_of(p.type));
                    p.values.push_back(load_scalar(text.data() + pos, p.type, swap));
                    pos += size_of(p.type);
                    continue;
                }
                need(size_of(p.count_type));
                const double n = load_scalar(text.data() + pos, p.count_type, swap);
                pos += size_of(p.count_type);
                if (n < 0) fail_at_byte(file.name, pos, "negative list length " + std::to_string(n) + " in " + e.name + " " + std::to_string(r));
                const size_t bytes = static_cast<size_t>(n) * size_of(p.type);
                need(bytes);
                for (size_t k = 0; k < static_cast<size_t>(n); ++k) p.values.push_back(load_scalar(text.data() + pos + k * size_of(p.type), p.type, swap));
                pos += bytes;
                p.list_offsets.push_back(static_cast<int64_t>(p.values.size()));
            }
        }
    }
    return ply;
}

/// An index or count read from the file, as message text: exact for integers an int64 holds, "%g"
/// otherwise. A corrupt file can hold 1e300, inf or NaN there, and casting those to int64 is UB.
std::string number_text(double v)
{
    if (v == std::floor(v) && std::abs(v) < 9.0e18) return std::to_string(static_cast<int64_t>(v));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

/// x, y, z of the vertex element as positions; NaN rejected naming the vertex.
std::vector<float3> read_positions(const FileBytes& file, const PlyElement& v)
{
    const PlyProperty* c[3] = {v.find("x"), v.find("y"), v.find("z")};
    for (int k = 0; k < 3; ++k) {
        if (!c[k] || c[k]->is_list) fail_at_line(file.name, v.line, std::string("expected a scalar property '") + "xyz"[k] + "' on element vertex");
    }
    std::vector<float3> pts(v.count);
    for (size_t i = 0; i < pts.size(); ++i) {
        pts[i] = {static_cast<float>(c[0]->values[i]), static_cast<float>(c[1]->values[i]), static_cast<float>(c[2]->values[i])};
        if (!isfinite(pts[i])) throw ParseError(file.name + ": vertex " + std::to_string(i) + " has a non-finite position (NaN or inf)");
    }
    return pts;
}

// --- groom comments: attribute types and detail values ---------------------------------------------

struct GroomComments {
    std::map<std::string, AttrType> point_types, curve_types;
    std::vector<std::pair<std::string, std::string>> details;  ///< name, "TYPE VALUE..."
};

std::optional<AttrType> attr_type_named(std::string_view s)
{
    for (AttrType t : {AttrType::Float, AttrType::Int32, AttrType::Int64, AttrType::Float3, AttrType::String})
        if (s == type_name(t)) return t;
    return std::nullopt;
}

GroomComments groom_comments(const PlyData& ply)
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
        }
    }
    return g;
}

std::string escape_line(std::string_view s)
{
    std::string out;
    for (char c : s) {
        if (c == '\\') out += "\\\\";
        else if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else out += c;
    }
    return out;
}

std::string unescape_line(std::string_view s)
{
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size()) {
            const char e = s[++i];
            out += e == 'n' ? '\n' : e == 'r' ? '\r' : e;
        }
        else {
            out += s[i];
        }
    }
    return out;
}

void add_detail(const FileBytes& file, CurveSet& cs, const std::string& name, const std::string& spec)
{
    TextCursor cur(spec);
    const auto type = attr_type_named(cur.token());
    auto bad = [&] { throw ParseError(file.name + ": malformed 'comment groom detail " + name + " " + spec + "'"); };
    if (!type) bad();
    switch (*type) {
        case AttrType::String: {
            std::string_view rest = cur.rest_of_line();
            if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
            cs.set_detail_string(name, unescape_line(rest));
            break;
        }
        case AttrType::Float: {
            float v;
            if (!parse_float(cur.token(), v)) bad();
            cs.add<float>(Domain::Detail, name)[0] = v;
            break;
        }
        case AttrType::Int32:
        case AttrType::Int64: {
            int64_t v;
            if (!parse_int(cur.token(), v)) bad();
            if (*type == AttrType::Int32) cs.add<int32_t>(Domain::Detail, name)[0] = static_cast<int32_t>(v);
            else cs.add<int64_t>(Domain::Detail, name)[0] = v;
            break;
        }
        case AttrType::Float3: {
            float3 v;
            for (int k = 0; k < 3; ++k)
                if (!parse_float(cur.token(), v[k])) bad();
            cs.add<float3>(Domain::Detail, name)[0] = v;
            break;
        }
    }
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

// --- Writing -----------------------------------------------------------------------------------------

struct Column {
    std::string name;  ///< PLY property name
    PlyType type;
    std::function<double(size_t)> get;
};

class PlyWriter {
public:
    explicit PlyWriter(PlyEncoding enc) : ascii_(enc == PlyEncoding::Ascii) {}
    std::string header;
    std::string body;

    void begin(std::initializer_list<std::string> comments)
    {
        header = "ply\nformat ";
        header += ascii_ ? "ascii 1.0\n" : "binary_little_endian 1.0\n";
        for (const std::string& c : comments) header += "comment " + c + "\n";
    }
    void comment(const std::string& c) { header += "comment " + c + "\n"; }
    void element(const std::string& name, size_t count, const std::vector<Column>& cols)
    {
        header += "element " + name + " " + std::to_string(count) + "\n";
        for (const Column& c : cols) header += "property " + std::string(type_text(c.type)) + " " + c.name + "\n";
        for (size_t r = 0; r < count; ++r) {
            for (size_t k = 0; k < cols.size(); ++k) {
                if (ascii_ && k > 0) body += ' ';
                put(cols[k].type, cols[k].get(r));
            }
            if (ascii_) body += '\n';
        }
    }
    /// A list element (mesh faces): one row per face.
    void list_element(const std::string& name, const std::string& prop, const PolygonSoup& soup)
    {
        size_t longest = 0;
        for (size_t f = 0; f < soup.num_faces(); ++f) longest = std::max(longest, soup.face(f).size());
        const PlyType ct = longest <= 255 ? PlyType::UInt8 : PlyType::Int32;
        header += "element " + name + " " + std::to_string(soup.num_faces()) + "\nproperty list " + type_text(ct) + " int " + prop + "\n";
        for (size_t f = 0; f < soup.num_faces(); ++f) {
            const auto face = soup.face(f);
            put(ct, static_cast<double>(face.size()));
            for (int32_t i : face) {
                if (ascii_) body += ' ';
                put(PlyType::Int32, i);
            }
            if (ascii_) body += '\n';
        }
    }
    std::string finish() { return header + "end_header\n" + body; }

    static const char* type_text(PlyType t)
    {
        switch (t) {
            case PlyType::UInt8: return "uchar";
            case PlyType::Int32: return "int";
            case PlyType::Float32: return "float";
            case PlyType::Float64: return "double";
            default: return "int";
        }
    }

private:
    void put(PlyType t, double v)
    {
        if (ascii_) {
            if (t == PlyType::Float32) append_number(body, static_cast<float>(v));
            else if (t == PlyType::Float64) {
                char buf[32];
                body.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
            }
            else append_number(body, static_cast<int64_t>(v));
            return;
        }
        auto raw = [&](auto x) {
            char b[sizeof x];
            std::memcpy(b, &x, sizeof x);
            if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + sizeof x);
            body.append(b, sizeof x);
        };
        switch (t) {
            case PlyType::UInt8: raw(static_cast<uint8_t>(v)); break;
            case PlyType::Int32: raw(static_cast<int32_t>(v)); break;
            case PlyType::Float32: raw(static_cast<float>(v)); break;
            case PlyType::Float64: raw(v); break;
            default: raw(static_cast<int32_t>(v)); break;
        }
    }
    bool ascii_;
};

/// PLY properties for the columns of one domain. int64 is stored as double (exact to 2^53).
void columns_for(const CurveSet& cs, Domain d, std::vector<Column>& cols, std::vector<std::string>& comments)
{
    for (const Attribute& a : cs.attributes(d).all()) {
        if (d == Domain::Point && a.name == attr::P) continue;
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
                for (int64_t v : a.values<int64_t>()) {
                    if (v > (int64_t(1) << 53) || v < -(int64_t(1) << 53)) {
                        throw InvalidParam("ply: int64 attribute '" + a.name + "' holds " + std::to_string(v) +
                                           ", beyond 2^53: PLY stores it as double and would round it (use .usda)");
                    }
                }
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

CurveSet read_ply_curves(const FileBytes& file)
{
    const PlyData ply = parse_ply(file);
    const PlyElement* v = ply.find("vertex");
    if (!v) throw ParseError(file.name + ": expected a 'vertex' element, found none");
    const std::vector<float3> pts = read_positions(file, *v);
    const GroomComments g = groom_comments(ply);
    const PlyElement* curve = ply.find("curve");
    const PlyElement* edge = ply.find("edge");

    std::vector<int64_t> order;  // point i of the result is vertex order[i]
    std::vector<int64_t> counts;
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
        // Chains: each vertex has at most one edge on each side. Edges are taken as undirected;
        // a chain whose edges all point one way starts at its source (root to tip).
        const int64_t n = static_cast<int64_t>(v->count);
        std::vector<int64_t> nb0(n, -1), nb1(n, -1);
        std::vector<char> is_target(n, 0);
        for (size_t e = 0; e < edge->count; ++e) {
            const double fa = a->values[e], fb = b->values[e];
            // Written so NaN and fractions (float-typed index properties) fail too, before any cast.
            if (!(fa >= 0 && fa < n && fa == std::floor(fa) && fb >= 0 && fb < n && fb == std::floor(fb))) {
                throw ParseError(file.name + ": edge " + std::to_string(e) + " joins vertex " + number_text(fa) + " and " + number_text(fb) +
                                 ": index out of range (" + std::to_string(n) + " vertices)");
            }
            const int64_t ia = static_cast<int64_t>(fa), ib = static_cast<int64_t>(fb);
            if (ia == ib) throw ParseError(file.name + ": edge " + std::to_string(e) + " joins vertex " + std::to_string(ia) + " to itself");
            is_target[ib] = 1;
            for (int64_t x : {ia, ib}) {
                const int64_t other = x == ia ? ib : ia;
                if (nb0[x] < 0) nb0[x] = other;
                else if (nb1[x] < 0) nb1[x] = other;
                else throw ParseError(file.name + ": vertex " + std::to_string(x) + " has more than two edges: curves must be simple chains");
            }
        }
        std::vector<char> seen(n, 0);
        for (int64_t s = 0; s < n; ++s) {
            if (seen[s] || nb1[s] >= 0) continue;  // start at chain ends (and isolated vertices)
            std::vector<int64_t> chain{s};
            seen[s] = 1;
            for (int64_t prev = -1, at = s;;) {
                const int64_t next = nb0[at] != prev ? nb0[at] : nb1[at];
                if (next < 0 || seen[next]) break;
                chain.push_back(next);
                seen[next] = 1;
                prev = at;
                at = next;
            }
            // Walked from the end that is a target while the other end is not: reverse to root-first.
            if (chain.size() > 1 && is_target[chain.front()] && !is_target[chain.back()]) std::reverse(chain.begin(), chain.end());
            order.insert(order.end(), chain.begin(), chain.end());
            counts.push_back(static_cast<int64_t>(chain.size()));
        }
        for (int64_t s = 0; s < n; ++s)
            if (!seen[s]) throw ParseError(file.name + ": vertex " + std::to_string(s) + " lies on a closed loop of edges; curves must be open chains");
    }

    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < order.size(); ++i) P[i] = pts[order[i]];
    add_columns(*v, g.point_types, Domain::Point, order, {"x", "y", "z"}, cs);
    if (curve && curve->find("point_count") && curve->count == counts.size()) {
        std::vector<int64_t> identity(counts.size());
        for (size_t c = 0; c < identity.size(); ++c) identity[c] = static_cast<int64_t>(c);
        add_columns(*curve, g.curve_types, Domain::Curve, identity, {"point_count"}, cs);
    }
    for (const auto& [name, spec] : g.details) add_detail(file, cs, name, spec);
    return cs;
}

std::string write_ply_curves(const CurveSet& curves, PlyEncoding encoding)
{
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
        std::string spec = "groom detail " + a.name + " " + type_name(a.type()) + " ";
        for (char c : a.name)
            if (c <= ' ' || c > '~') throw InvalidParam("ply: detail attribute name '" + a.name + "' contains spaces or non-ASCII characters");
        std::visit(
            [&](const auto& v) {
                using T = typename std::decay_t<decltype(v)>::value_type;
                if constexpr (std::is_same_v<T, std::string>) spec += escape_line(v[0]);
                else if constexpr (std::is_same_v<T, float3>) {
                    append_number(spec, v[0].x);
                    spec += ' ';
                    append_number(spec, v[0].y);
                    spec += ' ';
                    append_number(spec, v[0].z);
                }
                else append_number(spec, v[0]);
            },
            a.data);
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

PolygonSoup read_ply_mesh(const FileBytes& file)
{
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
