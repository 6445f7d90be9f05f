#include "flatten/sheen_albedo.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "flatten/ggx_albedo.hpp"
#include "flatten/table_rows.hpp"
#include "kernel/kernel.hpp"

namespace vkrt {
namespace {

using kernel::GGX_TABLE_SIZE;

// Directions per knot, on a kSide x kSide grid of cell midpoints of the hemisphere,
// uniform in solid angle: the lobe's peak lies at grazing directions, which a
// cosine-weighted grid would leave nearly empty. The knot mu = 0 is taken at this cosine.
constexpr int kSide = 96;
constexpr float kGrazing = 1e-3f;

// E_sheen(mu) = int f cos dwi with f = sheen_value: the mean of f cos 2 pi over
// directions of density 1 / (2 pi).
double albedo(kernel::Kernel& k, float mu, float alpha) {
    const kernel::vec3 n(0.0f, 0.0f, 1.0f);
    const kernel::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    double sum = 0.0;
    for (int a = 0; a < kSide; ++a) {
        for (int b = 0; b < kSide; ++b) {
            const kernel::vec3 wi =
                k.sample_hemisphere(kernel::HEMISPHERE_UNIFORM, (float(a) + 0.5f) / kSide, (float(b) + 0.5f) / kSide);
            sum += double(k.sheen_value(alpha, n, wo, wi)) * wi.z;
        }
    }
    return sum * 2.0 * kernel::PI / (double(kSide) * kSide);
}

std::vector<std::uint32_t> build() {
    const int n = int(GGX_TABLE_SIZE);
    const std::size_t knots = std::size_t(n) * n;
    std::vector<std::uint32_t> words(knots + n);
    for_each_row_on_every_core(n, [&](kernel::Kernel& k, int j) {
        const double r = double(j) / (n - 1);
        const float alpha = std::max(float(r * r), kernel::MIN_SHEEN_ALPHA);
        for (int i = 0; i < n; ++i) {
            const double s = double(i) / (n - 1);
            words[std::size_t(j) * n + i] = std::bit_cast<std::uint32_t>(float(albedo(k, std::max(float(s * s), kGrazing), alpha)));
        }
    });
    for (int j = 0; j < n; ++j) words[knots + j] = std::bit_cast<std::uint32_t>(table_row_mean(&words[std::size_t(j) * n], n));
    return words;
}

}  // namespace

const std::vector<std::uint32_t>& sheen_albedo_table() {
    static const std::vector<std::uint32_t> table = build();
    return table;
}

}  // namespace vkrt
