// Student's t tail (image/student_t.hpp) against its closed forms: 1, 2 and 3
// degrees of freedom, the normal's as they grow, far tails to their relative
// precision; and the incomplete beta function at values with closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "image/student_t.hpp"

namespace vkrt {
namespace {

constexpr double kPi = std::numbers::pi;

// P(|T| >= t) with 1 degree of freedom (Cauchy): (2 / pi) atan(1 / t); with 2:
// 1 - t / sqrt(2 + t^2); with 3: 1 - (2 / pi) (atan(t / sqrt 3) + sqrt(3) t / (3 + t^2)).
double cauchy_tail(double t) { return 2.0 / kPi * std::atan(1.0 / t); }
double two_dof_tail(double t) { return 2.0 / (std::sqrt(2.0 + t * t) * (std::sqrt(2.0 + t * t) + t)); }
double three_dof_tail(double t) {
    return 1.0 - 2.0 / kPi * (std::atan(t / std::sqrt(3.0)) + std::sqrt(3.0) * t / (3.0 + t * t));
}

TEST(StudentT, ClosedFormsOfOneTwoAndThreeDegreesOfFreedom) {
    for (double t : {0.0, 0.1, 0.5, 1.0, 2.0, 3.5, 10.0, 100.0}) {
        SCOPED_TRACE(t);
        EXPECT_NEAR(two_sided_t_p(t, 1.0), t == 0.0 ? 1.0 : cauchy_tail(t), 1e-13);
        EXPECT_NEAR(two_sided_t_p(-t, 1.0), two_sided_t_p(t, 1.0), 0.0);
        EXPECT_NEAR(two_sided_t_p(t, 2.0), two_dof_tail(t), 1e-13);
        EXPECT_NEAR(two_sided_t_p(t, 3.0), three_dof_tail(t), 1e-12);
    }
}

// Far tails, where a test's Sidak level lies: relative precision, not absolute.
TEST(StudentT, FarTailsToTheirRelativePrecision) {
    for (double t : {1e3, 1e6, 1e9}) {
        const double expected = cauchy_tail(t);
        EXPECT_NEAR(two_sided_t_p(t, 1.0) / expected, 1.0, 1e-12) << t;
    }
    for (double t : {30.0, 1e3, 1e5}) {
        EXPECT_NEAR(two_sided_t_p(t, 2.0) / two_dof_tail(t), 1.0, 1e-12) << t;
    }
    EXPECT_EQ(two_sided_t_p(std::numeric_limits<double>::infinity(), 4.0), 0.0);
}

// As the degrees of freedom grow the tail becomes the normal's, erfc(t / sqrt 2);
// at 10^4 within twice the first term of its expansion in 1 / dof, about
// (t^4 + 2 t^2 + 3) / (4 dof) relative.
TEST(StudentT, BecomesTheNormalTail) {
    for (double t : {0.5, 1.96, 4.0}) {
        const double normal = std::erfc(t / std::sqrt(2.0));
        EXPECT_EQ(two_sided_t_p(t, std::numeric_limits<double>::infinity()), normal);
        EXPECT_EQ(two_sided_t_p(t, 1e8), normal);
        EXPECT_NEAR(two_sided_t_p(t, 1e4) / normal, 1.0, (t * t * t * t + 2.0 * t * t + 3.0) / 2e4) << t;
        EXPECT_GT(two_sided_t_p(t, 10.0), normal) << "heavier tails than the normal's";
    }
    // The 97.5% quantile of t with 10 degrees of freedom, 2.228139 (tables).
    EXPECT_NEAR(two_sided_t_p(2.228139, 10.0), 0.05, 1e-6);
}

TEST(IncompleteBeta, ClosedForms) {
    for (double x : {0.0, 0.01, 0.3, 0.5, 0.77, 0.999, 1.0}) {
        SCOPED_TRACE(x);
        EXPECT_NEAR(incomplete_beta(1.0, 1.0, x), x, 1e-14);                          // uniform
        EXPECT_NEAR(incomplete_beta(2.0, 1.0, x), x * x, 1e-14);                      // x^a for b = 1
        EXPECT_NEAR(incomplete_beta(1.0, 3.0, x), 1.0 - std::pow(1.0 - x, 3.0), 1e-14);
        EXPECT_NEAR(incomplete_beta(0.5, 0.5, x), 2.0 / kPi * std::asin(std::sqrt(x)), 1e-13);  // arcsine
    }
}

}  // namespace
}  // namespace vkrt
