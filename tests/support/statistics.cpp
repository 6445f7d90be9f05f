#include "statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace vkrt::test {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// Both expansions below converge in about sqrt(a) terms; this many means a bug.
constexpr int kMaxTerms = 100000;

// x^a e^-x / Gamma(a), the factor both expansions share, through logarithms so
// that it neither overflows nor underflows before the product would.
double gamma_prefactor(double a, double x) { return std::exp(a * std::log(x) - x - std::lgamma(a)); }

// The lower function P(a, x) = 1 - Q(a, x) by its power series, which converges
// fast for x < a + 1:
//   P(a, x) = x^a e^-x / Gamma(a) * sum_{n >= 0} x^n / (a (a + 1) ... (a + n)).
double lower_gamma_series(double a, double x) {
    double term = 1.0 / a;
    double sum = term;
    for (int n = 1; n < kMaxTerms; ++n) {
        term *= x / (a + n);
        sum += term;
        if (term < sum * kEpsilon) return sum * gamma_prefactor(a, x);
    }
    throw std::runtime_error("regularized_upper_gamma: the series did not converge");
}

// Q(a, x) by its continued fraction, which converges fast for x >= a + 1:
//   Q(a, x) = x^a e^-x / Gamma(a) * 1 / (b_0 + a_1 / (b_1 + a_2 / (b_2 + ...)))
// with b_n = x + 2n + 1 - a and a_n = -n (n - a), evaluated front to back by the
// modified Lentz method: the n-th convergent is the product of ratios C_n D_n,
// where C_n = b_n + a_n / C_{n-1} and D_n = 1 / (b_n + a_n D_{n-1}). A zero
// denominator is nudged to a tiny number, which the next step corrects.
double upper_gamma_fraction(double a, double x) {
    constexpr double kTiny = std::numeric_limits<double>::min() / kEpsilon;
    const auto nudged = [](double v) { return std::abs(v) < kTiny ? kTiny : v; };
    // The first convergent, 1 / b_0, as the method leaves it: D = 1 / b_0, and C so
    // large that the next one, b_1 + a_1 / C, is b_1.
    double b = x + 1.0 - a;
    double c = 1.0 / kTiny;
    double d = 1.0 / nudged(b);
    double fraction = d;
    for (int n = 1; n < kMaxTerms; ++n) {
        const double an = -n * (n - a);
        b += 2.0;
        d = 1.0 / nudged(b + an * d);
        c = nudged(b + an / c);
        const double ratio = c * d;
        fraction *= ratio;
        if (std::abs(ratio - 1.0) < kEpsilon) return fraction * gamma_prefactor(a, x);
    }
    throw std::runtime_error("regularized_upper_gamma: the continued fraction did not converge");
}

void check_count(double value, const char* what) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
        throw std::invalid_argument(std::string("chi_square_test: ") + what + " count " + std::to_string(value) +
                                    " is not a finite number >= 0");
    }
}

struct Bin {
    double observed = 0.0;
    double expected = 0.0;
};

}  // namespace

double regularized_upper_gamma(double a, double x) {
    if (!(a > 0.0) || !(x >= 0.0)) {
        throw std::invalid_argument("regularized_upper_gamma: needs a > 0 and x >= 0, not a = " + std::to_string(a) +
                                    ", x = " + std::to_string(x));
    }
    if (x == 0.0) return 1.0;
    if (std::isinf(x)) return 0.0;
    return x < a + 1.0 ? 1.0 - lower_gamma_series(a, x) : upper_gamma_fraction(a, x);
}

double chi_square_p_value(double statistic, int degrees_of_freedom) {
    if (degrees_of_freedom < 1) {
        throw std::invalid_argument("chi_square_p_value: " + std::to_string(degrees_of_freedom) +
                                    " degrees of freedom");
    }
    return regularized_upper_gamma(0.5 * degrees_of_freedom, 0.5 * std::max(statistic, 0.0));
}

ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected,
                                const ChiSquareOptions& options) {
    if (observed.size() != expected.size()) {
        throw std::invalid_argument("chi_square_test: " + std::to_string(observed.size()) + " observed counts but " +
                                    std::to_string(expected.size()) + " expected");
    }
    ChiSquareResult result;
    std::vector<Bin> bins;
    Bin pool;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        check_count(observed[i], "observed");
        check_count(expected[i], "expected");
        if (expected[i] == 0.0) {
            result.impossible += observed[i];
        } else if (expected[i] >= options.min_expected) {
            bins.push_back({observed[i], expected[i]});
        } else {
            pool.observed += observed[i];
            pool.expected += expected[i];
            if (pool.expected >= options.min_expected) {
                bins.push_back(pool);
                pool = {};
            }
        }
    }
    if (pool.expected > 0.0) {
        if (bins.empty()) {
            bins.push_back(pool);
        } else {
            Bin& least = *std::min_element(bins.begin(), bins.end(),
                                           [](const Bin& l, const Bin& r) { return l.expected < r.expected; });
            least.observed += pool.observed;
            least.expected += pool.expected;
        }
    }

    result.bins = bins.size();
    result.degrees_of_freedom = int(bins.size()) - (options.bins_hold_every_draw ? 1 : 0);
    if (result.degrees_of_freedom < 1) {
        throw std::invalid_argument("chi_square_test: " + std::to_string(bins.size()) +
                                    " bins after pooling leave no degree of freedom");
    }
    for (const Bin& bin : bins) {
        const double difference = bin.observed - bin.expected;
        result.statistic += difference * difference / bin.expected;
    }
    if (result.impossible > 0.0) {
        result.statistic = std::numeric_limits<double>::infinity();
        result.p_value = 0.0;
    } else {
        result.p_value = chi_square_p_value(result.statistic, result.degrees_of_freedom);
    }
    return result;
}

ZTestResult z_test(double mean, double standard_error, double reference) {
    if (!(standard_error >= 0.0)) {
        throw std::invalid_argument("z_test: the standard error " + std::to_string(standard_error) +
                                    " is not a number >= 0");
    }
    ZTestResult result;
    if (standard_error == 0.0) {
        const bool equal = mean == reference;
        result.z = equal ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), mean - reference);
        result.p_value = equal ? 1.0 : 0.0;
        return result;
    }
    result.z = (mean - reference) / standard_error;
    // Both tails of the standard normal: 2 (1 - Phi(|z|)) = erfc(|z| / sqrt 2).
    result.p_value = std::erfc(std::abs(result.z) / std::sqrt(2.0));
    return result;
}

double sidak_significance(double family_level, std::size_t tests) {
    if (!(family_level > 0.0 && family_level < 1.0) || tests == 0) {
        throw std::invalid_argument("sidak_significance: needs a level in (0, 1) and at least one test");
    }
    // 1 - (1 - level)^(1 / tests) without the cancellation of the direct form.
    return -std::expm1(std::log1p(-family_level) / double(tests));
}

std::ostream& operator<<(std::ostream& out, const ChiSquareResult& result) {
    out << "chi-square " << result.statistic << ", " << result.degrees_of_freedom << " degrees of freedom ("
        << result.bins << " bins), p = " << result.p_value;
    if (result.impossible > 0.0) out << "; " << result.impossible << " draws in bins expected to get none";
    return out;
}

std::ostream& operator<<(std::ostream& out, const ZTestResult& result) {
    return out << "z = " << result.z << ", p = " << result.p_value;
}

}  // namespace vkrt::test
