#include "flatten/environment_table.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace vkrt {

namespace {

std::uint32_t bits(double v) {
    return std::bit_cast<std::uint32_t>(static_cast<float>(v));
}

double luminance(const glm::vec4& c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// Appends the cumulative sums of weights[first, first + n) over their total, the
// last exactly 1; n equal steps when the total is 0 (a row never drawn).
void append_cdf(const std::vector<double>& weights, std::size_t first, std::size_t n, std::vector<std::uint32_t>& out) {
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) total += weights[first + i];
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        sum += weights[first + i];
        const double c = i + 1 == n ? 1.0 : total > 0.0 ? sum / total : double(i + 1) / double(n);
        out.push_back(bits(std::min(c, 1.0)));
    }
}

}  // namespace

glm::dmat3 environment_frame(const Environment& env) {
    // Environment to world: turned about its own +y by `rotation`, then +y taken to
    // `up` by the shortest rotation (Rodrigues), so that an up of +z makes -y the
    // frame's +z, as a glTF file's axes become Blender's.
    const double a = env.rotation * std::numbers::pi / 180.0;
    const glm::dmat3 turn(glm::dvec3(std::cos(a), 0.0, -std::sin(a)), glm::dvec3(0.0, 1.0, 0.0),
                          glm::dvec3(std::sin(a), 0.0, std::cos(a)));
    const glm::dvec3 u = glm::normalize(env.up);
    glm::dmat3 tilt(1.0);
    if (u.y < -1.0 + 1e-12) {
        tilt = glm::dmat3(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, -1.0, 0.0), glm::dvec3(0.0, 0.0, -1.0));
    } else {
        // R = I + [v]x + [v]x^2 / (1 + c) with v = y x u, c = y . u; glm is column-major.
        const glm::dvec3 v(u.z, 0.0, -u.x);
        const glm::dmat3 k(glm::dvec3(0.0, v.z, -v.y), glm::dvec3(-v.z, 0.0, v.x), glm::dvec3(v.y, -v.x, 0.0));
        tilt = glm::dmat3(1.0) + k + (k * k) * (1.0 / (1.0 + u.y));
    }
    return glm::transpose(tilt * turn);
}

std::vector<double> environment_weights(const Environment& env) {
    const std::uint32_t w = env.image.width, h = env.image.height;
    std::vector<double> lum(std::size_t(w) * h);
    for (std::size_t i = 0; i < lum.size(); ++i) lum[i] = luminance(env.image.texels[i]);
    // Over a texel's square, bilinear interpolation averages each axis's neighbours
    // with weights 1/8, 3/4, 1/8 (the integral of the tent between texel centres).
    constexpr double tap[3] = {0.125, 0.75, 0.125};
    std::vector<double> weights(lum.size());
    for (std::uint32_t y = 0; y < h; ++y) {
        const double sin_theta = std::sin(std::numbers::pi * (y + 0.5) / h);
        for (std::uint32_t x = 0; x < w; ++x) {
            double mean = 0.0;
            for (int dy = -1; dy <= 1; ++dy) {
                const std::uint32_t sy = std::uint32_t(std::clamp<std::int64_t>(std::int64_t(y) + dy, 0, h - 1));
                for (int dx = -1; dx <= 1; ++dx) {
                    const std::uint32_t sx = std::uint32_t((std::int64_t(x) + dx + w) % w);
                    mean += tap[dy + 1] * tap[dx + 1] * lum[std::size_t(sy) * w + sx];
                }
            }
            weights[std::size_t(y) * w + x] = mean * sin_theta;
        }
    }
    return weights;
}

std::uint32_t append_environment(const Environment& env, std::vector<std::uint32_t>& words, bool& sampled) {
    const auto first = static_cast<std::uint32_t>(words.size());
    const std::uint32_t w = env.image.width, h = env.image.height;
    const glm::dmat3 m = environment_frame(env);
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) words.push_back(bits(m[col][row]));
    }
    words.push_back(w);
    words.push_back(h);
    words.push_back(0u);
    for (const glm::vec4& t : env.image.texels) {
        for (int c = 0; c < 3; ++c) words.push_back(bits(env.intensity * double(t[c])));
    }
    const std::vector<double> weights = environment_weights(env);
    std::vector<double> rows(h, 0.0);
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) rows[y] += weights[std::size_t(y) * w + x];
    }
    append_cdf(rows, 0, h, words);
    for (std::uint32_t y = 0; y < h; ++y) append_cdf(weights, std::size_t(y) * w, w, words);
    sampled = env.intensity > 0.0 && std::any_of(rows.begin(), rows.end(), [](double r) { return r > 0.0; });
    return first;
}

}  // namespace vkrt
