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

// Visible normals per knot, on a side x side grid of cell midpoints; the knot mu = 0
// is taken at this cosine, as for the GGX tables. The layer's tables, differences of
// the two ways' weights across the edge of total internal reflection, take a finer
// grid than E, whose sum smooths that edge: at 24 x 24 they were 2% off at worst.
constexpr int kAlbedoSide = 24;
constexpr int kLayerSide = 32;
constexpr float kGrazing = 1e-3f;

// Means over the drawn microfacets: the albedo E, what the two ways keep, each in
// proportion to its Fresnel share, R G2/G1 of the reflection + (1 - R) G2/G1 of the
// refraction; and off total internal reflection, the differences of the two ways'
// G2/G1, D1, and those times R, DR, with which a specular layer's albedo follows
// (kernel/lobes/rough_glass.glsl rough_glass_layered_albedo).
struct Means {
    double e = 0.0, d1 = 0.0, dr = 0.0;
};

Means albedo(kernel::Kernel& k, int side, float mu, float alpha, float eta) {
    const kernel::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    Means sum;
    for (int a = 0; a < side; ++a) {
        for (int b = 0; b < side; ++b) {
            const auto c = k.rough_crossing(alpha, eta, false, wo, (float(a) + 0.5f) / side, (float(b) + 0.5f) / side);
            const double r = c.reflectance;
            sum.e += r * c.reflect_weight + (1.0 - r) * c.refract_weight;
            if (r < 1.0) {
                sum.d1 += double(c.reflect_weight) - c.refract_weight;
                sum.dr += r * (double(c.reflect_weight) - c.refract_weight);
            }
        }
    }
    const double n = double(side) * side;
    return {sum.e / n, sum.d1 / n, sum.dr / n};
}

// E's knots, or the layer's: D1's, then DR's.
std::vector<std::uint32_t> build(bool layer) {
    const int n = int(GGX_TABLE_SIZE), knots = int(ROUGH_GLASS_ETA_KNOTS);
    const std::size_t per_eta = std::size_t(n) * n, per_table = knots * per_eta;
    std::vector<std::uint32_t> words((layer ? 2 : 1) * per_table);
    // One row of alpha at one eta after another.
    for_each_row_on_every_core(knots * n, [&](kernel::Kernel& k, int row) {
        const int e = row / n, j = row % n;
        const double log_eta = (2.0 * e / (knots - 1) - 1.0) * std::log(double(kernel::ROUGH_GLASS_ETA_MAX));
        const float eta = float(std::exp(log_eta));
        const double r = double(j) / (n - 1);
        const float alpha = std::max(float(r * r), kernel::MIN_GGX_ALPHA);
        for (int i = 0; i < n; ++i) {
            const double s = double(i) / (n - 1);
            const Means m = albedo(k, layer ? kLayerSide : kAlbedoSide, std::max(float(s * s), kGrazing), alpha, eta);
            const std::size_t at = e * per_eta + std::size_t(j) * n + i;
            if (layer) {
                words[at] = std::bit_cast<std::uint32_t>(float(m.d1));
                words[per_table + at] = std::bit_cast<std::uint32_t>(float(m.dr));
            } else {
                words[at] = std::bit_cast<std::uint32_t>(float(m.e));
            }
        }
    });
    return words;
}

}  // namespace

const std::vector<std::uint32_t>& rough_glass_albedo_table() {
    static const std::vector<std::uint32_t> table = build(false);
    return table;
}

const std::vector<std::uint32_t>& rough_glass_layer_tables() {
    static const std::vector<std::uint32_t> tables = build(true);
    return tables;
}

}  // namespace vkrt
