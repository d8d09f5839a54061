// Reading a PLY file into elements and properties (ply_data.h): the header, then every row in ASCII
// or binary of either byte order, with counts checked against the file size before allocating.
// Shared by the curve and mesh readers; what the elements mean is theirs to decide.
#include "kernel/io/ply_data.h"

#include <limits>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>

namespace groom::io::ply {

namespace {

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

/// The values an integer type holds, for ASCII bodies: "3000000000" for an `int` property would
/// otherwise wrap when it is stored as int32.
struct IntRange {
    double lo, hi;
    const char* name;
};
IntRange int_range(PlyType t)
{
    switch (t) {
        case PlyType::Int8: return {-128.0, 127.0, "char"};
        case PlyType::UInt8: return {0.0, 255.0, "uchar"};
        case PlyType::Int16: return {-32768.0, 32767.0, "short"};
        case PlyType::UInt16: return {0.0, 65535.0, "ushort"};
        case PlyType::Int32: return {-2147483648.0, 2147483647.0, "int"};
        case PlyType::UInt32: return {0.0, 4294967295.0, "uint"};
        default: return {-1e308, 1e308, "float"};
    }
}

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

}  // namespace

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
            for (const PlyProperty& q : ply.elements.back().props) {
                if (q.name == p.name) {
                    fail_at_line(file.name, cur.line(), "element " + ply.elements.back().name + " has a second property '" + p.name +
                                                            "' (which one holds the values?)");
                }
            }
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
                    auto number = [&](PlyType type) {
                        const bool integer = !is_float(type);
                        const std::string_view t = cur.token_any_line();
                        double v = 0;
                        if (!parse_double(t, v) || (integer && v != std::floor(v))) {
                            fail_at_line(file.name, cur.line(), "expected " + std::string(integer ? "an integer" : "a number") + " for " + e.name + " " +
                                                                    std::to_string(r) + " property '" + p.name + "', found " +
                                                                    (t.empty() ? std::string("end of file") : describe_found(t)));
                        }
                        // Past float's range: what rounds to inf as a float (FLT_MAX's own shortest
                        // text, 3.4028235e+38, is a hair above it as a double and rounds to it).
                        if (!integer && type == PlyType::Float32 && std::isfinite(v) && std::isinf(static_cast<float>(v))) {
                            fail_at_line(file.name, cur.line(), "value " + std::string(t) + " for " + e.name + " " + std::to_string(r) + " property '" +
                                                                    p.name + "' is out of range for its type float (it would round to inf)");
                        }
                        if (integer) {
                            const IntRange range = int_range(type);
                            if (v < range.lo || v > range.hi) {
                                fail_at_line(file.name, cur.line(), "value " + std::string(t) + " for " + e.name + " " + std::to_string(r) +
                                                                        " property '" + p.name + "' is out of range for its type " + range.name +
                                                                        " (" + number_text(range.lo) + " to " + number_text(range.hi) + ")");
                            }
                        }
                        return v;
                    };
                    if (!p.is_list) {
                        p.values.push_back(number(p.type));
                        continue;
                    }
                    const double n = number(p.count_type);
                    if (n < 0 || n > static_cast<double>(text.size())) fail_at_line(file.name, cur.line(), "list length " + std::to_string(n) + " is out of range");
                    for (int64_t k = 0; k < static_cast<int64_t>(n); ++k) p.values.push_back(number(p.type));
                    p.list_offsets.push_back(static_cast<int64_t>(p.values.size()));
                }
                // A row is a line: a value more than the properties (a stray token) had shifted every
                // value after it into the next property, read without a word (a trial).
                if (!cur.at_line_end(false)) {
                    const size_t line = cur.line();
                    fail_at_line(file.name, line, "expected the end of " + e.name + " " + std::to_string(r) + "'s line after its " +
                                                      std::to_string(e.props.size()) + (e.props.size() == 1 ? " property" : " properties") +
                                                      ", found " + describe_found(cur.token()));
                }
            }
        }
        if (!cur.token_any_line().empty()) {
            fail_at_line(file.name, cur.line(), "expected the end of the file after the header's elements' rows, found more values");
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

std::string number_text(double v)
{
    if (v == std::floor(v) && std::abs(v) < 9.0e18) return std::to_string(static_cast<int64_t>(v));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

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

}  // namespace groom::io::ply
