#pragma once
// How far an image is from a reference, as `vkrt converge` records it per
// checkpoint: the figures of an error-versus-time curve.
#include "image/image.hpp"

namespace vkrt {

struct ErrorMetrics {
    double rmse = 0.0;       // sqrt of the mean over pixels and channels of (x - ref)^2
    double relmse = 0.0;     // mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01)
    double mean = 0.0;       // mean radiance of the image, over pixels and channels
    double mean_diff = 0.0;  // mean - the reference's mean: the bias that survives averaging
};

// The 0.01 keeps relMSE finite on black reference pixels (the usual choice in the
// rendering literature). Throws ImageError when the sizes differ.
ErrorMetrics error_metrics(const Image& image, const Image& reference);

}  // namespace vkrt
