#pragma once
// A PNG in memory, for the live preview (host/live/): the same 8-bit sRGB bytes a
// .png file of the image holds, without a file or an image library.
#include <cstdint>
#include <vector>

#include "image/image.hpp"

namespace vkrt {

// An 8-bit RGB PNG (ISO/IEC 15948) of the image, encoded as to_srgb8 does. Fast
// rather than small: a preview is encoded after every pass.
std::vector<std::uint8_t> encode_png(const Image& image, const Display& display = {});

}  // namespace vkrt
