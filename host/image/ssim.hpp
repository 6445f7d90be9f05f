#pragma once
// The structural similarity index of two images (Wang, Bovik, Sheikh and Simoncelli,
// "Image Quality Assessment: From Error Visibility to Structural Similarity", IEEE
// Transactions on Image Processing 13(4), 2004): per window, the product of the
// luminance, contrast and structure comparisons,
//
//   SSIM(x, y) = (2 mx my + C1) (2 sxy + C2) / ((mx^2 + my^2 + C1) (sx^2 + sy^2 + C2)),
//
// with the paper's parameters: an 11 x 11 circular-symmetric Gaussian window of
// standard deviation 1.5 (normalized to sum 1), C1 = (0.01 L)^2, C2 = (0.03 L)^2 and
// a dynamic range L = 1. The index of two images is the mean over every window that
// lies wholly inside them (the paper's mean SSIM) and over the three channels, each
// channel clamped to [0, 1] first: the range of a displayed image, which is what
// SSIM was designed to judge (linear radiance above 1 counts as 1).
#include "image/image.hpp"

namespace vkrt {

// Side of the window, in pixels: the smallest image SSIM takes.
inline constexpr std::uint32_t kSsimWindow = 11;

// 1 for identical images, less for less similar ones (it can be negative). Throws
// ImageError when the sizes differ or an image is smaller than the window.
double ssim(const Image& a, const Image& b);

}  // namespace vkrt
