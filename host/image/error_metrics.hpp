#pragma once
// How far an image is from a reference, as `vkrt converge` records it per
// checkpoint: the figures of an error-versus-time curve.
#include <cstdint>
#include <string>

#include "image/image.hpp"

namespace vkrt {

struct ErrorMetrics {
    double mae = 0.0;        // mean over pixels and channels of |x - ref|
    double mse = 0.0;        // mean over pixels and channels of (x - ref)^2
    double rmse = 0.0;       // sqrt of the mean over pixels and channels of (x - ref)^2
    double relmse = 0.0;     // mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01)
    double mean = 0.0;       // mean radiance of the image, over pixels and channels
    double mean_diff = 0.0;  // mean - the reference's mean: the bias that survives averaging
};

// A reference image to measure renders of width x height against (--reference of
// `vkrt render` and `vkrt converge`): linear radiance, so .exr or .hdr, of that size.
// Throws ImageError saying what is wrong.
Image read_reference(const std::string& file, std::uint32_t width, std::uint32_t height);

// The 0.01 keeps relMSE finite on black reference pixels (the usual choice in the
// rendering literature). Throws ImageError when the sizes differ.
ErrorMetrics error_metrics(const Image& image, const Image& reference);

}  // namespace vkrt
