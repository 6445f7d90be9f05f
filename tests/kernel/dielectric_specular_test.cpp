// The dielectric's specular layer (glTF's KHR_materials_specular; scene.hpp,
// kernel/lobes/fresnel.glsl): the host writes the layer's reflectance at normal and
// grazing incidence and turns HAS_DIELECTRIC_SPECULAR on only for scenes that have
// one; under a white sky a plane whose layer has a strength of 0 shows its base colour
// (it is Lambertian), and a white plane shows 1 whatever its layer (the diffuse lobe
// takes what the layer leaves); both backends.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "flatten/flat_scene.hpp"
#include "kernel/kernel.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// A quad of material `material` filling a 6-degree view head-on, under a white sky.
Scene plane(const std::string& name, const std::string& material) {
    return test::scene_from_text(name, fmt::format(R"({{
      "camera": {{ "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 6, "width": 16, "height": 12 }},
      "render": {{ "mode": "global", "spp": 64, "max_bounces": 4, "background": [1, 1, 1] }},
      "materials": {{ "m": {} }},
      "objects": [ {{ "type": "quad", "corner": [-2, -2, 0], "edge1": [4, 0, 0], "edge2": [0, 4, 0], "material": "m" }} ]
    }})", material));
}

// Each channel's image mean within 4 standard errors (from the spread of the pixels)
// of `expected`, on both backends.
void expect_mean(const Scene& scene, glm::dvec3 expected) {
    for (const bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "vulkan" : "cpu");
        const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
        EXPECT_EQ(out.stats.nonfinite_samples, 0u);
        const std::size_t n = std::size_t(out.image.width) * out.image.height;
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0, sum2 = 0.0;
            for (std::size_t p = 0; p < n; ++p) {
                sum += out.image.rgb[3 * p + c];
                sum2 += double(out.image.rgb[3 * p + c]) * out.image.rgb[3 * p + c];
            }
            const double mean = sum / double(n);
            const double error = std::sqrt(std::max(0.0, (sum2 / double(n) - mean * mean) / double(n - 1)));
            std::printf("%s %s channel %d: mean %.5f, standard error %.5f, expected %.5f\n", scene.source.stem().c_str(),
                        vulkan ? "vulkan" : "cpu", c, mean, error, expected[c]);
            EXPECT_NEAR(mean, expected[c], 4.0 * error + 2e-3) << "channel " << c;
        }
    }
}

TEST(DielectricSpecular, TheHostWritesTheLayerAndItsFeature) {
    const FlatScene plain = flatten_scene(plane("plain", R"({ "base_color": [0.5, 0.5, 0.5], "roughness": 0.5 })"));
    EXPECT_FALSE(plain.features.has(Feature::HAS_DIELECTRIC_SPECULAR));
    const FlatScene layered = flatten_scene(plane("layered", R"({ "base_color": [0.5, 0.5, 0.5], "metallic": 0.5,
        "roughness": 0.5, "specular_factor": 0.5, "specular_color": [2, 1, 40] })"));
    ASSERT_TRUE(layered.features.has(Feature::HAS_DIELECTRIC_SPECULAR));
    const kernel::Material& m = layered.materials.at(0);
    EXPECT_EQ(m.dielectric_f0_rgb, glm::vec3(0.04f, 0.02f, 0.5f));  // min(0.04 colour, 1) / 2
    EXPECT_EQ(m.dielectric_f90, 0.5f);
    EXPECT_FLOAT_EQ(m.ggx_f90, 0.75f);  // half metal (f90 1), half dielectric
    EXPECT_FLOAT_EQ(m.ggx_f0.x, 0.5f * 0.04f + 0.5f * 0.5f);
}

TEST(DielectricSpecular, WithoutALayerTheDielectricIsLambertian) {
    expect_mean(plane("no_layer", R"({ "base_color": [0.5, 0.25, 1], "roughness": 0.3, "specular_factor": 0 })"),
                glm::dvec3(0.5, 0.25, 1.0));
}

TEST(DielectricSpecular, AWhiteBaseKeepsTheLightUnderAnyLayer) {
    expect_mean(plane("white_base", R"({ "base_color": [1, 1, 1], "roughness": 0.6, "specular_factor": 0.7,
                                         "specular_color": [20, 1, 0.1] })"),
                glm::dvec3(1.0));
}

}  // namespace
}  // namespace vkrt
