// A PLY file as parsed: format, comments, and every element's properties as doubles (PLY ASCII, binary
// little- and big-endian). Internal to kernel/io/ply_*.cpp: the one interface between reading the file
// (ply_parse.cpp) and turning elements into curves (ply_curves.cpp) or a mesh (ply_mesh.cpp).
#pragma once

#include "kernel/io/io_util.h"

#include <string>
#include <string_view>
#include <vector>

namespace groom::io::ply {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLE, BinaryBE };

inline bool is_float(PlyType t) { return t == PlyType::Float32 || t == PlyType::Float64; }

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

/// The header and every element's rows. Throws ParseError naming the line (header, ASCII body) or
/// byte (binary body), LimitExceeded when an element claims more rows than the file can hold.
PlyData parse_ply(const FileBytes& file);

/// An index or count read from the file, as message text: exact for integers an int64 holds, "%g"
/// otherwise. A corrupt file can hold 1e300, inf or NaN there, and casting those to int64 is UB.
std::string number_text(double v);

/// x, y, z of the vertex element as positions; NaN rejected naming the vertex.
std::vector<float3> read_positions(const FileBytes& file, const PlyElement& v);

}  // namespace groom::io::ply
