#pragma once
// Independent images of one scene made one image with a variance: the per-pixel
// mean of K images and the variance of that mean, estimated from their spread, for
// renderers that keep no variance of their own (vkrt stack; docs/verification.md).
#include <vector>

#include "image/image.hpp"

namespace vkrt {

// The name of the OpenEXR attribute that carries the variance layer's degrees of
// freedom (z_test.hpp's PixelVariance::dof); absent: infinite.
inline constexpr const char* kVarianceDofAttribute = "vkrt:variance_dof";

struct StackedImage {
    Image mean;      // per pixel channel, the mean of the K images
    Image variance;  // the variance of that mean: the images' unbiased variance over K
    double dof = 0;  // K - 1, the degrees of freedom of each variance
};

// The stack of `images` (two or more, of one size): throws ImageError otherwise.
StackedImage stack_images(const std::vector<Image>& images);

}  // namespace vkrt
