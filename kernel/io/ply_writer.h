// The PLY writer shared by the curve and mesh writers: a header of elements and properties, and rows in
// ASCII or binary little-endian. Internal to kernel/io/ply_*.cpp; kept apart from what each writer
// chooses to store (ply_curves.cpp, ply_mesh.cpp).
#pragma once

#include "kernel/io/curve_io.h"
#include "kernel/io/ply_data.h"
#include "kernel/polygon_soup.h"

#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

namespace groom::io::ply {

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

    void begin(std::initializer_list<std::string> comments);
    void comment(const std::string& c) { header += "comment " + c + "\n"; }
    void element(const std::string& name, size_t count, const std::vector<Column>& cols);
    /// A list element (mesh faces): one row per face.
    void list_element(const std::string& name, const std::string& prop, const PolygonSoup& soup);
    std::string finish() { return header + "end_header\n" + body; }

    static const char* type_text(PlyType t);

private:
    void put(PlyType t, double v);
    bool ascii_;
};

}  // namespace groom::io::ply
