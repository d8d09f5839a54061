// The individual curve and mesh formats behind read_curves / write_curves / read_mesh /
// write_mesh. Internal to kernel/io: callers use curve_io.h and mesh_io.h, which pick a format from
// the table in format_table.cpp (one row per format). Each reader takes the whole file in memory plus the name to put in messages.
#pragma once

#include <iosfwd>

#include "kernel/curve_set.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/io_util.h"
#include "kernel/io/mesh_io.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace groom::io {

// --- OBJ: one parser for both curves (`l`) and meshes (`f`) ----------------------------------------
struct ObjData {
    std::vector<float3> points;
    std::vector<int64_t> line_offsets{0};   ///< per `l` record
    std::vector<int32_t> line_indices;      ///< 0-based, resolved (negative indices made absolute)
    std::vector<size_t> line_lines;         ///< per `l` record: its line in the file
    PolygonSoup faces;                      ///< `f` records (shares `points` only after finish)
    /// Per face: index into `names`, the object (`o`) and group (`g`) names in force at the face.
    std::vector<int32_t> face_names;
    std::vector<std::vector<std::string>> names;  ///< distinct name sets, [0] = none given
};
/// Parses v/vt/l/f/o/g records (face texture coordinates into faces.uvs; vn, s, usemtl, mtllib and
/// comments are ignored).
ObjData parse_obj(const FileBytes& file);

/// Curves: an `l` record with 3 or more points is one curve; two-point records (what Blender's OBJ
/// exporters write, one per edge) are joined into chains where they share vertices (edge_chains.h).
/// `closed_loops`: a closed loop of edges is one closed curve (CurveReadOptions::closed_loops), else an error.
CurveSet read_obj_curves(const FileBytes& file, bool closed_loops = true);
/// `closed`: each `l` record ends with its first vertex again (CurveWriteOptions::closed).
std::string write_obj_curves(const CurveSet& curves, bool closed = false);
/// The same text written to `out` as it is made, a few MiB at a time.
void stream_obj_curves(const CurveSet& curves, bool closed, std::ostream& out);
/// The faces of the whole file, or (group not empty) only those inside an `o` object or `g` group
/// of that name; ParseError naming the names the file has when none matches.
PolygonSoup read_obj_mesh(const FileBytes& file, const std::string& group = {});
std::string write_obj_mesh(const PolygonSoup& soup);

// --- USD ASCII BasisCurves (usda_lexer, usda_parser, usda_build, usda_write) -----------------------
CurveSet read_usda(const FileBytes& file, const CurveReadOptions& options);
/// `closed`: `wrap = "periodic"` (CurveWriteOptions::closed), else "nonperiodic".
std::string write_usda(const CurveSet& curves, bool closed = false);
/// The same text written to `out` as it is made, a few MiB at a time (never held whole).
void stream_usda(const CurveSet& curves, bool closed, std::ostream& out);

// --- PLY (ply_parse, ply_curves, ply_mesh, ply_writer) ---------------------------------------------
CurveSet read_ply_curves(const FileBytes& file, bool closed_loops = true);
std::string write_ply_curves(const CurveSet& curves, PlyEncoding encoding);
/// Whether write_ply_curves keeps a column: every one but an int64 column with a value beyond
/// +-2^53 (stored as double, which would round it; left out instead).
bool ply_keeps_column(Domain d, const Attribute& a);
PolygonSoup read_ply_mesh(const FileBytes& file);
std::string write_ply_mesh(const PolygonSoup& soup);

// --- Cem Yuksel's .hair ------------------------------------------------------------------------------
CurveSet read_hair(const FileBytes& file);
/// The same read from the file a stretch at a time, straight into the curves (never the whole file in memory).
CurveSet read_hair_file(const std::string& path);
std::string write_hair(const CurveSet& curves);
/// The same written to `stream` an array at a time (no copy of the file in memory); checks before writing anything.
void write_hair(const CurveSet& curves, std::ostream& stream);

/// A .hair file written a block of curves at a time, for an output that is never whole in memory
/// (`groom curl` of a million hairs: its input and output held at once were 2x the file). The
/// format puts every strand's segment count first, then each array whole (points, thickness, ...),
/// so the strands' point counts come first and each block's part of every array is written at its
/// place: the stream must be seekable (a file). A single block writes the file front to back.
class HairBlockWriter final : public CurveBlockSink {
public:
    /// `counts`: every strand's point count, checked (1 to 65536 each, < 2^32 in all) before
    /// anything is written. Throws InvalidParam.
    HairBlockWriter(std::ostream& stream, std::span<const int64_t> counts);
    /// The next strands, in order. The first block's point columns (width, opacity, Cd) decide
    /// which arrays the file holds; a later block with other columns, or whose point counts are not
    /// those announced, is refused (InvalidParam).
    void write(const CurveSet& block) override;
    /// Throws InvalidParam unless every announced strand was written; leaves the stream at the end.
    void finish() override;

private:
    void start(uint32_t flags);
    void put_at(uint64_t at, const char* bytes, size_t size);
    template <class T, class Each> void column(uint64_t at, std::span<const T> values, Each each);

    std::ostream& stream_;
    std::vector<uint16_t> segments_;
    uint64_t base_ = 0;  ///< the stream's position when the writer was made: the file's byte 0
    uint64_t points_ = 0, written_ = 0;
    size_t curves_ = 0;
    uint32_t flags_ = 0;
    bool started_ = false;
};

// --- OFF, STL (meshes only) --------------------------------------------------------------------------
PolygonSoup read_off(const FileBytes& file);
PolygonSoup read_stl(const FileBytes& file);

}  // namespace groom::io
