#include "image/student_t.hpp"

#include <cmath>
#include <limits>

namespace vkrt {

namespace {

// The continued fraction of I_x(a, b) / (x^a (1 - x)^b / (a B(a, b))):
// 1 / (1 + d1 / (1 + d2 / (1 + ...))), with
//   d(2m + 1) = -(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1)),
//   d(2m)     = m (b - m) x / ((a + 2m - 1)(a + 2m)),
// evaluated front to back by the modified Lentz algorithm. It converges fast for
// x < (a + 1) / (a + b + 2); the caller uses the symmetry I_x(a, b) = 1 - I_(1-x)(b, a)
// beyond.
double beta_fraction(double a, double b, double x) {
    constexpr double kTiny = 1e-300;
    constexpr double kEpsilon = 1e-16;
    constexpr int kMaxTerms = 10000;
    const auto nudge = [](double v) { return std::abs(v) < kTiny ? kTiny : v; };
    double c = 1.0;
    double d = 1.0 / nudge(1.0 - (a + b) * x / (a + 1.0));
    double f = d;
    for (int m = 1; m <= kMaxTerms; ++m) {
        const double even = m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m));
        d = 1.0 / nudge(1.0 + even * d);
        c = nudge(1.0 + even / c);
        f *= c * d;
        const double odd = -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0));
        d = 1.0 / nudge(1.0 + odd * d);
        c = nudge(1.0 + odd / c);
        const double step = c * d;
        f *= step;
        if (std::abs(step - 1.0) < kEpsilon) break;
    }
    return f;
}

}  // namespace

double incomplete_beta(double a, double b, double x) {
    if (x <= 0.0) return 0.0;
    if (x >= 1.0) return 1.0;
    // x^a (1 - x)^b / B(a, b), in logarithms so that neither power underflows first.
    const double log_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    const double front = std::exp(log_front);
    if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(a, b, x) / a;
    return 1.0 - front * beta_fraction(b, a, 1.0 - x) / b;
}

double two_sided_t_p(double t, double dof) {
    const double s = std::abs(t);
    if (std::isnan(s) || std::isnan(dof)) return std::numeric_limits<double>::quiet_NaN();
    // Beyond 1e7 degrees of freedom the t density differs from the normal's by about
    // z^4 / (4 dof) relative (1e-4 at z = 8), and the logarithms of the gamma
    // functions below would cancel to fewer digits than that.
    if (!(dof < 1e7)) return std::erfc(s / std::sqrt(2.0));
    if (s == std::numeric_limits<double>::infinity()) return 0.0;
    // P(|T| >= s) = I_(dof / (dof + s^2))(dof / 2, 1 / 2) (A&S 26.7.1), with
    // dof / (dof + s^2) written so that a large s does not round it to 0.
    const double x = dof / (dof + s * s);
    return incomplete_beta(0.5 * dof, 0.5, x);
}

}  // namespace vkrt
