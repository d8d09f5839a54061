// PLY (placeholder until the full reader lands).
#include "kernel/io/formats.h"
namespace groom::io {
CurveSet read_ply_curves(const FileBytes& file) { throw ParseError(file.name + ": PLY reading is not implemented yet"); }
std::string write_ply_curves(const CurveSet&, PlyEncoding) { throw InvalidParam("PLY writing is not implemented yet"); }
PolygonSoup read_ply_mesh(const FileBytes& file) { throw ParseError(file.name + ": PLY reading is not implemented yet"); }
std::string write_ply_mesh(const PolygonSoup&) { throw InvalidParam("PLY writing is not implemented yet"); }
}  // namespace groom::io
