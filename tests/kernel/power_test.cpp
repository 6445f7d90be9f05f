// The kernel's own x^y (shaders/kernel/power.glsl) against the C library's in double
// precision, over the range the Phong lobe and its sampling use.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::Kernel;

// Within a few ULP where the result is a normal float, from cosines near 0 to 1 and
// exponents from 1e-4 to 1e4; the allowance grows with |y log2 x|, the exponent
// whose own rounding error x^y multiplies by ln 2.
TEST(Power, WithinAFewUlpsOfTheExactPower) {
    Kernel k;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_real_distribution<float> exponent(-4.0f, 4.0f);
    double worst = 0.0;
    int compared = 0;
    for (int i = 0; i < 200000; ++i) {
        const float x = i % 3 == 0 ? unit(rng) : 1.0f - unit(rng) * std::exp2(-float(i % 24));
        const float y = std::pow(10.0f, exponent(rng));
        const double want = std::pow(double(x), double(y));
        if (!(want > 1e-37) || !(x > 0.0f) || !(x < 1.0f)) continue;
        const double got = k.power(x, y);
        // An error in y log2(x) of half an ULP of it moves x^y by that times ln 2.
        const double allowed = 6.0 * 0x1p-24 * (1.0 + std::abs(double(y) * std::log2(double(x))) * 0.6931);
        worst = std::max(worst, std::abs(got - want) / want / allowed);
        ++compared;
    }
    EXPECT_GT(compared, 150000);
    EXPECT_LT(worst, 1.0);
}

TEST(Power, ExactWhereTheAnswerIs) {
    Kernel k;
    EXPECT_EQ(k.power(0.5f, 2.0f), 0.25f);
    EXPECT_EQ(k.power(0.25f, 0.5f), 0.5f);
    EXPECT_EQ(k.power(0.7f, 0.0f), 1.0f);
    EXPECT_EQ(k.power(0.0f, 0.0f), 1.0f);  // the lobe's x^0, as the paper's Phong with exponent 0
    EXPECT_EQ(k.power(0.0f, 3.0f), 0.0f);
    EXPECT_EQ(k.power(1.0f, 200.0f), 1.0f);
    EXPECT_EQ(k.power(1.0000001f, 200.0f), 1.0f);  // a cosine a rounding above 1
    EXPECT_EQ(k.power(0.5f, 200.0f), 0.0f);         // 2^-200: below float's normal range
    EXPECT_EQ(k.power(0.5f, 126.0f), 0x1p-126f);
}

}  // namespace
