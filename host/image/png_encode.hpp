#pragma once
// A PNG in memory, for the live preview (host/live/): the same 8-bit sRGB bytes a
// .png file of the image holds, without a file or an image library.
#include <cstdint>
#include <span>
#include <vector>

#include "image/image.hpp"

namespace vkrt {

// An 8-bit RGB PNG (ISO/IEC 15948) of the image, encoded as to_srgb8 does. Fast
// rather than small: a preview is encoded after every pass.
std::vector<std::uint8_t> encode_png(const Image& image, const Display& display = {});

// An 8-bit RGBA PNG of bytes r, g, b, a per pixel, rows from the top, written as they
// are: textures with alpha (tests write their cut-outs with it).
std::vector<std::uint8_t> encode_png_rgba8(std::uint32_t width, std::uint32_t height, std::span<const std::uint8_t> rgba);

}  // namespace vkrt
