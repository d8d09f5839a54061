// Cem Yuksel .hair (placeholder until the full reader lands).
#include "kernel/io/formats.h"
namespace groom::io {
CurveSet read_hair(const FileBytes& file) { throw ParseError(file.name + ": .hair reading is not implemented yet"); }
std::string write_hair(const CurveSet&) { throw InvalidParam(".hair writing is not implemented yet"); }
}  // namespace groom::io
