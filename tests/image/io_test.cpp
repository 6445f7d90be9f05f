// Image files through OpenImageIO: the extension picks the format, 8-bit formats
// are sRGB-encoded and clamped, float formats keep linear radiance; and the
// comparison's figures on images whose differences are known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "image/compare.hpp"
#include "image/image.hpp"
#include "test_support.hpp"

namespace {

using namespace vkrt;

std::filesystem::path temp_dir() {
    static const std::filesystem::path dir = test::temp_dir("image_io_test");
    return dir;
}

Image gradient() {
    Image img(4, 2);
    const float values[] = {0.0f, 0.001f, 0.18f, 0.5f, 1.0f, 2.5f, -1.0f, 0.75f};
    for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = values[i % 8] * (1.0f + float(i % 3) * 0.1f);
    return img;
}

TEST(ImageIo, SrgbTransferFunction) {
    EXPECT_EQ(linear_to_srgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linear_to_srgb(1.0f), 1.0f);
    EXPECT_FLOAT_EQ(linear_to_srgb(0.002f), 0.002f * 12.92f);  // the linear toe
    EXPECT_NEAR(linear_to_srgb(0.18f), 0.4614f, 1e-4);         // middle grey
    EXPECT_EQ(linear_to_srgb(7.0f), 1.0f);                     // clamped
    EXPECT_EQ(linear_to_srgb(-1.0f), 0.0f);
}

TEST(ImageIo, EightBitFormatsStoreClampedSrgb) {
    const Image img = gradient();
    for (const char* ext : {".png", ".ppm"}) {
        const auto file = temp_dir() / (std::string("g") + ext);
        write_image(img, file);
        const Image back = read_image(file);
        ASSERT_EQ(back.width, 4u);
        ASSERT_EQ(back.height, 2u);
        for (std::size_t i = 0; i < img.rgb.size(); ++i) {
            const float want = std::round(linear_to_srgb(img.rgb[i]) * 255.0f) / 255.0f;
            EXPECT_NEAR(back.rgb[i], want, 1e-6) << ext << " value " << i;
        }
    }
}

TEST(ImageIo, FloatFormatsKeepLinearRadiance) {
    const Image img = gradient();
    const auto exr = temp_dir() / "g.exr";
    write_image(img, exr);
    const Image back = read_image(exr);
    EXPECT_EQ(back.rgb, img.rgb);  // 32-bit float channels: exact, beyond 1 and below 0 too

    // Radiance HDR stores 8-bit mantissas under an exponent shared by the pixel's
    // channels (precision about 1% of the pixel's largest channel) and no sign:
    // negatives are written as 0.
    const auto hdr = temp_dir() / "g.hdr";
    write_image(img, hdr);
    const Image rgbe = read_image(hdr);
    for (std::size_t p = 0; p < 8; ++p) {
        const float* want = img.pixel(std::uint32_t(p % 4), std::uint32_t(p / 4));
        const float* got = rgbe.pixel(std::uint32_t(p % 4), std::uint32_t(p / 4));
        const float peak = std::max({want[0], want[1], want[2], 0.0f});
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(got[c], std::max(want[c], 0.0f), 0.01f * peak + 1e-6f) << "pixel " << p << " channel " << c;
        }
    }
}

TEST(ImageIo, UnknownFormatAndMissingFileAreClearErrors) {
    Image img(1, 1);
    try {
        write_image(img, temp_dir() / "x.notaformat");
        FAIL() << "no error";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("x.notaformat"), std::string::npos) << e.what();
    }
    try {
        read_image(temp_dir() / "missing.png");
        FAIL() << "no error";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.png: no such file"), std::string::npos) << e.what();
    }
}

TEST(Compare, FiguresOnKnownDifferences) {
    Image a(10, 10);
    Image b(10, 10);
    b.pixel(3, 4)[1] = 0.5f;     // one pixel, one channel off by 0.5
    b.pixel(7, 7)[0] = 0.0005f;  // under the threshold
    const ImageDiff d = compare_images(a, b, 1e-3);
    EXPECT_EQ(d.pixels, 100u);
    EXPECT_EQ(d.pixels_over, 1u);
    EXPECT_DOUBLE_EQ(d.max_abs, 0.5);
    EXPECT_NEAR(d.rmse, std::sqrt((0.25 + 0.0005 * 0.0005) / 300.0), 1e-12);
    EXPECT_NEAR(d.psnr, 10.0 * std::log10(1.0 / (d.rmse * d.rmse)), 1e-9);
    EXPECT_TRUE(std::isinf(compare_images(a, a).psnr));
    EXPECT_THROW(compare_images(a, Image(10, 9)), ImageError);
}

TEST(Compare, NanNeverHides) {
    Image a(2, 2);
    Image b(2, 2);
    b.rgb[4] = std::nanf("");
    const ImageDiff d = compare_images(a, b);
    EXPECT_EQ(d.pixels_over, 1u);
    EXPECT_TRUE(std::isinf(d.max_abs));
}

TEST(Compare, CommandExitsOneOverABound) {
    Image a(4, 4);
    Image b(4, 4);
    b.rgb[0] = 0.2f;
    write_image(a, temp_dir() / "a.exr");
    write_image(b, temp_dir() / "b.exr");
    const std::string base = "compare " + test::shell_quote((temp_dir() / "a.exr").string()) + " " +
                             test::shell_quote((temp_dir() / "b.exr").string());
    EXPECT_EQ(test::run_vkrt(base + " --max-abs 0.3", temp_dir()).code, 0);
    EXPECT_EQ(test::run_vkrt(base + " --max-abs 0.1", temp_dir()).code, 1);
    EXPECT_EQ(test::run_vkrt(base + " --max-rmse 0.01", temp_dir()).code, 1);
    // An unreadable image is an error, told apart from "over the bound".
    EXPECT_EQ(test::run_vkrt("compare " + test::shell_quote((temp_dir() / "none.exr").string()) + " " +
                                 test::shell_quote((temp_dir() / "a.exr").string()),
                             temp_dir())
                  .code,
              2);
}

}  // namespace
