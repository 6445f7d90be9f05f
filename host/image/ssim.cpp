#include "image/ssim.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>

namespace vkrt {
namespace {

constexpr double kC1 = 0.01 * 0.01;
constexpr double kC2 = 0.03 * 0.03;

// The window's weights along one axis: the Gaussian is separable, and the two
// axes' weights, each summing to 1, multiply to the window's, which sums to 1.
std::array<double, kSsimWindow> gaussian_weights() {
    std::array<double, kSsimWindow> w{};
    const double centre = (kSsimWindow - 1) / 2.0, sigma = 1.5;
    double sum = 0.0;
    for (std::uint32_t i = 0; i < kSsimWindow; ++i) {
        w[i] = std::exp(-(i - centre) * (i - centre) / (2.0 * sigma * sigma));
        sum += w[i];
    }
    for (double& v : w) v /= sum;
    return w;
}

// `values` (width x height) averaged over every window wholly inside: an image of
// (width - 10) x (height - 10), the horizontal pass first.
std::vector<double> window_means(const std::vector<double>& values, std::uint32_t width, std::uint32_t height) {
    static const std::array<double, kSsimWindow> w = gaussian_weights();
    const std::uint32_t out_w = width - kSsimWindow + 1, out_h = height - kSsimWindow + 1;
    std::vector<double> rows(std::size_t(out_w) * height);
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < out_w; ++x) {
            double s = 0.0;
            for (std::uint32_t i = 0; i < kSsimWindow; ++i) s += w[i] * values[std::size_t(y) * width + x + i];
            rows[std::size_t(y) * out_w + x] = s;
        }
    }
    std::vector<double> out(std::size_t(out_w) * out_h);
    for (std::uint32_t y = 0; y < out_h; ++y) {
        for (std::uint32_t x = 0; x < out_w; ++x) {
            double s = 0.0;
            for (std::uint32_t j = 0; j < kSsimWindow; ++j) s += w[j] * rows[std::size_t(y + j) * out_w + x];
            out[std::size_t(y) * out_w + x] = s;
        }
    }
    return out;
}

}  // namespace

double ssim(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) {
        throw ImageError(fmt::format("images differ in size: {}x{} and {}x{}", a.width, a.height, b.width, b.height));
    }
    if (a.width < kSsimWindow || a.height < kSsimWindow) {
        throw ImageError(fmt::format("SSIM needs images of at least {0} x {0} pixels, its window; these are {1}x{2}",
                                     kSsimWindow, a.width, a.height));
    }
    const std::size_t n = std::size_t(a.width) * a.height;
    const auto clamped = [](float v) { return std::isnan(v) ? 0.0 : std::clamp(double(v), 0.0, 1.0); };
    double total = 0.0;
    std::size_t windows = 0;
    for (int c = 0; c < 3; ++c) {
        std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
        for (std::size_t p = 0; p < n; ++p) {
            x[p] = clamped(a.rgb[3 * p + c]);
            y[p] = clamped(b.rgb[3 * p + c]);
            xx[p] = x[p] * x[p];
            yy[p] = y[p] * y[p];
            xy[p] = x[p] * y[p];
        }
        const std::vector<double> mx = window_means(x, a.width, a.height), my = window_means(y, a.width, a.height),
                                  mxx = window_means(xx, a.width, a.height), myy = window_means(yy, a.width, a.height),
                                  mxy = window_means(xy, a.width, a.height);
        for (std::size_t i = 0; i < mx.size(); ++i) {
            const double sx2 = mxx[i] - mx[i] * mx[i], sy2 = myy[i] - my[i] * my[i], sxy = mxy[i] - mx[i] * my[i];
            total += (2.0 * mx[i] * my[i] + kC1) * (2.0 * sxy + kC2) /
                     ((mx[i] * mx[i] + my[i] * my[i] + kC1) * (sx2 + sy2 + kC2));
        }
        windows += mx.size();
    }
    return total / double(windows);
}

}  // namespace vkrt
