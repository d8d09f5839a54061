// PNG pictures (8-bit RGB) through libpng: encoding to memory, atomic writing to a file, and reading
// back (tests and tools check rendered pixels with it). libpng reports errors with longjmp, so every
// call into it happens in functions that own no C++ objects across the setjmp; errors surface as
// IoError / ParseError naming the file.
#pragma once

#include "kernel/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace groom {

/// The PNG file bytes of `image` (deflate level 6, no interlacing). Throws InvalidParam for an empty
/// image or one whose buffer does not hold width*height*3 bytes, IoError if libpng fails.
std::vector<uint8_t> encode_png(const RgbImage& image);

/// Writes `image` as a PNG to `path` atomically (kernel/io/atomic_file.h): on any error the target is
/// left untouched. Throws IoError / InvalidParam.
void write_png(const RgbImage& image, const std::string& path);

/// Reads a PNG of any colour type and bit depth, converted to 8-bit RGB (alpha composited onto black
/// is NOT done: alpha is dropped). Throws IoError (cannot open) or ParseError (not a PNG, corrupt).
RgbImage read_png(const std::string& path);

}  // namespace groom
