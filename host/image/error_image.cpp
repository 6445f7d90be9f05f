#include "image/error_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "image/png_encode.hpp"

namespace vkrt {
namespace {

void check_sizes(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) {
        throw ImageError(fmt::format("images differ in size: {}x{} and {}x{}", a.width, a.height, b.width, b.height));
    }
}

double signed_difference(const Image& a, const Image& b, std::size_t p) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c) d += double(a.rgb[3 * p + c]) - double(b.rgb[3 * p + c]);
    return d / 3.0;
}

constexpr std::array<double, 3> kCool = {59, 76, 192};
constexpr std::array<double, 3> kMiddle = {242, 242, 242};
constexpr std::array<double, 3> kWarm = {180, 4, 38};

}  // namespace

double largest_signed_difference(const Image& a, const Image& b) {
    check_sizes(a, b);
    double largest = 0.0;
    for (std::size_t p = 0; p < std::size_t(a.width) * a.height; ++p) {
        const double d = std::abs(signed_difference(a, b, p));
        if (std::isfinite(d)) largest = std::max(largest, d);
    }
    return largest;
}

std::vector<std::uint8_t> difference_rgba8(const Image& a, const Image& b, double range) {
    check_sizes(a, b);
    const std::size_t n = std::size_t(a.width) * a.height;
    std::vector<std::uint8_t> out(4 * n, 255);
    for (std::size_t p = 0; p < n; ++p) {
        const double d = signed_difference(a, b, p);
        for (int c = 0; c < 3; ++c) {
            double v = 0.0;
            if (!std::isnan(d)) {
                const double t = std::clamp(d / range, -1.0, 1.0);
                const std::array<double, 3>& end = t < 0.0 ? kCool : kWarm;
                v = kMiddle[c] + std::abs(t) * (end[c] - kMiddle[c]);
            }
            out[4 * p + c] = std::uint8_t(std::lround(v));
        }
    }
    return out;
}

void write_difference_png(const Image& a, const Image& b, double range, const std::filesystem::path& file) {
    if (file.extension() != ".png") {
        throw ImageError(fmt::format("{}: the difference image is written as PNG; name a .png file", file.string()));
    }
    const std::vector<std::uint8_t> rgba = difference_rgba8(a, b, range);
    const std::vector<std::uint8_t> png = encode_png_rgba8(a.width, a.height, rgba);
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    if (!out) throw ImageError(fmt::format("{}: cannot write the difference image", file.string()));
}

}  // namespace vkrt
