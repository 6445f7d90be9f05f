#pragma once
// Where two images differ, as a picture: the signed difference a - b of each pixel
// (the mean of its three channels) in a diverging colour map, blue where a is below
// b, red where it is above, white where they agree. The map runs straight in sRGB
// from blue (59, 76, 192) through near-white (242, 242, 242) to red (180, 4, 38), the
// end points of Moreland's cool-to-warm map ("Diverging Color Maps for Scientific
// Visualization", 2009); a difference of -range or below is the blue end, +range or
// above the red end. A NaN in either image is black.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "image/image.hpp"

namespace vkrt {

// The largest |a - b| of any pixel's channel mean: the range that shows every
// difference without clipping. Throws ImageError when the sizes differ.
double largest_signed_difference(const Image& a, const Image& b);

// The sRGB bytes (r, g, b, 255 per pixel, rows from the top) of the difference
// image. range > 0. Throws ImageError when the sizes differ.
std::vector<std::uint8_t> difference_rgba8(const Image& a, const Image& b, double range);

// Writes it as a PNG; throws ImageError when the file is not .png or cannot be written.
void write_difference_png(const Image& a, const Image& b, double range, const std::filesystem::path& file);

}  // namespace vkrt
