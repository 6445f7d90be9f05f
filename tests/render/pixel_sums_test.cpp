// The exact per-pixel sums of kernel/sums.glsl: the fixed-point conversion, carries,
// clamping, and the property they exist for, that any split adds up bit for bit.
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
    for (std::uint32_t i = 0; i < kMaxSpp; ++i) kernel::add_sample(s, vec3(kernel::SUM_SAMPLE_MAX));
    EXPECT_EQ(vkrt::samples_summed(s), kMaxSpp);
    EXPECT_EQ(vkrt::samples_clamped(s), 0u);
    EXPECT_EQ(vkrt::radiance_sum(s).g, double(kMaxSpp) * double(kernel::SUM_SAMPLE_MAX));
}

TEST(PixelSum, OutOfRangeChannelsAreClampedAndCounted) {
    kernel::PixelSum s{};
    kernel::add_sample(s, vec3(1e38f, 1.0f, -2.0f));
    EXPECT_EQ(vkrt::samples_summed(s), 1u);
    EXPECT_EQ(vkrt::samples_clamped(s), 1u);
    EXPECT_EQ(vkrt::radiance_sum(s), glm::dvec3(double(kernel::SUM_SAMPLE_MAX), 1.0, 0.0));
    kernel::add_sample(s, vec3(0.25f));
    EXPECT_EQ(vkrt::samples_clamped(s), 1u);
    EXPECT_EQ(vkrt::mean_radiance(s).g, 0.625f);
}

TEST(PixelSum, MeanOfNoSamplesIsBlack) {
    EXPECT_EQ(vkrt::mean_radiance(kernel::PixelSum{}), glm::vec3(0.0f));
}

// The point of it all: float sums depend on the order, these do not.
TEST(PixelSum, AnySplitOfTheSamplesAddsUpBitForBit) {
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> exponent(-20.0f, 10.0f);
    std::vector<vec3> samples(1000);
    for (vec3& v : samples) v = vec3(std::exp2(exponent(gen)), std::exp2(exponent(gen)), std::exp2(exponent(gen)));

    kernel::PixelSum whole{};
    for (const vec3& v : samples) kernel::add_sample(whole, v);
    for (std::size_t cut : {std::size_t(1), std::size_t(333), std::size_t(999)}) {
        kernel::PixelSum head{}, tail{};
        for (std::size_t i = 0; i < cut; ++i) kernel::add_sample(head, samples[i]);
        for (std::size_t i = samples.size(); i-- > cut;) kernel::add_sample(tail, samples[i]);  // backwards
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
