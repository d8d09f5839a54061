#include "kernel/io/png.h"

#include "kernel/error.h"
#include "kernel/io/atomic_file.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

namespace groom {

namespace {

// libpng callbacks must not throw (they are called from C); they only append to / read from plain
// buffers and record messages, and the caller turns the outcome into an exception afterwards.
struct WriteState {
    std::vector<uint8_t>* out;
    char message[256];
};

void on_write(png_structp png, png_bytep data, png_size_t n)
{
    auto* s = static_cast<WriteState*>(png_get_io_ptr(png));
    s->out->insert(s->out->end(), data, data + n);
}
void on_flush(png_structp) {}

void on_error(png_structp png, png_const_charp msg)
{
    auto* text = static_cast<char*>(png_get_error_ptr(png));
    std::snprintf(text, 256, "%s", msg);
    png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}

/// Returns false (message in `error`) when libpng fails. No C++ object with a destructor lives in
/// this frame across setjmp, so longjmp cannot skip one.
bool encode_raw(const RgbImage& image, std::vector<uint8_t>& out, char* error)
{
    WriteState state{&out, {}};
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_error, on_warning);
    if (!png) {
        std::snprintf(error, 256, "png_create_write_struct failed");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, info ? &info : nullptr);
        return false;
    }
    png_set_write_fn(png, &state, on_write, on_flush);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 6);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) png_write_row(png, const_cast<png_bytep>(image.at(0, y)));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

struct ReadState {
    const std::vector<uint8_t>* in;
    size_t pos;
};

void on_read(png_structp png, png_bytep data, png_size_t n)
{
    auto* s = static_cast<ReadState*>(png_get_io_ptr(png));
    if (s->pos + n > s->in->size()) png_error(png, "file is truncated");
    std::memcpy(data, s->in->data() + s->pos, n);
    s->pos += n;
}

/// Decodes into `out` (already default-constructed by the caller); false + message on failure.
bool decode_raw(const std::vector<uint8_t>& bytes, RgbImage& out, char* error)
{
    ReadState state{&bytes, 0};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, on_error, on_warning);
    if (!png) {
        std::snprintf(error, 256, "png_create_read_struct failed");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
        return false;
    }
    png_set_read_fn(png, &state, on_read);
    png_read_info(png, info);
    const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    if (w == 0 || h == 0 || w > 65536 || h > 65536) png_error(png, "image size out of range");
    const int color = png_get_color_type(png, info);
    // Normalise every colour type and depth to 8-bit RGB.
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    png_set_packing(png);
    if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA) {
        png_set_expand_gray_1_2_4_to_8(png);
        png_set_gray_to_rgb(png);
    }
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != static_cast<size_t>(w) * 3u) png_error(png, "unsupported pixel layout");
    out.width = static_cast<int>(w);
    out.height = static_cast<int>(h);
    out.rgb.resize(static_cast<size_t>(w) * h * 3u);
    for (png_uint_32 y = 0; y < h; ++y) png_read_row(png, out.rgb.data() + static_cast<size_t>(y) * w * 3u, nullptr);
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

}  // namespace

std::vector<uint8_t> encode_png(const RgbImage& image)
{
    if (image.width <= 0 || image.height <= 0) {
        throw InvalidParam("png: image size must be at least 1x1 (got " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + ")");
    }
    const size_t expected = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3u;
    if (image.rgb.size() != expected) {
        throw InvalidParam("png: pixel buffer holds " + std::to_string(image.rgb.size()) + " bytes, expected " + std::to_string(expected));
    }
    std::vector<uint8_t> out;
    out.reserve(expected / 4 + 1024);
    char error[256] = {};
    if (!encode_raw(image, out, error)) throw IoError(std::string("png: encoding failed: ") + error);
    return out;
}

void write_png(const RgbImage& image, const std::string& path)
{
    const std::vector<uint8_t> bytes = encode_png(image);
    AtomicOutput out(path, true);
    out.stream().write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.commit();
}

RgbImage read_png(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path + ": cannot open for reading (" + std::strerror(errno) + ")");
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), signature, 8) != 0) {
        throw ParseError(path + ":0: not a PNG file (expected the 8-byte PNG signature)");
    }
    RgbImage image;
    char error[256] = {};
    if (!decode_raw(bytes, image, error)) throw ParseError(path + ": corrupt PNG (" + error + ")");
    return image;
}

}  // namespace groom
