// RgbImage: an 8-bit RGB picture in memory, what the renderer draws into and kernel/io/png.h encodes.
#pragma once

#include <cstddef>
#include <cstdint>
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

}  // namespace groom
