#include "kernel/io/curve_io.h"

#include "kernel/io/atomic_file.h"
#include "kernel/io/formats.h"

namespace groom {

namespace {

/// The format of a path: its extension, or for "-" (stdin) a sniff of the first bytes.
std::string format_of(const std::string& path, const std::string& data)
{
    if (path != "-") return io::extension_of(path);
    if (data.rfind("#usda", 0) == 0) return "usda";
    if (data.rfind("ply", 0) == 0) return "ply";
    if (data.rfind("HAIR", 0) == 0) return "hair";
    return "obj";
}

const char* const kCurveFormats = ".usda, .obj, .ply, .hair";

}  // namespace

bool is_curve_path(const std::string& path)
{
    const std::string ext = io::extension_of(path);
    return ext == "usda" || ext == "obj" || ext == "ply" || ext == "hair";
}

CurveSet read_curves(const std::string& path, const CurveReadOptions& options)
{
    if (path != "-" && !is_curve_path(path)) {
        throw IoError(path + ": unknown curve format '." + io::extension_of(path) + "' (expected " + kCurveFormats + ")");
    }
    const io::FileBytes file = io::read_all(path);
    const std::string fmt = format_of(path, file.data);
    if (file.data.empty()) throw ParseError(file.name + ": file is empty (expected " + fmt + " curves)");
    CurveSet cs;
    if (fmt == "usda") cs = io::read_usda(file, options);
    else if (fmt == "obj") cs = io::read_obj_curves(file);
    else if (fmt == "ply") cs = io::read_ply_curves(file);
    else cs = io::read_hair(file);
    cs.validate(file.name);
    return cs;
}

void write_curves(const CurveSet& curves, const std::string& path, const CurveWriteOptions& options)
{
    const std::string fmt = path == "-" ? "usda" : io::extension_of(path);
    if (fmt != "usda" && fmt != "obj" && fmt != "ply" && fmt != "hair") {
        throw InvalidParam(path + ": unknown curve format '." + fmt + "' (expected " + kCurveFormats + ")");
    }
    curves.validate("writing " + path);
    // Encode fully before opening the output, so an encoding error leaves no file behind.
    std::string bytes;
    if (fmt == "usda") bytes = io::write_usda(curves);
    else if (fmt == "obj") bytes = io::write_obj_curves(curves);
    else if (fmt == "ply") bytes = io::write_ply_curves(curves, options.ply_encoding);
    else bytes = io::write_hair(curves);
    AtomicOutput out(path);
    out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.commit();
}

std::vector<std::string> attributes_dropped(const CurveSet& curves, const std::string& path)
{
    const std::string fmt = path == "-" ? "usda" : io::extension_of(path);
    std::vector<std::string> lost;
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
        for (const Attribute& a : curves.attributes(d).all()) {
            if (d == Domain::Point && a.name == attr::P) continue;
            bool kept = fmt == "usda" || fmt == "ply";
            if (fmt == "hair") {
                kept = d == Domain::Point && ((a.type() == AttrType::Float && (a.name == attr::width || a.name == "opacity")) ||
                                              (a.type() == AttrType::Float3 && a.name == "Cd"));
            }
            if (!kept) lost.push_back(std::string(domain_name(d)) + " " + a.name);
        }
    }
    return lost;
}

bool holds_curves(const std::string& path)
{
    const std::string ext = io::extension_of(path);
    if (ext == "usda" || ext == "hair" || path == "-") return true;
    if (ext == "off" || ext == "stl") return false;
    const io::FileBytes file = io::read_all(path);
    const std::string_view d = file.data;
    if (ext == "ply") {
        const size_t end = d.find("end_header");
        const std::string_view header = d.substr(0, end);
        const bool face = header.find("\nelement face ") != std::string_view::npos;
        const bool edge = header.find("\nelement edge ") != std::string_view::npos || header.find("\nelement curve ") != std::string_view::npos;
        return edge && !face;
    }
    bool lines = false, faces = false;
    for (size_t pos = 0; pos < d.size();) {
        const size_t start = d.find_first_not_of(" \t", pos);
        if (start == std::string_view::npos) break;
        if (d.compare(start, 2, "l ") == 0 || d.compare(start, 2, "l\t") == 0) lines = true;
        if (d.compare(start, 2, "f ") == 0 || d.compare(start, 2, "f\t") == 0) faces = true;
        if (faces) break;
        const size_t nl = d.find('\n', start);
        pos = nl == std::string_view::npos ? d.size() : nl + 1;
    }
    return lines && !faces;
}

}  // namespace groom
