// The individual curve and mesh formats behind read_curves / write_curves / read_mesh /
// write_mesh. Internal to kernel/io: callers use curve_io.h and mesh_io.h, which pick a format from
// the table in format_table.cpp (one row per format). Each reader takes the whole file in memory plus the name to put in messages.
#pragma once

#include "kernel/curve_set.h"
#include "kernel/io/curve_io.h"
#include "kernel/io/io_util.h"
#include "kernel/io/mesh_io.h"

#include <string>
#include <vector>

namespace groom::io {

// --- OBJ: one parser for both curves (`l`) and meshes (`f`) ----------------------------------------
struct ObjData {
    std::vector<float3> points;
    std::vector<int64_t> line_offsets{0};   ///< per `l` record
    std::vector<int32_t> line_indices;      ///< 0-based, resolved (negative indices made absolute)
    PolygonSoup faces;                      ///< `f` records (shares `points` only after finish)
};
/// Parses v/vt/l/f records (face texture coordinates into faces.uvs; vn, o, g, s, usemtl, mtllib and
/// comments are ignored).
ObjData parse_obj(const FileBytes& file);

CurveSet read_obj_curves(const FileBytes& file);
std::string write_obj_curves(const CurveSet& curves);
PolygonSoup read_obj_mesh(const FileBytes& file);
std::string write_obj_mesh(const PolygonSoup& soup);

// --- USD ASCII BasisCurves (usda_lexer, usda_parser, usda_build, usda_write) -----------------------
CurveSet read_usda(const FileBytes& file, const CurveReadOptions& options);
std::string write_usda(const CurveSet& curves);

// --- PLY (ply_parse, ply_curves, ply_mesh, ply_writer) ---------------------------------------------
CurveSet read_ply_curves(const FileBytes& file);
std::string write_ply_curves(const CurveSet& curves, PlyEncoding encoding);
PolygonSoup read_ply_mesh(const FileBytes& file);
std::string write_ply_mesh(const PolygonSoup& soup);

// --- Cem Yuksel's .hair ------------------------------------------------------------------------------
CurveSet read_hair(const FileBytes& file);
std::string write_hair(const CurveSet& curves);

// --- OFF, STL (meshes only) --------------------------------------------------------------------------
PolygonSoup read_off(const FileBytes& file);
PolygonSoup read_stl(const FileBytes& file);

}  // namespace groom::io
