#pragma once
// Reading a pixel's exact sums (shaders/kernel/sums.glsl) on the host: the 96-bit
// fixed-point words back to radiance, the mean the image shows, and the variance of
// that mean.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

#include "kernel/types.hpp"

namespace vkrt {

// One channel's sum, words (lo, mid, hi) in units of 2^-40, as a double. Rounded
// once to 53 bits, the same way for any split that produced the same words.
inline double channel_sum(const glm::uvec4& words) {
    const double integer = (double(words.z) * 4294967296.0 + double(words.y)) * 4294967296.0 + double(words.x);
    return std::ldexp(integer, -40);
}

inline std::uint32_t samples_summed(const kernel::PixelSum& s) { return s.red.w; }
inline std::uint32_t samples_clamped(const kernel::PixelSum& s) { return s.green.w; }

inline glm::dvec3 radiance_sum(const kernel::PixelSum& s) {
    return {channel_sum(s.red), channel_sum(s.green), channel_sum(s.blue)};
}

// The mean radiance of the pixel's good samples; black where it has none.
inline glm::vec3 mean_radiance(const kernel::PixelSum& s) {
    const std::uint32_t n = samples_summed(s);
    return n != 0 ? glm::vec3(radiance_sum(s) / double(n)) : glm::vec3(0.0f);
}

inline glm::dvec3 squares_sum(const kernel::PixelSum& s) {
    return {channel_sum(s.red_squares), channel_sum(s.green_squares), channel_sum(s.blue_squares)};
}

// The variance of the pixel's mean radiance, per channel: the samples' unbiased
// variance, (sum of squares - sum^2 / n) / (n - 1), over n. Infinite (unknown) with
// fewer than two samples. Each square was rounded once to a float before it was
// summed (kernel/sums.glsl), which moves the sum of squares by a relative 2^-24 at
// most: a pixel whose samples all agree may show a variance of that order, never a
// negative one.
inline glm::dvec3 variance_of_mean(const kernel::PixelSum& s) {
    const std::uint32_t n = samples_summed(s);
    if (n < 2) return glm::dvec3(std::numeric_limits<double>::infinity());
    const glm::dvec3 sum = radiance_sum(s);
    const glm::dvec3 spread = squares_sum(s) - sum * sum / double(n);
    return glm::max(spread, glm::dvec3(0.0)) / (double(n) * double(n - 1));
}

// A pixel's render passes (kernel/layout.glsl's PassSums) as means: the first hits'
// base colour and shading normal over all of the pixel's `samples` (a sample whose
// eye ray missed adds black and a zero normal), their distance over the `hits`
// alone (infinite where no sample hit). The normal's sums hold n + 1 per hit.
struct PassMeans {
    glm::dvec3 albedo{0.0};
    glm::dvec3 normal{0.0};
    double depth = std::numeric_limits<double>::infinity();
};

inline PassMeans pass_means(const kernel::PassSums& p, std::uint32_t samples, std::uint32_t hits) {
    PassMeans m;
    if (samples == 0 || hits == 0) return m;
    const double n = double(samples);
    m.albedo = glm::dvec3(channel_sum(p.albedo_red), channel_sum(p.albedo_green), channel_sum(p.albedo_blue)) / n;
    m.normal = (glm::dvec3(channel_sum(p.normal_x), channel_sum(p.normal_y), channel_sum(p.normal_z)) - double(hits)) / n;
    m.depth = channel_sum(p.depth) / double(hits);
    return m;
}

}  // namespace vkrt
