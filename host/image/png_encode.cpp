#include "image/png_encode.hpp"

#include <array>
#include <span>
#include <string_view>

#include <zlib.h>

namespace vkrt {
namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

// A chunk: length, type, data, and the CRC-32 of type and data (PNG section 5.3).
void put_chunk(std::vector<std::uint8_t>& out, std::string_view type, const std::vector<std::uint8_t>& data) {
    put_u32(out, std::uint32_t(data.size()));
    const std::size_t type_at = out.size();
    out.insert(out.end(), type.begin(), type.end());
    out.insert(out.end(), data.begin(), data.end());
    const uLong crc = crc32(0L, out.data() + type_at, uInt(out.size() - type_at));
    put_u32(out, std::uint32_t(crc));
}

// The PNG of 8-bit scanlines of `channels` bytes a pixel: 3 (RGB) or 4 (RGBA).
std::vector<std::uint8_t> encode_scanlines(std::uint32_t width, std::uint32_t height, int channels,
                                           std::span<const std::uint8_t> pixels) {
    const std::size_t row = std::size_t(width) * channels;
    if (pixels.size() != row * height) throw ImageError("encoding a PNG: the pixels do not fill the image");
    // Each scanline starts with its filter type; 0 (none) keeps encoding cheap.
    std::vector<std::uint8_t> scanlines;
    scanlines.reserve((row + 1) * height);
    for (std::uint32_t y = 0; y < height; ++y) {
        scanlines.push_back(0);
        scanlines.insert(scanlines.end(), pixels.begin() + std::ptrdiff_t(y * row),
                         pixels.begin() + std::ptrdiff_t((y + 1) * row));
    }
    uLongf packed_size = compressBound(uLong(scanlines.size()));
    std::vector<std::uint8_t> packed(packed_size);
    if (compress2(packed.data(), &packed_size, scanlines.data(), uLong(scanlines.size()), Z_BEST_SPEED) != Z_OK) {
        throw ImageError("encoding a PNG: zlib failed");
    }
    packed.resize(packed_size);

    std::vector<std::uint8_t> header;
    put_u32(header, width);
    put_u32(header, height);
    // 8 bits, colour type 2 (RGB) or 6 (RGBA), deflate, adaptive filters, no interlace
    header.insert(header.end(), {8, std::uint8_t(channels == 4 ? 6 : 2), 0, 0, 0});

    constexpr std::array<std::uint8_t, 8> kSignature{137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
    std::vector<std::uint8_t> png(kSignature.begin(), kSignature.end());
    put_chunk(png, "IHDR", header);
    put_chunk(png, "IDAT", packed);
    put_chunk(png, "IEND", {});
    return png;
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& image, const Display& display) {
    return encode_scanlines(image.width, image.height, 3, to_srgb8(image, display));
}

std::vector<std::uint8_t> encode_png_rgba8(std::uint32_t width, std::uint32_t height, std::span<const std::uint8_t> rgba) {
    return encode_scanlines(width, height, 4, rgba);
}

}  // namespace vkrt
