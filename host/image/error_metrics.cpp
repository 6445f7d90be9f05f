#include "image/error_metrics.hpp"

#include <cmath>

#include <fmt/format.h>

namespace vkrt {

ErrorMetrics error_metrics(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height) {
        throw ImageError(fmt::format("image is {}x{} but the reference is {}x{}", image.width, image.height,
                                     reference.width, reference.height));
    }
    const std::size_t n = image.rgb.size();
    double squared = 0.0, relative = 0.0, sum = 0.0, ref_sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = image.rgb[i], r = reference.rgb[i];
        const double d2 = (x - r) * (x - r);
        squared += d2;
        relative += d2 / (r * r + 0.01);
        sum += x;
        ref_sum += r;
    }
    ErrorMetrics m;
    if (n == 0) return m;
    m.rmse = std::sqrt(squared / double(n));
    m.relmse = relative / double(n);
    m.mean = sum / double(n);
    m.mean_diff = m.mean - ref_sum / double(n);
    return m;
}

}  // namespace vkrt
