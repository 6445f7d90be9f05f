#pragma once
#include <cstddef>

#include "image/image.hpp"

namespace vkrt {

struct ImageDiff {
    double rmse = 0.0;          // over all channels
    double max_abs = 0.0;       // largest channel difference
    double psnr = 0.0;          // dB against a peak of 1 (infinite for identical images)
    std::size_t pixels = 0;
    std::size_t pixels_over = 0;  // pixels with any channel differing by more than the threshold
    double fraction_over() const { return pixels == 0 ? 0.0 : double(pixels_over) / double(pixels); }
};

// Throws ImageError when the sizes differ. A NaN in either image counts as an
// infinite difference, so it can never hide.
ImageDiff compare_images(const Image& a, const Image& b, double threshold = 1e-3);

}  // namespace vkrt
