#include "flatten/ggx_albedo.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <thread>

#include "kernel/kernel.hpp"

namespace vkrt {
namespace {

using kernel::GGX_TABLE_SIZE;

// Visible-normal samples per knot of E, on a kSide x kSide grid of cell midpoints.
constexpr int kSide = 40;
// The knot mu = 0 is taken at this cosine: the albedo is continuous there, and a view
// in the plane of the surface has no visible normals to draw.
constexpr float kGrazing = 1e-3f;

// E(mu) for the lobe of width alpha with a Fresnel of 1: the mean over the drawn
// directions of the visible-normal sample's weight G2 / G1(wo), 0 below the surface.
double albedo(kernel::Kernel& k, float mu, float alpha) {
    const kernel::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    const double lambda_o = k.ggx_lambda(mu, alpha);
    double sum = 0.0;
    for (int a = 0; a < kSide; ++a) {
        for (int b = 0; b < kSide; ++b) {
            const kernel::vec3 wi = k.ggx_sample(alpha, wo, (float(a) + 0.5f) / kSide, (float(b) + 0.5f) / kSide);
            if (!(wi.z > 0.0f)) continue;
            sum += (1.0 + lambda_o) / (1.0 + lambda_o + k.ggx_lambda(wi.z, alpha));
        }
    }
    return sum / (kSide * kSide);
}

std::vector<std::uint32_t> build() {
    const int n = int(GGX_TABLE_SIZE);
    std::vector<std::uint32_t> words(std::size_t(n) * n);
    // One row of alpha after another, on every core: each thread its own Kernel.
    std::atomic<int> next_row{0};
    auto work = [&] {
        kernel::Kernel k;
        for (int j = next_row++; j < n; j = next_row++) {
            const double r = double(j) / (n - 1);
            const float alpha = std::max(float(r * r), kernel::MIN_GGX_ALPHA);
            for (int i = 0; i < n; ++i) {
                const double s = double(i) / (n - 1);
                const float mu = std::max(float(s * s), kGrazing);
                words[std::size_t(j) * n + i] = std::bit_cast<std::uint32_t>(float(albedo(k, mu, alpha)));
            }
        }
    };
    std::vector<std::thread> threads(std::max(1u, std::min(std::thread::hardware_concurrency(), 16u)) - 1);
    for (std::thread& t : threads) t = std::thread(work);
    work();
    for (std::thread& t : threads) t.join();
    // E_avg = 2 int_0^1 E(mu) mu dmu of E as the kernel interpolates it, linearly in
    // s = sqrt(mu) between knots, integrated exactly: 2 mu dmu = 4 s^3 ds, and on
    // [s_a, s_b] with E = E_a + (E_b - E_a) (s - s_a) / (s_b - s_a),
    //   int 4 s^3 E ds = E_a (s_b^4 - s_a^4) + (E_b - E_a) / (s_b - s_a)
    //                    * (4/5 (s_b^5 - s_a^5) - s_a (s_b^4 - s_a^4)).
    // The multiple-scattering lobe then gives back exactly 1 - E(mu_o) of the
    // interpolated E, with a Fresnel of 1.
    for (int j = 0; j < n; ++j) {
        double avg = 0.0;
        for (int i = 0; i + 1 < n; ++i) {
            const double a = double(i) / (n - 1), b = double(i + 1) / (n - 1);
            const double ea = double(std::bit_cast<float>(words[std::size_t(j) * n + i]));
            const double eb = double(std::bit_cast<float>(words[std::size_t(j) * n + i + 1]));
            const double d4 = std::pow(b, 4) - std::pow(a, 4), d5 = std::pow(b, 5) - std::pow(a, 5);
            avg += ea * d4 + (eb - ea) / (b - a) * (0.8 * d5 - a * d4);
        }
        words.push_back(std::bit_cast<std::uint32_t>(float(avg)));
    }
    return words;
}

}  // namespace

const std::vector<std::uint32_t>& ggx_albedo_table() {
    static const std::vector<std::uint32_t> table = build();
    return table;
}

}  // namespace vkrt
