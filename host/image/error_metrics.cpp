#include "image/error_metrics.hpp"

#include <cmath>

#include <fmt/format.h>

namespace vkrt {

Image read_reference(const std::string& file, std::uint32_t width, std::uint32_t height) {
    if (!is_float_format(file)) {
        throw ImageError(fmt::format(
            "--reference {}: the reference must hold linear radiance, an .exr or .hdr file (8-bit images are "
            "sRGB-encoded and clamped)",
            file));
    }
    Image image = read_image(file);
    if (image.width != width || image.height != height) {
        throw ImageError(fmt::format("--reference {} is {}x{} but the render is {}x{}: give --width and "
                                     "--height to match, or another reference",
                                     file, image.width, image.height, width, height));
    }
    return image;
}

ErrorMetrics error_metrics(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height) {
        throw ImageError(fmt::format("image is {}x{} but the reference is {}x{}", image.width, image.height,
                                     reference.width, reference.height));
    }
    const std::size_t n = image.rgb.size();
    double absolute = 0.0, squared = 0.0, relative = 0.0, sum = 0.0, ref_sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = image.rgb[i], r = reference.rgb[i];
        const double d2 = (x - r) * (x - r);
        absolute += std::abs(x - r);
        squared += d2;
        relative += d2 / (r * r + 0.01);
        sum += x;
        ref_sum += r;
    }
    ErrorMetrics m;
    if (n == 0) return m;
    m.mae = absolute / double(n);
    m.mse = squared / double(n);
    m.rmse = std::sqrt(m.mse);
    m.relmse = relative / double(n);
    m.mean = sum / double(n);
    m.mean_diff = m.mean - ref_sum / double(n);
    return m;
}

}  // namespace vkrt
