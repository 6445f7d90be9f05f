// `vkrt compare`'s metrics and difference image (host/image/error_metrics.hpp,
// ssim.hpp, error_image.hpp): exact values on small images, SSIM against its closed
// form where the windows are uniform, and the colour map's ends and middle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "image/error_image.hpp"
#include "image/error_metrics.hpp"
#include "image/ssim.hpp"
#include "uniform_image.hpp"

namespace vkrt {
namespace {

using test::uniform_image;

TEST(CompareMetrics, MaeMseRmseAndRelMseOfAKnownDifference) {
    // Two pixels: channels differ by 0.1 (reference 0.5) and by 0.3 (reference 0).
    Image a(2, 1), b(2, 1);
    for (int c = 0; c < 3; ++c) {
        a.rgb[c] = 0.6f;
        b.rgb[c] = 0.5f;
        a.rgb[3 + c] = 0.3f;
        b.rgb[3 + c] = 0.0f;
    }
    const ErrorMetrics m = error_metrics(a, b);
    const double d1 = double(0.6f) - double(0.5f), d2 = double(0.3f);
    EXPECT_DOUBLE_EQ(m.mae, (d1 + d2) / 2.0);
    EXPECT_DOUBLE_EQ(m.mse, (d1 * d1 + d2 * d2) / 2.0);
    EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(m.mse));
    EXPECT_DOUBLE_EQ(m.relmse, (d1 * d1 / (0.25 + 0.01) + d2 * d2 / 0.01) / 2.0);
}

TEST(CompareMetrics, SsimOfAnImageWithItselfIsOne) {
    Image a(16, 12);
    for (std::size_t i = 0; i < a.rgb.size(); ++i) a.rgb[i] = float((i * 37) % 101) / 100.0f;
    EXPECT_EQ(ssim(a, a), 1.0);
}

// Uniform images have no contrast or structure in any window: the contrast and
// structure terms are C2 / C2, and SSIM is the luminance term (2 a b + C1) / (a^2 +
// b^2 + C1), C1 = 1e-4.
TEST(CompareMetrics, SsimOfUniformImagesIsTheLuminanceTerm) {
    for (const auto& [x, y] : {std::pair{0.5f, 0.25f}, std::pair{0.0f, 1.0f}, std::pair{0.8f, 0.8f}}) {
        const double a = x, b = y, c1 = 1e-4;
        EXPECT_NEAR(ssim(uniform_image(12, 11, x), uniform_image(12, 11, y)), (2 * a * b + c1) / (a * a + b * b + c1), 1e-12);
    }
    // Values beyond the display range count as its ends.
    EXPECT_NEAR(ssim(uniform_image(11, 11, 7.0f), uniform_image(11, 11, 1.0f)), 1.0, 1e-12);
}

// Opposite structure: a pattern against its negation around the same mean gives a
// structure term of -1 (luminance and contrast terms are 1), so SSIM is near -1.
TEST(CompareMetrics, SsimOfAPatternAndItsNegationIsNegative) {
    Image a(11, 11), b(11, 11);
    for (std::uint32_t y = 0; y < 11; ++y) {
        for (std::uint32_t x = 0; x < 11; ++x) {
            const float v = (x + y) % 2 ? 0.9f : 0.1f;
            for (int c = 0; c < 3; ++c) {
                a.pixel(x, y)[c] = v;
                b.pixel(x, y)[c] = 1.0f - v;
            }
        }
    }
    const double s = ssim(a, b);
    EXPECT_LT(s, -0.99);
    EXPECT_EQ(s, ssim(b, a)) << "symmetric";
}

TEST(CompareMetrics, SsimRefusesImagesSmallerThanItsWindow) {
    try {
        (void)ssim(uniform_image(10, 20, 0.5f), uniform_image(10, 20, 0.5f));
        FAIL() << "no error";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("at least 11 x 11 pixels"), std::string::npos) << e.what();
    }
}

// The map's ends at -range and +range (and beyond), near-white where the images
// agree, black for NaN; the difference is the mean of the channels.
TEST(DifferenceImage, TheColourMapRunsFromBlueThroughWhiteToRed) {
    Image a(5, 1), b = uniform_image(5, 1, 0.5f);
    const float values[5] = {0.5f, 0.25f, 1.0f, 0.0f, std::numeric_limits<float>::quiet_NaN()};
    for (int p = 0; p < 5; ++p) {
        for (int c = 0; c < 3; ++c) a.rgb[3 * p + c] = values[p];
    }
    EXPECT_DOUBLE_EQ(largest_signed_difference(a, b), 0.5);
    const std::vector<std::uint8_t> rgba = difference_rgba8(a, b, 0.25);
    const auto pixel = [&](int p) { return std::vector<int>{rgba[4 * p], rgba[4 * p + 1], rgba[4 * p + 2], rgba[4 * p + 3]}; };
    EXPECT_EQ(pixel(0), (std::vector<int>{242, 242, 242, 255}));
    EXPECT_EQ(pixel(1), (std::vector<int>{59, 76, 192, 255})) << "-range";
    EXPECT_EQ(pixel(2), (std::vector<int>{180, 4, 38, 255})) << "beyond +range";
    EXPECT_EQ(pixel(3), (std::vector<int>{59, 76, 192, 255})) << "beyond -range";
    EXPECT_EQ(pixel(4), (std::vector<int>{0, 0, 0, 255})) << "NaN";
    // Half way to +range: half way from white to red.
    const std::vector<std::uint8_t> half = difference_rgba8(uniform_image(1, 1, 0.625f), uniform_image(1, 1, 0.5f), 0.25);
    EXPECT_EQ(int(half[0]), 211);  // 242 + (180 - 242) / 2
    EXPECT_EQ(int(half[1]), 123);  // 242 + (4 - 242) / 2
    EXPECT_EQ(int(half[2]), 140);  // 242 + (38 - 242) / 2
}

}  // namespace
}  // namespace vkrt
