// PNG pictures (8-bit RGB) through libpng: encoding to memory, atomic writing to a file, and reading
// back (tests and tools check rendered pixels with it). libpng reports errors with longjmp, so every
// call into it happens in functions that own no C++ objects across the setjmp; errors surface as
// IoError / ParseError naming the file.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace groom {

/// An 8-bit RGB picture, rows top to bottom, 3 bytes per pixel (R, G, B).
struct RgbImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;  ///< #height by #width by 3

    RgbImage() = default;
    RgbImage(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3u, 0) {}
    uint8_t* at(int x, int y) { return rgb.data() + (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3u; }
    const uint8_t* at(int x, int y) const
    {
        return rgb.data() + (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3u;
    }
};

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
