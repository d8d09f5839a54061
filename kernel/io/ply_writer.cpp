// PlyWriter (ply_writer.h): the header text and the rows, each value as the shortest text that reads back
// exactly (ASCII) or as raw little-endian bytes (binary).
#include "kernel/io/ply_writer.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>

namespace groom::io::ply {

void PlyWriter::begin(std::initializer_list<std::string> comments)
{
    header = "ply\nformat ";
    header += ascii_ ? "ascii 1.0\n" : "binary_little_endian 1.0\n";
    for (const std::string& c : comments) header += "comment " + c + "\n";
}

void PlyWriter::element(const std::string& name, size_t count, const std::vector<Column>& cols)
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

void PlyWriter::list_element(const std::string& name, const std::string& prop, const PolygonSoup& soup)
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

const char* PlyWriter::type_text(PlyType t)
{
    switch (t) {
        case PlyType::UInt8: return "uchar";
        case PlyType::Int32: return "int";
        case PlyType::Float32: return "float";
        case PlyType::Float64: return "double";
        default: return "int";
    }
}

void PlyWriter::put(PlyType t, double v)
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

}  // namespace groom::io::ply
