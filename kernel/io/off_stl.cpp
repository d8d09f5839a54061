// OFF and STL meshes (placeholder until the full readers land).
#include "kernel/io/formats.h"
namespace groom::io {
PolygonSoup read_off(const FileBytes& file) { throw ParseError(file.name + ": OFF reading is not implemented yet"); }
PolygonSoup read_stl(const FileBytes& file) { throw ParseError(file.name + ": STL reading is not implemented yet"); }
}  // namespace groom::io
