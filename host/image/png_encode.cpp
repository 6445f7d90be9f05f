#include "image/png_encode.hpp"

#include <array>
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

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& image, const Display& display) {
    const std::vector<std::uint8_t> rgb = to_srgb8(image, display);
    const std::size_t row = std::size_t(image.width) * 3;
    // Each scanline starts with its filter type; 0 (none) keeps encoding cheap.
    std::vector<std::uint8_t> scanlines;
    scanlines.reserve((row + 1) * image.height);
    for (std::uint32_t y = 0; y < image.height; ++y) {
        scanlines.push_back(0);
        scanlines.insert(scanlines.end(), rgb.begin() + std::ptrdiff_t(y * row),
                         rgb.begin() + std::ptrdiff_t((y + 1) * row));
    }
    uLongf packed_size = compressBound(uLong(scanlines.size()));
    std::vector<std::uint8_t> packed(packed_size);
    if (compress2(packed.data(), &packed_size, scanlines.data(), uLong(scanlines.size()), Z_BEST_SPEED) != Z_OK) {
        throw ImageError("encoding a PNG: zlib failed");
    }
    packed.resize(packed_size);

    std::vector<std::uint8_t> header;
    put_u32(header, image.width);
    put_u32(header, image.height);
    header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, adaptive filters, no interlace

    constexpr std::array<std::uint8_t, 8> kSignature{137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
    std::vector<std::uint8_t> png(kSignature.begin(), kSignature.end());
    put_chunk(png, "IHDR", header);
    put_chunk(png, "IDAT", packed);
    put_chunk(png, "IEND", {});
    return png;
}

}  // namespace vkrt
