// png_image.cpp — PNG chunks (IHDR, IDAT, IEND) around zlib-compressed, filtered scanlines.
#include "render/png_image.h"

#include <zlib.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace btgpu::render {

namespace {

const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

void put32(std::vector<std::uint8_t>& out, std::uint32_t v)
{
    for (int s = 24; s >= 0; s -= 8) out.push_back(std::uint8_t(v >> s));
}

std::uint32_t get32(const std::uint8_t* p)
{
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

void chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data)
{
    put32(out, std::uint32_t(data.size()));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    put32(out, std::uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
}

int paeth(int a, int b, int c)
{
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// Predictor of filter `f` for byte i of a row (left a, above b, above-left c).
int predict(int f, int a, int b, int c)
{
    switch (f) {
    case 1: return a;
    case 2: return b;
    case 3: return (a + b) / 2;
    case 4: return paeth(a, b, c);
    default: return 0;
    }
}

bool fail(std::string* error, const std::string& why)
{
    if (error) *error = why;
    return false;
}

}  // namespace

bool writePng(const std::string& path, const Image& image, std::string* error)
{
    const size_t stride = size_t(image.width) * 3;
    if (image.width <= 0 || image.height <= 0 || image.rgb.size() != stride * size_t(image.height))
        return fail(error, "image size does not match its pixels");
    std::vector<std::uint8_t> raw;
    raw.reserve((stride + 1) * size_t(image.height));
    std::vector<std::uint8_t> zero(stride, 0), best, trial(stride);
    for (int y = 0; y < image.height; ++y) {
        const std::uint8_t* row = &image.rgb[size_t(y) * stride];
        const std::uint8_t* up = y ? row - stride : zero.data();
        long bestCost = -1;
        int bestFilter = 0;
        for (int f : {0, 1, 2, 4}) {
            long cost = 0;
            for (size_t i = 0; i < stride; ++i) {
                const int a = i >= 3 ? row[i - 3] : 0, c = i >= 3 ? up[i - 3] : 0;
                trial[i] = std::uint8_t(row[i] - predict(f, a, up[i], c));
                cost += std::abs(int(std::int8_t(trial[i])));
            }
            if (bestCost < 0 || cost < bestCost) bestCost = cost, bestFilter = f, best = trial;
        }
        raw.push_back(std::uint8_t(bestFilter));
        raw.insert(raw.end(), best.begin(), best.end());
    }
    uLongf packedSize = compressBound(uLong(raw.size()));
    std::vector<std::uint8_t> packed(packedSize);
    if (compress2(packed.data(), &packedSize, raw.data(), uLong(raw.size()), 9) != Z_OK)
        return fail(error, "zlib could not compress the image");
    packed.resize(packedSize);

    std::vector<std::uint8_t> file(kSignature, kSignature + 8), header;
    put32(header, std::uint32_t(image.width));
    put32(header, std::uint32_t(image.height));
    header.insert(header.end(), {8, 2, 0, 0, 0});  // 8-bit, RGB, deflate, adaptive filters, no interlace
    chunk(file, "IHDR", header);
    chunk(file, "IDAT", packed);
    chunk(file, "IEND", {});
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return fail(error, "cannot create " + path);
    const bool ok = std::fwrite(file.data(), 1, file.size(), f) == file.size();
    if (std::fclose(f) != 0 || !ok) return fail(error, "cannot write " + path);
    return true;
}

bool readPng(const std::string& path, Image& image, std::string* error)
{
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return fail(error, "cannot open " + path);
    std::vector<std::uint8_t> file;
    std::uint8_t buf[65536];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) file.insert(file.end(), buf, buf + n);
    std::fclose(f);
    if (file.size() < 8 || std::memcmp(file.data(), kSignature, 8)) return fail(error, path + " is not a PNG file");
    std::vector<std::uint8_t> packed;
    int w = 0, h = 0;
    for (size_t at = 8; at + 12 <= file.size();) {
        const std::uint32_t len = get32(&file[at]);
        if (at + 12 + len > file.size()) return fail(error, path + ": truncated chunk");
        const std::uint8_t* type = &file[at + 4];
        const std::uint8_t* data = &file[at + 8];
        if (get32(data + len) != std::uint32_t(crc32(0, type, len + 4))) return fail(error, path + ": bad chunk CRC");
        if (!std::memcmp(type, "IHDR", 4)) {
            if (len != 13 || data[8] != 8 || data[9] != 2 || data[12] != 0)
                return fail(error, path + ": only 8-bit RGB, non-interlaced PNGs are read");
            w = int(get32(data)), h = int(get32(data + 4));
        } else if (!std::memcmp(type, "IDAT", 4)) {
            packed.insert(packed.end(), data, data + len);
        } else if (!std::memcmp(type, "IEND", 4)) {
            break;
        }
        at += 12 + len;
    }
    if (w <= 0 || h <= 0) return fail(error, path + ": no image header");
    const size_t stride = size_t(w) * 3;
    std::vector<std::uint8_t> raw((stride + 1) * size_t(h));
    uLongf rawSize = uLongf(raw.size());
    if (uncompress(raw.data(), &rawSize, packed.data(), uLong(packed.size())) != Z_OK || rawSize != raw.size())
        return fail(error, path + ": damaged image data");
    image.width = w, image.height = h;
    image.rgb.assign(stride * size_t(h), 0);
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* in = &raw[size_t(y) * (stride + 1)];
        std::uint8_t* row = &image.rgb[size_t(y) * stride];
        const std::uint8_t* up = y ? row - stride : nullptr;
        if (in[0] > 4) return fail(error, path + ": unknown row filter");
        for (size_t i = 0; i < stride; ++i) {
            const int a = i >= 3 ? row[i - 3] : 0, b = up ? up[i] : 0, c = up && i >= 3 ? up[i - 3] : 0;
            row[i] = std::uint8_t(in[1 + i] + predict(in[0], a, b, c));
        }
    }
    return true;
}

}  // namespace btgpu::render
