// The layers' textures (kernel/texture.glsl, apply_layer_textures; glTF's
// clearcoatTexture, clearcoatRoughnessTexture, sheenColorTexture and
// sheenRoughnessTexture) and the specular ones (apply_specular_textures; glTF's
// specularTexture and specularColorTexture): a uniform texture of value t renders as
// the factor times t without the texture, on both backends; and the factor alone
// renders otherwise, so that the texture is seen to act.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "image/image.hpp"
#include "image/png_encode.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// A 2 x 2 PNG whose every texel is `rgba` (linear data, or sRGB for a colour).
std::string uniform_png(const std::string& name, std::array<std::uint8_t, 4> rgba) {
    std::vector<std::uint8_t> texels(16);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = rgba[i % 4];
    const std::vector<std::uint8_t> png = encode_png_rgba8(2, 2, texels);
    const std::filesystem::path file = test::temp_dir("layer_textures") / (name + ".png");
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    return file.string();
}

// A 2 x 2 OpenEXR of one linear colour.
std::string uniform_exr(const std::string& name, float r, float g, float b) {
    Image image(2, 2);
    for (std::size_t p = 0; p < 4; ++p) {
        image.rgb[3 * p] = r;
        image.rgb[3 * p + 1] = g;
        image.rgb[3 * p + 2] = b;
    }
    const std::filesystem::path file = test::temp_dir("layer_textures") / (name + ".exr");
    write_image(image, file);
    return file.string();
}

// A black Lambertian-free dielectric quad (specular 0: only its layers reflect) of
// the layers `layers`, seen at 45 degrees, a small lamp in its mirror direction,
// under a sky of 0.2. The specular cases give the dielectric's own fields in
// `layers`, and a base without them.
const char* const kLayersOnly = R"("base_color": [0, 0, 0], "specular_factor": 0, "roughness": 1)";
const char* const kBlackBase = R"("base_color": [0, 0, 0], "roughness": 0.5)";

Scene layered_quad(const std::string& name, const std::string& layers, const std::string& base) {
    return test::scene_from_text(name, fmt::format(R"({{
      "camera": {{ "eye": [0, 2, 2], "look_at": [0, 0, 0], "fov": 30, "width": 16, "height": 12 }},
      "render": {{ "mode": "global", "spp": 256, "max_bounces": 4, "background": [0.2, 0.2, 0.2] }},
      "materials": {{ "m": {{ {}, {} }},
                      "lamp": {{ "emission": [20, 20, 20] }} }},
      "objects": [
        {{ "type": "quad", "corner": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "m" }},
        {{ "type": "quad", "corner": [-0.2, 2, -2.2], "edge1": [0.4, 0, 0], "edge2": [0, 0.4, 0], "material": "lamp" }}
      ]}})", base, layers));
}

struct Mean {
    double value = 0.0, error = 0.0;
};

// The image mean over pixels and channels and its standard error from the pixels' spread.
Mean image_mean(const Image& image) {
    const std::size_t n = std::size_t(image.width) * image.height;
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
        const double v = (image.rgb[3 * p] + image.rgb[3 * p + 1] + image.rgb[3 * p + 2]) / 3.0;
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / double(n);
    return {mean, std::sqrt(std::max(0.0, (sum2 / double(n) - mean * mean) / double(n - 1)))};
}

// `textured` and `factored` agree within 4 combined standard errors on both backends,
// and `untextured` (the factor the texture scales) differs from `factored` by more.
void expect_texture_acts_as_factor(const std::string& name, const std::string& textured, const std::string& factored,
                                   const std::string& untextured, const std::string& base = kLayersOnly) {
    for (const bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "vulkan" : "cpu");
        const auto render = [&](const std::string& suffix, const std::string& layers) {
            const Scene scene = layered_quad(name + suffix, layers, base);
            const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
            EXPECT_EQ(out.stats.nonfinite_samples, 0u);
            return image_mean(out.image);
        };
        const Mean t = render("_textured", textured), f = render("_factored", factored), u = render("_untextured", untextured);
        std::printf("%s %s: textured %.5f (%.5f), factor %.5f (%.5f), without the texture %.5f (%.5f)\n", name.c_str(),
                    vulkan ? "vulkan" : "cpu", t.value, t.error, f.value, f.error, u.value, u.error);
        const double both = std::hypot(t.error, f.error);
        EXPECT_NEAR(t.value, f.value, 4.0 * both + 1e-4);
        EXPECT_GT(std::abs(u.value - f.value), 4.0 * std::hypot(u.error, f.error) + 1e-4) << "the texture acts";
    }
}

TEST(LayerTextures, CoatTextureScalesTheCoat) {
    const std::string half = uniform_png("coat_half", {128, 0, 0, 255});
    expect_texture_acts_as_factor("coat", fmt::format(R"("clearcoat": 1, "clearcoat_roughness": 0.3, "clearcoat_texture": "{}")", half),
                                  fmt::format(R"("clearcoat": {}, "clearcoat_roughness": 0.3)", 128.0 / 255.0),
                                  R"("clearcoat": 1, "clearcoat_roughness": 0.3)");
}

TEST(LayerTextures, CoatRoughnessTextureScalesTheRoughness) {
    const std::string half = uniform_png("coat_rough_half", {0, 128, 0, 255});
    expect_texture_acts_as_factor(
        "coat_roughness", fmt::format(R"("clearcoat": 1, "clearcoat_roughness": 0.6, "clearcoat_roughness_texture": "{}")", half),
        fmt::format(R"("clearcoat": 1, "clearcoat_roughness": {})", 0.6 * 128.0 / 255.0),
        R"("clearcoat": 1, "clearcoat_roughness": 0.6)");
}

TEST(LayerTextures, SheenColourTextureScalesTheColour) {
    const std::string colour = uniform_exr("sheen_colour", 0.5f, 0.25f, 1.0f);
    expect_texture_acts_as_factor("sheen_colour",
                                  fmt::format(R"("sheen_color": [1, 1, 1], "sheen_roughness": 0.5, "sheen_color_texture": "{}")", colour),
                                  R"("sheen_color": [0.5, 0.25, 1], "sheen_roughness": 0.5)",
                                  R"("sheen_color": [1, 1, 1], "sheen_roughness": 0.5)");
}

TEST(LayerTextures, SheenRoughnessTextureScalesTheRoughness) {
    const std::string half = uniform_png("sheen_rough_half", {0, 0, 0, 128});
    expect_texture_acts_as_factor(
        "sheen_roughness", fmt::format(R"("sheen_color": [1, 1, 1], "sheen_roughness": 1, "sheen_roughness_texture": "{}")", half),
        fmt::format(R"("sheen_color": [1, 1, 1], "sheen_roughness": {})", 128.0 / 255.0),
        R"("sheen_color": [1, 1, 1], "sheen_roughness": 1)");
}

TEST(SpecularTextures, SpecularTextureScalesTheFactor) {
    const std::string half = uniform_png("specular_half", {0, 0, 0, 128});
    expect_texture_acts_as_factor("specular", fmt::format(R"("specular_factor": 1, "specular_texture": "{}")", half),
                                  fmt::format(R"("specular_factor": {})", 128.0 / 255.0), R"("specular_factor": 1)",
                                  kBlackBase);
}

TEST(SpecularTextures, SpecularColourTextureScalesTheColour) {
    const std::string colour = uniform_exr("specular_colour", 4.0f, 1.0f, 0.25f);
    expect_texture_acts_as_factor(
        "specular_colour", fmt::format(R"("specular_color": [1, 2, 2], "specular_color_texture": "{}")", colour),
        R"("specular_color": [4, 2, 0.5])", R"("specular_color": [1, 2, 2])", kBlackBase);
}

}  // namespace
}  // namespace vkrt
