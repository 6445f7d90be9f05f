#include "flatten/ggx_albedo.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/geometric.hpp>

#include "flatten/table_rows.hpp"
#include "kernel/kernel.hpp"

namespace vkrt {
namespace {

using kernel::GGX_TABLE_SIZE;

// Visible-normal samples per knot of E, on a kSide x kSide grid of cell midpoints.
constexpr int kSide = 40;
// The knot mu = 0 is taken at this cosine: the albedo is continuous there, and a view
// in the plane of the surface has no visible normals to draw.
constexpr float kGrazing = 1e-3f;

// E(mu) and E_s(mu) for the lobe of width alpha (kernel/lobes/ggx_albedo.glsl): the
// means over the drawn directions of the visible-normal sample's weight G2 / G1(wo),
// and of that weight times Schlick's (1 - wo.h)^5; 0 below the surface.
struct Albedos {
    double e = 0.0, e_s = 0.0;
};

Albedos albedos(kernel::Kernel& k, float mu, float alpha) {
    const kernel::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    const double lambda_o = k.ggx_lambda(mu, alpha);
    Albedos sum;
    for (int a = 0; a < kSide; ++a) {
        for (int b = 0; b < kSide; ++b) {
            const kernel::vec3 wi = k.ggx_sample(alpha, wo, (float(a) + 0.5f) / kSide, (float(b) + 0.5f) / kSide);
            if (!(wi.z > 0.0f)) continue;
            const double w = (1.0 + lambda_o) / (1.0 + lambda_o + k.ggx_lambda(wi.z, alpha));
            sum.e += w;
            sum.e_s += w * k.schlick_scalar(glm::dot(wo, k.unit_vector(wo + wi)));
        }
    }
    const double n = double(kSide) * kSide;
    return {sum.e / n, sum.e_s / n};
}

// The mean 2 int_0^1 E(mu) mu dmu of a table row as the kernel interpolates it,
// linearly in s = sqrt(mu) between knots, integrated exactly: 2 mu dmu = 4 s^3 ds,
// and on [s_a, s_b] with E = E_a + (E_b - E_a) (s - s_a) / (s_b - s_a),
//   int 4 s^3 E ds = E_a (s_b^4 - s_a^4) + (E_b - E_a) / (s_b - s_a)
//                    * (4/5 (s_b^5 - s_a^5) - s_a (s_b^4 - s_a^4)).
// The multiple-scattering lobe then gives back exactly 1 - E(mu_o) of the
// interpolated E with a Fresnel of 1, and the diffuse lobe under the rough one
// shares out exactly what that leaves.
}  // namespace

float table_row_mean(const std::uint32_t* row, int n) {
    double avg = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
        const double a = double(i) / (n - 1), b = double(i + 1) / (n - 1);
        const double ea = double(std::bit_cast<float>(row[i])), eb = double(std::bit_cast<float>(row[i + 1]));
        const double d4 = std::pow(b, 4) - std::pow(a, 4), d5 = std::pow(b, 5) - std::pow(a, 5);
        avg += ea * d4 + (eb - ea) / (b - a) * (0.8 * d5 - a * d4);
    }
    return float(avg);
}

namespace {

// Each table: GGX_TABLE_SIZE^2 knots, mu fastest, then GGX_TABLE_SIZE means; E's, then E_s's.
std::vector<std::uint32_t> build() {
    const int n = int(GGX_TABLE_SIZE);
    const std::size_t knots = std::size_t(n) * n, table = knots + n;
    std::vector<std::uint32_t> words(2 * table);
    // One row of alpha after another.
    for_each_row_on_every_core(n, [&](kernel::Kernel& k, int j) {
        const double r = double(j) / (n - 1);
        const float alpha = std::max(float(r * r), kernel::MIN_GGX_ALPHA);
        for (int i = 0; i < n; ++i) {
            const double s = double(i) / (n - 1);
            const Albedos e = albedos(k, std::max(float(s * s), kGrazing), alpha);
            words[std::size_t(j) * n + i] = std::bit_cast<std::uint32_t>(float(e.e));
            words[table + std::size_t(j) * n + i] = std::bit_cast<std::uint32_t>(float(e.e_s));
        }
    });
    for (std::size_t at : {std::size_t(0), table}) {
        for (int j = 0; j < n; ++j) {
            words[at + knots + j] = std::bit_cast<std::uint32_t>(table_row_mean(&words[at + std::size_t(j) * n], n));
        }
    }
    return words;
}

}  // namespace

const std::vector<std::uint32_t>& ggx_albedo_table() {
    static const std::vector<std::uint32_t> table = build();
    return table;
}

}  // namespace vkrt
