// png_image.h — 8-bit RGB images to and from PNG files with zlib alone (no libpng): the demos'
// frames and the stills. The reader reads what the writer writes (and any 8-bit RGB,
// non-interlaced PNG), which is what the render test needs to look at a frame on disk.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace btgpu::render {

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // rows top to bottom, 3 bytes a pixel
    const std::uint8_t* at(int x, int y) const { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
};

// Writes `image` as a PNG (each row filtered with whichever of None, Sub, Up, Paeth gives the
// smallest sum of magnitudes; zlib level 9). False with `error` set when it cannot.
bool writePng(const std::string& path, const Image& image, std::string* error = nullptr);
// Reads an 8-bit RGB PNG; false with `error` set on anything else or a damaged file.
bool readPng(const std::string& path, Image& image, std::string* error = nullptr);

}  // namespace btgpu::render
