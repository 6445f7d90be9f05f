#include "image/z_test.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace vkrt {

ZTestResult z_test(const Image& a, const Image& var_a, const Image& b, const Image* var_b, double alpha,
                   Image* p_values) {
    ZTestResult r;
    r.alpha = alpha;
    if (p_values) *p_values = Image(a.width, a.height);
    // The p-values first, then the level, which depends on how many were tested.
    std::vector<double> p(a.rgb.size(), 1.0);
    std::vector<double> z(a.rgb.size(), 0.0);
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double variance = double(var_a.rgb[i]) + (var_b ? double(var_b->rgb[i]) : 0.0);
        const double d = double(a.rgb[i]) - double(b.rgb[i]);
        if (!(variance < std::numeric_limits<double>::infinity())) continue;  // unknown (or NaN): untested
        ++r.tests;
        if (variance > 0.0) {
            z[i] = d / std::sqrt(variance);
            p[i] = std::erfc(std::abs(z[i]) / std::sqrt(2.0));
        } else if (d != 0.0) {
            z[i] = d > 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
            p[i] = 0.0;
        }
        if (p[i] < r.min_p || (p[i] == r.min_p && std::abs(z[i]) > std::abs(r.worst_z))) {
            r.min_p = p[i];
            r.worst_z = z[i];
            r.worst_x = std::uint32_t((i / 3) % a.width);
            r.worst_y = std::uint32_t((i / 3) / a.width);
            r.worst_channel = std::uint32_t(i % 3);
        }
    }
    // 1 - (1 - alpha)^(1/m), without the cancellation of the plain formula.
    r.level = r.tests > 0 ? -std::expm1(std::log1p(-alpha) / double(r.tests)) : alpha;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p[i] < r.level) ++r.rejected;
        if (p_values) p_values->rgb[i] = static_cast<float>(p[i]);
    }
    return r;
}

}  // namespace vkrt
