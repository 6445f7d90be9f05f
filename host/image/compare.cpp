#include "image/compare.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace vkrt {

ImageDiff compare_images(const Image& a, const Image& b, double threshold) {
    if (a.width != b.width || a.height != b.height) {
        throw ImageError(fmt::format("images differ in size: {}x{} and {}x{}", a.width, a.height, b.width, b.height));
    }
    ImageDiff d;
    d.pixels = std::size_t(a.width) * a.height;
    double sum_sq = 0.0;
    for (std::size_t p = 0; p < d.pixels; ++p) {
        double pixel_max = 0.0;
        for (int c = 0; c < 3; ++c) {
            double diff = std::abs(double(a.rgb[p * 3 + c]) - double(b.rgb[p * 3 + c]));
            if (std::isnan(diff)) diff = std::numeric_limits<double>::infinity();
            sum_sq += diff * diff;
            pixel_max = std::max(pixel_max, diff);
        }
        d.max_abs = std::max(d.max_abs, pixel_max);
        if (pixel_max > threshold) ++d.pixels_over;
    }
    const double mse = d.pixels == 0 ? 0.0 : sum_sq / double(d.pixels * 3);
    d.rmse = std::sqrt(mse);
    d.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
    return d;
}

}  // namespace vkrt
