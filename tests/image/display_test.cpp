// How 8-bit outputs show the linear image (image/display.hpp): the exposure, the
// tone curves, the float formats left alone, and the scene file's and command
// line's ways to ask for them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "image/display.hpp"
#include "image/image.hpp"
#include "scene/load_scene.hpp"
#include "scene/scene_error.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using vkrt::Display;
using vkrt::Image;
using vkrt::Tonemap;

TEST(Display, DefaultIsTheClampedSrgbEncoding) {
    Image image(4, 1);
    image.rgb = {0.0f, 0.5f, 1.0f, 2.0f, -1.0f, 0.0031308f, 0.25f, 1e30f, 0.5f, 0.0f, 0.0f, 0.0f};
    const std::vector<std::uint8_t> bytes = vkrt::to_srgb8(image);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        const float clamped = std::min(std::max(image.rgb[i], 0.0f), 1.0f);
        EXPECT_EQ(bytes[i], std::lround(vkrt::linear_to_srgb(clamped) * 255.0f)) << i;
    }
    EXPECT_EQ(bytes[1], 188);  // 0.5 linear
}

TEST(Display, ExposureScalesByPowersOfTwo) {
    const Display up{1.0, Tonemap::None};
    const Display down{-2.0, Tonemap::None};
    EXPECT_EQ(vkrt::display_value(0.25f, up), 0.5f);
    EXPECT_EQ(vkrt::display_value(2.0f, down), 0.5f);
    EXPECT_EQ(vkrt::display_value(0.75f, up), 1.0f);  // clamped
}

TEST(Display, FilmicCurveRisesFromZeroToOne) {
    const Display filmic{0.0, Tonemap::Filmic};
    EXPECT_EQ(vkrt::display_value(0.0f, filmic), 0.0f);
    // x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) at 0.18 and 1, worked out by hand.
    EXPECT_NEAR(vkrt::display_value(0.18f, filmic), 0.266898, 1e-5);
    EXPECT_NEAR(vkrt::display_value(1.0f, filmic), 0.803797, 1e-5);
    float last = 0.0f;
    for (float x = 0.001f; x < 20.0f; x *= 1.1f) {
        const float y = vkrt::display_value(x, filmic);
        EXPECT_GE(y, last) << x;
        EXPECT_LE(y, 1.0f) << x;
        last = y;
    }
    EXPECT_EQ(vkrt::display_value(1e6f, filmic), 1.0f);
    EXPECT_EQ(vkrt::display_value(std::numeric_limits<float>::infinity(), filmic), 1.0f);
    EXPECT_EQ(vkrt::display_value(std::numeric_limits<float>::quiet_NaN(), filmic), 0.0f);
    EXPECT_EQ(vkrt::display_value(-3.0f, filmic), 0.0f);
}

TEST(Display, FloatFormatsStayLinearAndPngTakesTheCurve) {
    const fs::path dir = vkrt::test::temp_dir("display_files");
    Image image(3, 2);
    for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = 0.37f * float(i);
    const Display display{1.5, Tonemap::Filmic};
    vkrt::write_image(image, dir / "linear.exr", display);
    EXPECT_EQ(vkrt::read_image(dir / "linear.exr").rgb, image.rgb);
    vkrt::write_image(image, dir / "shown.png", display);
    const Image shown = vkrt::read_image(dir / "shown.png");
    const std::vector<std::uint8_t> bytes = vkrt::to_srgb8(image, display);
    ASSERT_EQ(shown.rgb.size(), bytes.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) EXPECT_EQ(std::lround(shown.rgb[i] * 255.0f), bytes[i]) << i;
}

std::string scene_text(const std::string& render) {
    return R"({"camera": {"eye": [0, 0, 3], "look_at": [0, 0, 0]}, "render": )" + render +
           R"(, "materials": {"m": {"diffuse": [1, 1, 1]}},
              "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
}

TEST(Display, SceneFileSetsExposureAndToneMap) {
    const vkrt::Scene s = vkrt::test::scene_from_text("display", scene_text(R"({"exposure": -1.5, "tonemap": "filmic"})"));
    EXPECT_EQ(s.render.display.exposure, -1.5);
    EXPECT_EQ(s.render.display.tonemap, Tonemap::Filmic);
    const vkrt::Scene d = vkrt::test::scene_from_text("display_default", scene_text("{}"));
    EXPECT_EQ(d.render.display.exposure, 0.0);
    EXPECT_EQ(d.render.display.tonemap, Tonemap::None);
}

TEST(Display, SceneFileRefusesBadValues) {
    auto message = [](const std::string& render) {
        try {
            vkrt::test::scene_from_text("display_bad", scene_text(render));
        } catch (const vkrt::SceneError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    const std::string curve = message(R"({"tonemap": "aces"})");
    EXPECT_NE(curve.find("render.tonemap: unknown tone map 'aces' (expected \"none\" or \"filmic\")"), std::string::npos)
        << curve;
    const std::string stops = message(R"({"exposure": 100})");
    EXPECT_NE(stops.find("render.exposure: expected a number of stops from -64 to 64, got 100"), std::string::npos)
        << stops;
}

}  // namespace
