#pragma once
// The Portable Float Map: 32-bit floats, three channels ("PF") or one ("Pf"), rows
// from the bottom up, after a text header "PF\n<width> <height>\n<scale>\n" whose
// scale's sign gives the byte order (negative: little-endian). Written and read here
// without the OpenImageIO plug-in, so that a build without it (scripts/bundle) still
// writes and compares linear images bit for bit.
#include <filesystem>

#include "image/image.hpp"

namespace vkrt {

// Little-endian, scale -1. Throws ImageError when the file cannot be written.
void write_pfm(const Image& image, const std::filesystem::path& file);

// Either byte order; a grey map fills all three channels. Throws ImageError naming
// the file and what is wrong with it.
Image read_pfm(const std::filesystem::path& file);

}  // namespace vkrt
