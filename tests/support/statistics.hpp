#pragma once
// Statistical checks for tests of random sampling: does a sampler draw what its
// density says (a chi-square goodness-of-fit test over binned counts), and does a
// Monte Carlo estimate agree with a known value (a two-sided Z-test)? Each answers
// with a p-value: the probability, were the sampler right, of a result at least
// this far from what was expected. A test fails when the p-value falls below its
// significance level, the rate of false alarms it accepts.
#include <cstddef>
#include <iosfwd>
#include <span>

namespace vkrt::test {

struct ChiSquareOptions {
    // The statistic follows the chi-square distribution only when every bin expects
    // a few draws. Bins expected to hold fewer than this are pooled, in index order,
    // each pool closed once it expects this many; a last pool that falls short joins
    // the bin that expects least. The pools depend on the expected counts alone, so
    // the test stays valid.
    double min_expected = 5.0;
    // True when the bins hold every draw, so that the observed counts add up to the
    // expected total by construction: that constraint costs a degree of freedom.
    // False when some draws fall outside the bins (a sampler that can fail, or
    // outcomes the test does not bin).
    bool bins_hold_every_draw = true;
};

struct ChiSquareResult {
    double statistic = 0.0;      // sum over the pooled bins of (observed - expected)^2 / expected
    int degrees_of_freedom = 0;  // pooled bins, less one if they hold every draw
    double p_value = 1.0;        // of a chi-square variate with those degrees of freedom reaching the statistic
    std::size_t bins = 0;        // after pooling
    double impossible = 0.0;     // draws in bins expected to get none: any makes the p-value 0
};

// Compares observed counts with expected ones, bin by bin (spans of the same size;
// counts may be fractional, e.g. weighted). Throws std::invalid_argument for
// negative or non-finite counts, spans of different sizes, or too few bins left
// after pooling to have a degree of freedom.
ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected,
                                const ChiSquareOptions& options = {});

// The probability that a chi-square variate with `degrees_of_freedom` (> 0)
// reaches `statistic`: Q(degrees_of_freedom / 2, statistic / 2).
double chi_square_p_value(double statistic, int degrees_of_freedom);

// The regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a),
// for a > 0 and x >= 0. Its relative error, however far into the tail, is below
// (x + a |ln x|) times the double epsilon, from the rounding of x^a e^-x: about
// 1e-13 for the statistics of a few hundred bins.
double regularized_upper_gamma(double a, double x);

struct ZTestResult {
    double z = 0.0;        // (mean - reference) / standard error
    double p_value = 1.0;  // two-sided: of a standard normal variate at least |z| from 0
};

// Whether an estimate `mean` with `standard_error` (>= 0) is consistent with
// `reference`. With a standard error of 0 the p-value is 1 when the mean equals
// the reference and 0 otherwise.
ZTestResult z_test(double mean, double standard_error, double reference);

// The significance level for each of `tests` independent tests such that the
// chance of any false alarm among them is `family_level` (Sidak's correction):
// 1 - (1 - family_level)^(1 / tests).
double sidak_significance(double family_level, std::size_t tests);

// For failure messages, e.g. "chi-square 12.3, 15 degrees of freedom (16 bins), p = 0.66".
std::ostream& operator<<(std::ostream& out, const ChiSquareResult& result);
std::ostream& operator<<(std::ostream& out, const ZTestResult& result);

}  // namespace vkrt::test
