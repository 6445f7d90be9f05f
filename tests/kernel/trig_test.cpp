// The kernel's own sine, cosine and arc tangent (shaders/kernel/trig.glsl) against
// the C library's in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernel/kernel.hpp"

namespace {

using vkrt::kernel::Kernel;

TEST(Trig, SinAndCosWithinAnUlpOnTheKernelsAngles) {
    Kernel k;
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> angle(-8.0f, 8.0f);
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const float x = i < 1000 ? float(i) * 0.0072f : angle(rng);  // also every quadrant boundary near 2 pi
        const auto sc = k.sin_cos(x);
        worst = std::max({worst, std::abs(double(sc.x) - std::sin(double(x))),
                          std::abs(double(sc.y) - std::cos(double(x)))});
    }
    EXPECT_LT(worst, 1.5e-7);  // float's ULP at 1 is 1.2e-7; Vulkan allows 2^-11 = 4.9e-4
    EXPECT_EQ(k.sin_cos(0.0f).x, 0.0f);
    EXPECT_EQ(k.sin_cos(0.0f).y, 1.0f);
}

TEST(Trig, UpperHalfPlaneAngleIsAtan2WithinAFewUlps) {
    Kernel k;
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> coordinate(-10.0f, 10.0f);
    std::uniform_real_distribution<float> exponent(-20.0f, 20.0f);
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const float y = std::abs(coordinate(rng)) * std::exp2(exponent(rng));
        const float x = coordinate(rng) * std::exp2(exponent(rng));
        if (!(y > 0.0f)) continue;
        const double want = std::atan2(double(y), double(x));
        worst = std::max(worst, std::abs(double(k.upper_half_plane_angle(y, x)) - want) / want);
    }
    EXPECT_LT(worst, 5e-7);  // a few ULPs; Vulkan allows atan 4096
    EXPECT_FLOAT_EQ(k.upper_half_plane_angle(1.0f, 1.0f), float(M_PI / 4));
    EXPECT_FLOAT_EQ(k.upper_half_plane_angle(1.0f, 0.0f), float(M_PI / 2));
    EXPECT_FLOAT_EQ(k.upper_half_plane_angle(1.0f, -1.0f), float(3 * M_PI / 4));
}

}  // namespace
