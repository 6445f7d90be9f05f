// The statistics harness (support/statistics.hpp): the incomplete gamma function
// against closed forms and tables, the chi-square test's pooling and degrees of
// freedom on counts small enough to work by hand, the Z-test and Sidak's
// correction against their formulas; and both tests on a fair generator, which
// they must pass, and on biased ones, which they must catch.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "statistics.hpp"

namespace {

using namespace vkrt::test;

// Q(k, x) for a whole k: e^-x (1 + x + x^2 / 2! + ... + x^(k-1) / (k-1)!), summed
// in long double (every term positive, so nothing cancels).
double upper_gamma_whole(int k, double x) {
    long double term = std::exp(-static_cast<long double>(x)), sum = 0.0L;
    for (int j = 0; j < k; ++j) {
        sum += term;
        term *= x / (j + 1);
    }
    return double(sum);
}

// Relative closeness, for values that may lie far in a tail. The function is good
// to about 13 digits there: x^a e^-x is computed as the exponential of a sum of
// terms as large as x, whose rounding its relative error inherits.
void expect_relative(double got, double want, double tolerance) {
    EXPECT_NEAR(got, want, tolerance * want) << "relative error " << (got - want) / want;
}

TEST(IncompleteGamma, MatchesTheClosedForms) {
    // x below a + 1 takes the power series, above it the continued fraction.
    for (const double x : {1e-6, 0.01, 0.5, 1.0, 1.9, 2.1, 5.0, 30.0, 200.0, 700.0}) {
        SCOPED_TRACE(testing::Message() << "x = " << x);
        expect_relative(regularized_upper_gamma(1.0, x), std::exp(-x), 1e-12);
        expect_relative(regularized_upper_gamma(0.5, x), std::erfc(std::sqrt(x)), 1e-12);
        expect_relative(regularized_upper_gamma(5.0, x), upper_gamma_whole(5, x), 1e-12);
    }
    // A hundred degrees of freedom and more, as a test over many bins has.
    for (const double x : {20.0, 80.0, 99.0, 101.0, 150.0, 300.0}) {
        SCOPED_TRACE(testing::Message() << "x = " << x);
        expect_relative(regularized_upper_gamma(100.0, x), upper_gamma_whole(100, x), 1e-12);
    }
    EXPECT_EQ(regularized_upper_gamma(3.0, 0.0), 1.0);
    EXPECT_EQ(regularized_upper_gamma(3.0, INFINITY), 0.0);
    EXPECT_THROW(regularized_upper_gamma(0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(regularized_upper_gamma(1.0, -1.0), std::invalid_argument);
}

TEST(ChiSquare, PValuesAtTabulatedCriticalValues) {
    // The 5% point of 1 degree of freedom and the 1% point of 10.
    EXPECT_NEAR(chi_square_p_value(3.841458820694124, 1), 0.05, 1e-14);
    EXPECT_NEAR(chi_square_p_value(23.20925115895436, 10), 0.01, 1e-14);
    // As the tables print them, to three decimals.
    EXPECT_NEAR(chi_square_p_value(3.841, 1), 0.05, 2e-5);
    EXPECT_NEAR(chi_square_p_value(23.209, 10), 0.01, 1e-6);
    // Two degrees of freedom: p = e^(-x / 2).
    EXPECT_NEAR(chi_square_p_value(5.991464547107979, 2), 0.05, 1e-14);
    EXPECT_EQ(chi_square_p_value(0.0, 7), 1.0);
    EXPECT_THROW(chi_square_p_value(1.0, 0), std::invalid_argument);
}

TEST(ChiSquare, PoolsBinsThatExpectTooFew) {
    // Bins 0 to 2 expect 2 each: pooled, they expect 6 and hold 8.
    const std::vector<double> observed{4, 1, 3, 12, 10};
    const std::vector<double> expected{2, 2, 2, 10, 14};
    const ChiSquareResult r = chi_square_test(observed, expected);
    EXPECT_EQ(r.bins, 3u);
    EXPECT_EQ(r.degrees_of_freedom, 2);
    const double statistic = 4.0 / 6.0 + 4.0 / 10.0 + 16.0 / 14.0;
    EXPECT_NEAR(r.statistic, statistic, 1e-15);
    EXPECT_NEAR(r.p_value, std::exp(-statistic / 2.0), 1e-15);  // 2 degrees of freedom

    // Pooled in index order, each pool closed as soon as it expects enough: bins
    // 0 and 1, 2 and 3, 4 and 5, holding 3, 7 and 11 where 6 were expected.
    const ChiSquareResult pairs = chi_square_test(std::vector<double>{1, 2, 3, 4, 5, 6},
                                                  std::vector<double>{3, 3, 3, 3, 3, 3});
    EXPECT_EQ(pairs.bins, 3u);
    EXPECT_NEAR(pairs.statistic, (9.0 + 1.0 + 25.0) / 6.0, 1e-15);
}

TEST(ChiSquare, ALastShortPoolJoinsTheBinThatExpectsLeast) {
    const std::vector<double> observed{9, 11, 1, 2};
    const std::vector<double> expected{10, 12, 1.5, 1.5};
    const ChiSquareResult r = chi_square_test(observed, expected);
    // The pool of bins 2 and 3 (3 against 3) joins bin 0: 12 against 13.
    EXPECT_EQ(r.bins, 2u);
    EXPECT_EQ(r.degrees_of_freedom, 1);
    const double statistic = 1.0 / 13.0 + 1.0 / 12.0;
    EXPECT_NEAR(r.statistic, statistic, 1e-15);
    EXPECT_NEAR(r.p_value, std::erfc(std::sqrt(statistic / 2.0)), 1e-15);  // 1 degree of freedom
}

TEST(ChiSquare, DegreesOfFreedomFollowWhatTheBinsHold) {
    const std::vector<double> observed{8, 12, 10};
    const std::vector<double> expected{10, 10, 10};
    EXPECT_EQ(chi_square_test(observed, expected).degrees_of_freedom, 2);
    const ChiSquareResult open = chi_square_test(observed, expected, {.bins_hold_every_draw = false});
    EXPECT_EQ(open.degrees_of_freedom, 3);
    EXPECT_NEAR(open.statistic, 0.8, 1e-15);
    // A larger minimum pools more: every bin here, which leaves no test.
    EXPECT_THROW(chi_square_test(observed, expected, {.min_expected = 40.0}), std::invalid_argument);
}

TEST(ChiSquare, DrawsWhereNoneWereExpectedFailTheTest) {
    const std::vector<double> expected{10, 0, 10, 10};
    const ChiSquareResult fair = chi_square_test(std::vector<double>{10, 0, 10, 10}, expected);
    EXPECT_EQ(fair.bins, 3u) << "a bin that expects none and holds none is no bin";
    EXPECT_EQ(fair.p_value, 1.0);
    const ChiSquareResult r = chi_square_test(std::vector<double>{10, 1, 10, 9}, expected);
    EXPECT_EQ(r.impossible, 1.0);
    EXPECT_EQ(r.p_value, 0.0);
}

TEST(ChiSquare, RefusesCountsThatAreNoCounts) {
    const std::vector<double> three{1, 2, 3};
    EXPECT_THROW(chi_square_test(three, std::vector<double>{1, 2}), std::invalid_argument);
    EXPECT_THROW(chi_square_test(std::vector<double>{1, -2, 3}, three), std::invalid_argument);
    EXPECT_THROW(chi_square_test(three, std::vector<double>{1, NAN, 3}), std::invalid_argument);
}

TEST(ZTest, TwoSidedPValues) {
    EXPECT_NEAR(z_test(1.96, 1.0, 0.0).p_value, 0.04999579029644087, 1e-15);
    // Either side, in units of the standard error.
    const ZTestResult low = z_test(10.0 - 0.196, 0.1, 10.0);
    EXPECT_NEAR(low.z, -1.96, 1e-12);
    EXPECT_NEAR(low.p_value, 0.04999579029644087, 1e-12);
    EXPECT_EQ(z_test(3.0, 0.5, 3.0).p_value, 1.0);
    EXPECT_NEAR(z_test(0.0, 1.0, 1.0).p_value, 0.3173105078629141, 1e-15);  // one standard error off
    // An exact estimate is right or wrong.
    EXPECT_EQ(z_test(2.0, 0.0, 2.0).p_value, 1.0);
    EXPECT_EQ(z_test(2.0, 0.0, 2.5).p_value, 0.0);
    EXPECT_THROW(z_test(2.0, -1.0, 2.0), std::invalid_argument);
}

TEST(Sidak, SplitsAFamilyLevelAmongItsTests) {
    EXPECT_NEAR(sidak_significance(0.05, 1), 0.05, 1e-17);
    EXPECT_NEAR(sidak_significance(0.05, 10), 0.005116196891823706, 1e-17);
    // Ten tests at that level falsely alarm, together, 5% of the time.
    EXPECT_NEAR(1.0 - std::pow(1.0 - sidak_significance(0.05, 10), 10.0), 0.05, 1e-15);
    // Tiny levels keep their digits: about level / tests.
    EXPECT_NEAR(sidak_significance(1e-12, 1000), 1e-15, 1e-27);
    EXPECT_THROW(sidak_significance(0.05, 0), std::invalid_argument);
    EXPECT_THROW(sidak_significance(1.0, 3), std::invalid_argument);
}

// ---- the tests at work: fair and biased generators --------------------------------

constexpr int kBins = 16;
constexpr int kDraws = 160000;
constexpr double kLevel = 0.01;

// Counts of kDraws bins drawn by `bin_of` from the (standardised) output of mt19937.
template <class BinOf>
std::array<double, kBins> histogram(BinOf bin_of) {
    std::mt19937 rng(2024);
    std::array<double, kBins> counts{};
    for (int i = 0; i < kDraws; ++i) counts[bin_of(rng)] += 1.0;
    return counts;
}

std::array<double, kBins> uniform_expectation() {
    std::array<double, kBins> expected;
    expected.fill(double(kDraws) / kBins);
    return expected;
}

TEST(ChiSquare, PassesAFairGenerator) {
    // The top four bits of each 32-bit output: every bin equally likely.
    const auto counts = histogram([](std::mt19937& rng) { return rng() >> 28; });
    const ChiSquareResult r = chi_square_test(counts, uniform_expectation());
    EXPECT_EQ(r.degrees_of_freedom, kBins - 1);
    EXPECT_GT(r.p_value, kLevel) << r;
}

TEST(ChiSquare, CatchesModuloBias) {
    // A number from 0 to 99 taken modulo 16: 0 to 3 come up 7 times in 100, the
    // others 6.
    const auto counts = histogram([](std::mt19937& rng) {
        std::uint32_t v;
        do v = rng() >> 25; while (v >= 100);  // 0 to 127, of which 0 to 99 kept
        return v % kBins;
    });
    const ChiSquareResult r = chi_square_test(counts, uniform_expectation());
    EXPECT_LT(r.p_value, 1e-12) << r;
}

// The mean of kDraws uniform numbers in [0, 1) as an estimate of 1/2, and its
// standard error from the samples.
ZTestResult mean_against_one_half(double scale) {
    std::mt19937 rng(7);
    double sum = 0.0, sum_sq = 0.0;
    for (int i = 0; i < kDraws; ++i) {
        const double u = scale * (rng() + 0.5) / 4294967296.0;
        sum += u;
        sum_sq += u * u;
    }
    const double mean = sum / kDraws;
    const double variance = (sum_sq - kDraws * mean * mean) / (kDraws - 1);
    return z_test(mean, std::sqrt(variance / kDraws), 0.5);
}

TEST(ZTest, PassesAnUnbiasedEstimateAndCatchesABiasedOne) {
    const ZTestResult fair = mean_against_one_half(1.0);
    EXPECT_GT(fair.p_value, kLevel) << fair;
    // Numbers in [0, 0.99): the mean is 0.495, some seven standard errors low.
    const ZTestResult biased = mean_against_one_half(0.99);
    EXPECT_LT(biased.z, 0.0);
    EXPECT_LT(biased.p_value, 1e-9) << biased;
}

}  // namespace
