#include "image/z_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "image/student_t.hpp"

namespace vkrt {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The degrees of freedom a score of variance va + vb is judged by: the smaller of
// those of the terms that have any variance (decision 0051). Not Welch and
// Satterthwaite's estimate, (va + vb)^2 / (va^2 / dof_a + vb^2 / dof_b): computed from
// the estimated variances themselves, it gives a pixel whose few-image variance came
// out small by chance nearly normal tails, just where the score is too large.
double score_dof(double va, double dof_a, double vb, double dof_b) {
    return std::min(va > 0.0 ? dof_a : kInfinity, vb > 0.0 ? dof_b : kInfinity);
}

// The two-sided p-value of a difference d of variance v (v of `dof` degrees of
// freedom); of variance 0, certain: 1 where d is 0, else 0. Sets z to the score.
double p_value(double d, double v, double dof, double& z) {
    if (v > 0.0) {
        z = d / std::sqrt(v);
        return two_sided_t_p(z, dof);
    }
    z = d == 0.0 ? 0.0 : d > 0.0 ? kInfinity : -kInfinity;
    return d == 0.0 ? 1.0 : 0.0;
}

}  // namespace

ZTestResult z_test(const Image& a, PixelVariance var_a, const Image& b, PixelVariance var_b, double alpha,
                   Image* p_values) {
    ZTestResult r;
    r.alpha = alpha;
    if (p_values) *p_values = Image(a.width, a.height);
    // The p-values first, then the level, which depends on how many were tested.
    std::vector<double> p(a.rgb.size(), 1.0);
    std::array<double, 3> mean_sum{}, mean_variance{};
    std::array<std::size_t, 3> mean_count{};
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double va = double(var_a.image->rgb[i]);
        const double vb = var_b.image ? double(var_b.image->rgb[i]) : 0.0;
        const double variance = va + vb;
        const double d = double(a.rgb[i]) - double(b.rgb[i]);
        if (!(variance < kInfinity)) continue;  // unknown (or NaN): untested
        ++r.tests;
        const std::size_t channel = i % 3;
        mean_sum[channel] += d;
        mean_variance[channel] += variance;
        ++mean_count[channel];
        double z = 0.0;
        p[i] = p_value(d, variance, score_dof(va, var_a.dof, vb, var_b.dof), z);
        if (p[i] < r.min_p || (p[i] == r.min_p && std::abs(z) > std::abs(r.worst_z))) {
            r.min_p = p[i];
            r.worst_z = z;
            r.worst_x = std::uint32_t((i / 3) % a.width);
            r.worst_y = std::uint32_t((i / 3) / a.width);
            r.worst_channel = std::uint32_t(channel);
        }
    }
    std::size_t mean_tests = 0;
    for (std::size_t c = 0; c < 3; ++c) {
        if (mean_count[c] == 0) continue;
        ++mean_tests;
        const double n = double(mean_count[c]);
        MeanTest& m = r.means[c];
        m.difference = mean_sum[c] / n;
        m.standard_error = std::sqrt(mean_variance[c]) / n;
        m.p = p_value(m.difference, m.standard_error * m.standard_error, kInfinity, m.z);
    }
    // 1 - (1 - alpha)^(1/m), without the cancellation of the plain formula.
    const std::size_t family = r.tests + mean_tests;
    r.level = family > 0 ? -std::expm1(std::log1p(-alpha) / double(family)) : alpha;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p[i] < r.level) ++r.rejected;
        if (p_values) p_values->rgb[i] = static_cast<float>(p[i]);
    }
    for (std::size_t c = 0; c < 3; ++c) {
        if (mean_count[c] != 0 && r.means[c].p < r.level) ++r.means_rejected;
    }
    return r;
}

}  // namespace vkrt
