#include "kernel/io/format_table.h"

#include "kernel/io/atomic_file.h"
#include "kernel/io/detail_text.h"

#include "kernel/io/formats.h"
#include "kernel/io/io_util.h"

#include <array>

namespace groom::io {

namespace {

bool starts_with(std::string_view head, std::string_view magic) { return head.substr(0, magic.size()) == magic; }

// --- signatures ---------------------------------------------------------------------------------
bool sniff_usda(std::string_view head) { return starts_with(head, "#usda"); }
bool sniff_ply(std::string_view head) { return starts_with(head, "ply"); }
bool sniff_hair(std::string_view head) { return starts_with(head, "HAIR"); }
bool sniff_crate(std::string_view head) { return starts_with(head, "PXR-USDC"); }

// --- adapters to one signature per column -------------------------------------------------------
CurveSet read_obj_curves_row(const FileBytes& f, const CurveReadOptions& o) { return read_obj_curves(f, o.closed_loops); }
CurveSet read_ply_curves_row(const FileBytes& f, const CurveReadOptions& o) { return read_ply_curves(f, o.closed_loops); }
CurveSet read_hair_row(const FileBytes& f, const CurveReadOptions&) { return read_hair(f); }
CurveSet read_hair_file_row(const std::string& path, const CurveReadOptions&) { return read_hair_file(path); }
std::string write_usda_row(const CurveSet& c, const CurveWriteOptions& o) { return write_usda(c, o.closed); }
void stream_usda_row(const CurveSet& c, const CurveWriteOptions& o, std::ostream& out) { stream_usda(c, o.closed, out); }
std::string write_obj_curves_row(const CurveSet& c, const CurveWriteOptions& o) { return write_obj_curves(c, o.closed); }
void stream_obj_curves_row(const CurveSet& c, const CurveWriteOptions& o, std::ostream& out) { stream_obj_curves(c, o.closed, out); }
std::string write_ply_curves_row(const CurveSet& c, const CurveWriteOptions& o) { return write_ply_curves(c, o.ply_encoding); }
std::string write_hair_row(const CurveSet& c, const CurveWriteOptions&) { return write_hair(c); }
void stream_hair_row(const CurveSet& c, const CurveWriteOptions&, std::ostream& out) { write_hair(c, out); }
std::unique_ptr<CurveBlockSink> hair_blocks_row(std::ostream& out, std::span<const int64_t> counts)
{
    return std::make_unique<HairBlockWriter>(out, counts);
}

/// `.usd` is either encoding of USD: the text one is read as .usda, the binary crate refused.
CurveSet read_usd_row(const FileBytes& f, const CurveReadOptions& options)
{
    if (sniff_usda(f.data)) return read_usda(f, options);
    const std::string found = sniff_crate(f.data) ? "a binary USD crate file" : "not a '#usda' text file";
    throw ParseError(f.name + ": " + found + "; groom reads USD as text (no OpenUSD package exists on Debian): convert it with `usdcat " +
                     f.name + " -o " + f.name + "a` (OpenUSD's tool) and pass the .usda");
}

// --- content of the formats that hold either ------------------------------------------------------
bool ply_holds_curves(const FileBytes& file)
{
    const std::string_view d = file.data;
    const std::string_view header = d.substr(0, d.find("end_header"));
    const bool face = header.find("\nelement face ") != std::string_view::npos;
    const bool edge = header.find("\nelement edge ") != std::string_view::npos || header.find("\nelement curve ") != std::string_view::npos;
    return edge && !face;
}

bool obj_holds_curves(const FileBytes& file)
{
    const std::string_view d = file.data;
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

// --- which columns survive a write -----------------------------------------------------------------
bool obj_keeps(Domain d, const Attribute& a) { return d == Domain::Detail && plain_detail_name(a.name); }  // positions, and detail values as comments
/// Cem Yuksel's .hair has per-point thickness, transparency and colour arrays, nothing else.
bool hair_keeps(Domain d, const Attribute& a)
{
    return d == Domain::Point && ((a.type() == AttrType::Float && (a.name == attr::width || a.name == "opacity")) ||
                                  (a.type() == AttrType::Float3 && a.name == "Cd"));
}

Format row(std::string_view ext, std::string_view name) { return Format{ext, name}; }

const std::array<Format, 10> kFormats = [] {
    Format usda = row("usda", "USD ASCII BasisCurves");
    usda.sniff = sniff_usda, usda.read_curves = read_usda, usda.write_curves = write_usda_row, usda.stream_curves = stream_usda_row;

    Format obj = row("obj", "Wavefront OBJ (l polylines, f faces)");
    obj.read_curves = read_obj_curves_row, obj.write_curves = write_obj_curves_row, obj.stream_curves = stream_obj_curves_row;
    obj.read_mesh = [](const FileBytes& f) { return read_obj_mesh(f); }, obj.write_mesh = write_obj_mesh;
    obj.content_is_curves = obj_holds_curves, obj.keeps = obj_keeps;

    Format ply = row("ply", "PLY (edge or curve element, or faces)");
    ply.sniff = sniff_ply, ply.read_curves = read_ply_curves_row, ply.write_curves = write_ply_curves_row;
    ply.read_mesh = read_ply_mesh, ply.write_mesh = write_ply_mesh, ply.content_is_curves = ply_holds_curves;
    ply.keeps = ply_keeps_column;

    Format hair = row("hair", "Cem Yuksel's .hair");
    hair.sniff = sniff_hair, hair.read_curves = read_hair_row, hair.read_curves_file = read_hair_file_row, hair.write_curves = write_hair_row, hair.stream_curves = stream_hair_row, hair.open_blocks = hair_blocks_row, hair.keeps = hair_keeps;

    Format off = row("off", "OFF mesh");
    off.read_mesh = read_off;
    Format stl = row("stl", "STL mesh (ASCII or binary)");
    stl.read_mesh = read_stl;

    Format usd = row("usd", "USD, text encoding");
    usd.read_curves = read_usd_row;

    Format usdc = row("usdc", "binary USD crate");
    usdc.refusal = "binary USD is not readable here (no OpenUSD package exists on Debian); convert it to text with "
                   "`usdcat FILE.usdc -o FILE.usda` (OpenUSD's tool) or export .usda from your DCC";
    Format usdz = row("usdz", "USD zip package");
    usdz.refusal = "a USDZ package is a zip of binary USD (no OpenUSD package exists on Debian); unzip it and convert "
                   "the .usdc inside with `usdcat FILE.usdc -o FILE.usda`, or export .usda from your DCC";
    Format abc = row("abc", "Alembic");
    abc.refusal = "Alembic is not readable here (no Alembic package exists on Debian); export the curves as .usda, "
                  ".ply or .obj from your DCC (Houdini, Maya and Blender all write them)";
    usdc.write_refusal = "binary USD is not written here (no OpenUSD package exists on Debian); write .usda (text USD, which "
                         "every USD reader loads) and, if a binary is needed, convert it with `usdcat FILE.usda -o FILE.usdc`";
    usdz.write_refusal = "a USDZ package is not written here (no OpenUSD package exists on Debian); write .usda and package it "
                         "with OpenUSD's `usdzip`";
    abc.write_refusal = "Alembic is not written here (no Alembic package exists on Debian); write .usda (Houdini, Maya and "
                        "Blender builds with USD read it; Debian's Blender has no USD importer: give it .obj), .ply or .obj instead";
    return std::array<Format, 10>{usda, obj, ply, hair, off, stl, usd, usdc, usdz, abc};
}();

}  // namespace

std::span<const Format> formats() { return kFormats; }

const Format* format_by_extension(std::string_view extension)
{
    for (const Format& f : kFormats)
        if (f.extension == extension) return &f;
    return nullptr;
}

const Format* format_of_path(const std::string& path) { return format_by_extension(extension_of(path)); }

std::string format_list(unsigned cap, std::string_view separator)
{
    std::string out;
    for (const Format& f : kFormats) {
        // .usd reads the same files as .usda: listed once, under .usda.
        if (!f.can(cap) || f.extension == "usd") continue;
        if (!out.empty()) out += separator;
        out += '.';
        out += f.extension;
    }
    return out;
}

const Format& format_for(const std::string& path, unsigned cap, std::string_view what, std::string_view head, bool error_is_param)
{
    auto fail = [&](const std::string& message) -> const Format& {
        if (error_is_param) throw InvalidParam(message);
        throw IoError(message);
    };
    if (path == "-") {
        if (cap & (kReadCurves | kReadMesh)) {
            for (const Format& f : kFormats)
                if (f.can(cap) && f.sniff && f.sniff(head)) return f;
            return *format_by_extension("obj");  // OBJ has no signature: whatever else comes on stdin
        }
        return *format_by_extension("usda");
    }
    const std::string ext = extension_of(path);
    const Format* f = format_by_extension(ext);
    const bool writing = cap & (kWriteCurves | kWriteMesh);
    if (!f && writing && written_in_place(path)) {
        // A device or FIFO with no extension (`-o /dev/null`, `/dev/stdout`) is written as stdout
        // is: it had been refused as "unknown format '.'" though every output writes into one.
        for (const Format& g : kFormats)
            if (g.can(cap) && g.refusal.empty() && g.write_refusal.empty()) return g;
    }
    if (f && writing && !f->write_refusal.empty()) return fail(path + ": " + std::string(f->write_refusal));
    if (f && !f->refusal.empty()) return fail(path + ": " + std::string(f->refusal));
    if (!f || !f->can(cap)) {
        return fail(path + ": " + (f ? std::string(f->name) + " files are not " + (writing ? "written" : "read") + " as " + std::string(what) + (std::string_view(what) == "mesh" ? "es" : "s")
                                     : ext.empty() ? "no extension to tell the " + std::string(what) + " format by"
                                                   : "unknown " + std::string(what) + " format '." + ext + "'") +
                    " (expected " + format_list(cap, ", ") + ")");
    }
    return *f;
}

}  // namespace groom::io
