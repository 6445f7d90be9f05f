#include "flatten/rough_glass_albedo.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "flatten/table_rows.hpp"
#include "kernel/kernel.hpp"

namespace vkrt {
namespace {

using kernel::GGX_TABLE_SIZE;
using kernel::ROUGH_GLASS_ETA_KNOTS;

// Visible normals per knot, on a kSide x kSide grid of cell midpoints; the knot mu = 0
// is taken at this cosine, as for the GGX tables.
constexpr int kSide = 24;
constexpr float kGrazing = 1e-3f;

// The mean over the drawn microfacets of what the two ways keep, each in proportion
// to its Fresnel share: R G2/G1 of the reflection + (1 - R) G2/G1 of the refraction.
double albedo(kernel::Kernel& k, float mu, float alpha, float eta) {
    const kernel::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    double sum = 0.0;
    for (int a = 0; a < kSide; ++a) {
        for (int b = 0; b < kSide; ++b) {
            const auto c = k.rough_crossing(alpha, eta, false, wo, (float(a) + 0.5f) / kSide, (float(b) + 0.5f) / kSide);
            sum += double(c.reflectance) * c.reflect_weight + (1.0 - double(c.reflectance)) * c.refract_weight;
        }
    }
    return sum / (double(kSide) * kSide);
}

std::vector<std::uint32_t> build() {
    const int n = int(GGX_TABLE_SIZE), knots = int(ROUGH_GLASS_ETA_KNOTS);
    const std::size_t per_eta = std::size_t(n) * n;
    std::vector<std::uint32_t> words(knots * per_eta);
    // One row of alpha at one eta after another.
    for_each_row_on_every_core(knots * n, [&](kernel::Kernel& k, int row) {
        const int e = row / n, j = row % n;
        const double log_eta = (2.0 * e / (knots - 1) - 1.0) * std::log(double(kernel::ROUGH_GLASS_ETA_MAX));
        const float eta = float(std::exp(log_eta));
        const double r = double(j) / (n - 1);
        const float alpha = std::max(float(r * r), kernel::MIN_GGX_ALPHA);
        for (int i = 0; i < n; ++i) {
            const double s = double(i) / (n - 1);
            words[e * per_eta + std::size_t(j) * n + i] =
                std::bit_cast<std::uint32_t>(float(albedo(k, std::max(float(s * s), kGrazing), alpha, eta)));
        }
    });
    return words;
}

}  // namespace

const std::vector<std::uint32_t>& rough_glass_albedo_table() {
    static const std::vector<std::uint32_t> table = build();
    return table;
}

}  // namespace vkrt
