// The exact per-pixel sums of kernel/sums.glsl: the fixed-point conversion, carries,
// clamping, the variance of the mean from the sums of squares, and the property they
// exist for, that any split adds up bit for bit (the squares' sums too).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "render/pixel_sums.hpp"

namespace {

namespace kernel = vkrt::kernel;
using kernel::uvec3;
using kernel::vec3;

TEST(FixedPoint, UnitsOfTwoToTheMinus40) {
    EXPECT_EQ(kernel::fixed_point(0.0f), uvec3(0u, 0u, 0u));
    EXPECT_EQ(kernel::fixed_point(1.0f), uvec3(0u, 256u, 0u));                 // 2^40 = 2^8 * 2^32
    EXPECT_EQ(kernel::fixed_point(std::ldexp(1.0f, -40)), uvec3(1u, 0u, 0u));  // one unit
    EXPECT_EQ(kernel::fixed_point(std::ldexp(1.0f, -41)), uvec3(0u, 0u, 0u));  // below one: dropped
    EXPECT_EQ(kernel::fixed_point(3.5f * 16777216.0f), uvec3(0u, 0x80000000u, 3u));  // 3.5 * 2^64 units
    // 2^-20 + 1.5 * 2^-40 (a float: 21 bits apart) keeps its unit and drops the half.
    EXPECT_EQ(kernel::fixed_point(std::ldexp(1.0f, -20) + std::ldexp(1.5f, -40)), uvec3(0x100001u, 0u, 0u));
}

TEST(FixedPoint, WordsCarry) {
    EXPECT_EQ(kernel::add_words(uvec3(0xFFFFFFFFu, 0xFFFFFFFFu, 0u), uvec3(1u, 0u, 0u)), uvec3(0u, 0u, 1u));
    EXPECT_EQ(kernel::add_words(uvec3(0xFFFFFFFFu, 5u, 0u), uvec3(0xFFFFFFFFu, 0xFFFFFFFAu, 2u)),
              uvec3(0xFFFFFFFEu, 0u, 3u));
}

TEST(FixedPoint, SumSampleMaxIsTheLargestFloatBelowTwoToThe40) {
    EXPECT_EQ(kernel::SUM_SAMPLE_MAX, std::nextafter(std::ldexp(1.0f, 40), 0.0f));
}

TEST(PixelSum, MostSamplesOfTheLargestValueDoNotOverflow) {
    kernel::PixelSum s{};
    constexpr std::uint32_t kMaxSpp = 65536;  // limits::kMaxSpp
    for (std::uint32_t i = 0; i < kMaxSpp; ++i) kernel::add_sample(s, vec3(kernel::SUM_SAMPLE_MAX), true);
    EXPECT_EQ(vkrt::samples_summed(s), kMaxSpp);
    EXPECT_EQ(vkrt::samples_clamped(s), 0u);
    EXPECT_EQ(vkrt::radiance_sum(s).g, double(kMaxSpp) * double(kernel::SUM_SAMPLE_MAX));
}

TEST(PixelSum, OutOfRangeChannelsAreClampedAndCounted) {
    kernel::PixelSum s{};
    kernel::add_sample(s, vec3(1e38f, 1.0f, -2.0f), true);
    EXPECT_EQ(vkrt::samples_summed(s), 1u);
    EXPECT_EQ(vkrt::samples_clamped(s), 1u);
    EXPECT_EQ(vkrt::radiance_sum(s), glm::dvec3(double(kernel::SUM_SAMPLE_MAX), 1.0, 0.0));
    kernel::add_sample(s, vec3(0.25f), true);
    EXPECT_EQ(vkrt::samples_clamped(s), 1u);
    EXPECT_EQ(vkrt::mean_radiance(s).g, 0.625f);
}

TEST(PixelSum, MeanOfNoSamplesIsBlack) {
    EXPECT_EQ(vkrt::mean_radiance(kernel::PixelSum{}), glm::vec3(0.0f));
}

// (sum of squares - sum^2 / n) / (n - 1) / n, exactly where every value is a short
// binary fraction: samples 0, 1, 2, 5 (sum 8, squares 30, n 4) give (30 - 16) / 3 / 4.
TEST(PixelSum, VarianceOfTheMean) {
    kernel::PixelSum s{};
    for (float v : {0.0f, 1.0f, 2.0f, 5.0f}) kernel::add_sample(s, vec3(v, 0.5f * v, 3.0f), true);
    EXPECT_EQ(vkrt::squares_sum(s), glm::dvec3(30.0, 7.5, 36.0));
    const glm::dvec3 v = vkrt::variance_of_mean(s);
    EXPECT_DOUBLE_EQ(v.r, 14.0 / 12.0);
    EXPECT_DOUBLE_EQ(v.g, 3.5 / 12.0);
    EXPECT_EQ(v.b, 0.0) << "samples that agree have no variance";
}

TEST(PixelSum, VarianceIsUnknownBelowTwoSamples) {
    kernel::PixelSum s{};
    EXPECT_TRUE(std::isinf(vkrt::variance_of_mean(s).r));
    kernel::add_sample(s, vec3(1.0f), true);
    EXPECT_TRUE(std::isinf(vkrt::variance_of_mean(s).g));
}

// Squares rounded to floats never make a negative variance: 0.1 (not a short binary
// fraction) a thousand times.
TEST(PixelSum, AgreeingSamplesHaveNoNegativeVariance) {
    kernel::PixelSum s{};
    for (int i = 0; i < 1000; ++i) kernel::add_sample(s, vec3(0.1f, 1.0f / 3.0f, 7.7f), true);
    const glm::dvec3 v = vkrt::variance_of_mean(s);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GE(v[c], 0.0);
        EXPECT_LT(v[c], 1e-9 * vkrt::mean_radiance(s)[c] * vkrt::mean_radiance(s)[c]);
    }
}

// The point of it all: float sums depend on the order, these do not.
TEST(PixelSum, AnySplitOfTheSamplesAddsUpBitForBit) {
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> exponent(-20.0f, 10.0f);
    std::vector<vec3> samples(1000);
    for (vec3& v : samples) v = vec3(std::exp2(exponent(gen)), std::exp2(exponent(gen)), std::exp2(exponent(gen)));

    kernel::PixelSum whole{};
    for (const vec3& v : samples) kernel::add_sample(whole, v, true);
    for (std::size_t cut : {std::size_t(1), std::size_t(333), std::size_t(999)}) {
        kernel::PixelSum head{}, tail{};
        for (std::size_t i = 0; i < cut; ++i) kernel::add_sample(head, samples[i], true);
        for (std::size_t i = samples.size(); i-- > cut;) kernel::add_sample(tail, samples[i], true);  // backwards
        EXPECT_EQ(kernel::add_sums(tail, head), whole) << "cut at " << cut;
    }
    // Float sums of the same split differ, which is why the sums are not floats.
    float forward = 0.0f, backward = 0.0f;
    for (const vec3& v : samples) forward += v.x;
    for (std::size_t i = samples.size(); i-- > 0;) backward += samples[i].x;
    EXPECT_NE(forward, backward);
    // And the exact sum is the true sum to within one unit per sample. (The samples'
    // bits span 2^10 down to 2^-43, and their sum stays below 2^20: a long double,
    // 64 bits of mantissa, adds them without rounding.)
    long double exact = 0.0L;
    for (const vec3& v : samples) exact += (long double)v.x;
    EXPECT_NEAR(vkrt::radiance_sum(whole).r, double(exact), 1000 * std::ldexp(1.0, -40) + 1e-10);
}

}  // namespace
