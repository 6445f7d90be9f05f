// Glass of a metallic-roughness material (glTF's KHR_materials_transmission, _ior and
// _volume; kernel/lobes/glass.glsl, texture.glsl): the host and the kernel build the
// same material; a thin wall seen head-on under a white sky shows its closed form,
// F + (1 - F) base, and a slab of the same glass F + (1 - F) base^2 (its light is
// tinted going in and coming out, and reflected inside as often as it likes); a
// clear slab that absorbs (KHR_materials_volume) lets through what Beer and Lambert's
// law says, channel by channel; a specular layer (KHR_materials_specular) sets what
// the glass reflects; both backends.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <cstdint>
#include <string>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "flatten/flat_scene.hpp"
#include "cpu/cpu_backend.hpp"
#include "image/image.hpp"
#include "kernel/kernel.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using glm::vec3;

// The exact Fresnel reflectance of unpolarized light at normal incidence.
double fresnel_normal(double ior) {
    return std::pow((ior - 1.0) / (ior + 1.0), 2.0);
}

// A sheet of material `material` (quads of 4 x 4 around the view's axis, the first at
// z = 0 facing the camera, `back` more objects) seen head-on from (0, 0, 3) through a
// 6-degree view, under a white sky.
Scene sheet(const std::string& name, const std::string& material, const std::string& back = "") {
    return test::scene_from_text(name, fmt::format(R"({{
      "camera": {{ "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 6, "width": 16, "height": 12 }},
      "render": {{ "mode": "global", "spp": 128, "max_bounces": 64, "background": [1, 1, 1] }},
      "materials": {{ "glass": {} }},
      "objects": [
        {{ "type": "quad", "corner": [-2, -2, 0], "edge1": [4, 0, 0], "edge2": [0, 4, 0], "material": "glass" }}{}
      ]}})", material, back));
}

// The mean of a channel of the image and its standard error from the spread of the
// pixels (every pixel has the same expectation, within 1e-5 over this narrow view).
std::pair<double, double> mean_and_error(const Image& image, int channel) {
    const std::size_t n = std::size_t(image.width) * image.height;
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
        const double x = image.rgb[3 * p + channel];
        sum += x;
        sum2 += x * x;
    }
    const double mean = sum / double(n);
    return {mean, std::sqrt(std::max(0.0, (sum2 / double(n) - mean * mean) / double(n - 1)))};
}

// Each channel's image mean within 4 standard errors of `expected`, on both backends.
void expect_image_mean(const Scene& scene, glm::dvec3 expected) {
    for (const bool vulkan : {false, true}) {
        SCOPED_TRACE(vulkan ? "vulkan" : "cpu");
        const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
        EXPECT_EQ(out.stats.nonfinite_samples, 0u);
        EXPECT_EQ(out.stats.truncated_samples, 0u);
        for (int c = 0; c < 3; ++c) {
            const auto [mean, error] = mean_and_error(out.image, c);
            std::printf("%s %s channel %d: mean %.5f, standard error %.5f, expected %.5f\n",
                        scene.source.stem().c_str(), vulkan ? "vulkan" : "cpu", c, mean, error, expected[c]);
            EXPECT_GT(error, 0.0) << "the glass both reflects and transmits";
            EXPECT_NEAR(mean, expected[c], 4.0 * error + 1e-4) << "channel " << c << ", standard error " << error;
        }
    }
}

// The back face of a slab 0.2 thick behind sheet()'s front face.
const std::string kSlabBack = R"(,
        { "type": "quad", "corner": [-2, -2, -0.2], "edge1": [0, 4, 0], "edge2": [4, 0, 0], "material": "glass" })";

TEST(Transmission, AThinWallPassesItsBaseColourAndReflectsWhite) {
    const double f = fresnel_normal(1.5);
    expect_image_mean(sheet("thin_wall", R"({ "base_color": [0.5, 0.5, 0.5], "roughness": 0, "transmission": 1, "thin": true })"),
                      glm::dvec3(f + (1.0 - f) * 0.5));
}

TEST(Transmission, ASlabTintsGoingInAndComingOut) {
    const double ior = 1.8, f = fresnel_normal(ior);
    expect_image_mean(
        sheet("slab", R"({ "base_color": [0.5, 0.5, 0.5], "roughness": 0, "transmission": 1, "ior": 1.8 })", kSlabBack),
        glm::dvec3(f + (1.0 - f) * 0.25));
}

// A clear slab whose glass keeps T = attenuation_color^(0.2 / attenuation_distance)
// of the light crossing it once. Under the white sky it shows what it reflects and
// what it lets through: F + (1 - F)^2 T (1 + F T) / (1 - F^2 T^2), the sum over the
// light's passes inside, which is F + (1 - F)^2 T / (1 - F T). Red crosses half, green
// a quarter, blue all (a white channel: the slab without absorption, 1).
TEST(Transmission, AnAbsorbingSlabFollowsBeerAndLambert) {
    const double f = fresnel_normal(1.5);
    const auto seen = [f](double t) { return f + (1.0 - f) * (1.0 - f) * t / (1.0 - f * t); };
    const Scene scene = sheet("absorbing_slab", R"({ "base_color": [1, 1, 1], "roughness": 0, "transmission": 1,
        "attenuation_color": [0.5, 0.0625, 1], "attenuation_distance": 0.1 })", kSlabBack);
    const FlatScene flat = flatten_scene(scene);
    ASSERT_TRUE(flat.features.has(Feature::HAS_ABSORPTION));
    EXPECT_EQ(flat.materials.at(0).attenuation, vec3(float(std::log(2.0) / 0.1), float(std::log(16.0) / 0.1), 0.0f));
    expect_image_mean(scene, glm::dvec3(seen(0.25), seen(1.0 / 256.0), 1.0));
}

// glTF's specular layer on glass (KHR_materials_specular; glass.glsl glass_split): at
// normal incidence the glass reflects F0 = min(0.04 colour, 1) factor per channel and
// lets 1 - max(F0) through, tinted by the base colour b. A thin wall then shows
// F0 + (1 - max F0) b; a slab, whose faces reflect F0 = R and pass T = 1 - max R
// from either side, R + T^2 b^2 / (1 - R), the sum over the light's passes inside.
TEST(Transmission, TheSpecularLayerSetsTheGlassesReflectance) {
    const glm::dvec3 wall_f0(0.08, 0.02, 0.005);  // factor 0.5, colour (4, 1, 0.25)
    expect_image_mean(sheet("layered_wall", R"({ "base_color": [0.5, 0.5, 0.5], "roughness": 0, "transmission": 1,
        "thin": true, "specular_factor": 0.5, "specular_color": [4, 1, 0.25] })"),
                      wall_f0 + (1.0 - 0.08) * 0.5);
    const glm::dvec3 r(0.16, 0.04, 0.01);  // factor 1, colour (4, 1, 0.25)
    const double t = 1.0 - 0.16, b = 0.8;
    expect_image_mean(sheet("layered_slab", R"({ "base_color": [0.8, 0.8, 0.8], "roughness": 0, "transmission": 1,
        "specular_color": [4, 1, 0.25] })", kSlabBack),
                      r + t * t * b * b / (1.0 - r));
}

// A transmission texture multiplies the transmission by its red channel (glTF's
// transmissionTexture; the kernel rebuilds the material per hit): a white thin wall
// of transmission 1 with a texture of red 0.5 (exact in the EXR's half floats), in
// front of an emitter of radiance 1 and nothing else, shows 0.5 (1 - F) of it, the
// glass's share; with red 0 nothing. Nothing lights the wall's front, so its other
// lobes add nothing.
TEST(Transmission, ATransmissionTextureScalesTheGlass) {
    const std::filesystem::path dir = test::temp_dir("transmission_texture");
    for (const float red : {0.5f, 0.0f}) {
        SCOPED_TRACE(testing::Message() << "red " << red);
        Image texture(2, 2);
        for (std::size_t p = 0; p < 4; ++p) texture.rgb[3 * p] = red;
        const std::filesystem::path file = dir / fmt::format("red_{}.exr", red);
        write_image(texture, file);
        const Scene scene = test::scene_from_text("transmission_texture", fmt::format(R"({{
          "camera": {{ "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 6, "width": 16, "height": 12 }},
          "render": {{ "mode": "global", "spp": 64, "max_bounces": 8 }},
          "materials": {{ "wall": {{ "base_color": [1, 1, 1], "roughness": 0, "transmission": 1, "thin": true,
                                     "transmission_texture": "{}" }},
                          "lamp": {{ "emission": [1, 1, 1] }} }},
          "objects": [
            {{ "type": "quad", "corner": [-2, -2, 0], "edge1": [4, 0, 0], "edge2": [0, 4, 0], "material": "wall" }},
            {{ "type": "quad", "corner": [-2, -2, -1], "edge1": [4, 0, 0], "edge2": [0, 4, 0], "material": "lamp" }}
          ]}})", file.string()));
        ASSERT_TRUE(flatten_scene(scene).features.has(Feature::HAS_TEXTURES));
        const double f = fresnel_normal(1.5);
        if (red > 0.0f) {
            expect_image_mean(scene, glm::dvec3(0.5 * (1.0 - f)));
        } else {
            for (const bool vulkan : {false, true}) {
                const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
                EXPECT_EQ(*std::max_element(out.image.rgb.begin(), out.image.rgb.end()), 0.0f) << (vulkan ? "vulkan" : "cpu");
            }
        }
    }
    const std::string message = test::scene_error_of("transmission_texture_alone", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "materials": { "m": { "base_color": [1, 1, 1], "transmission_texture": "t.png" } },
      "objects": [{ "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" }]
    })");
    test::expect_error_message(message, "", {"materials.m.transmission_texture", "needs \"transmission\""});
}

// Attenuation is inside a solid: a thin wall refuses it, and glass that absorbs
// nothing (white, or no distance) leaves absorption compiled out.
TEST(Transmission, AbsorptionNeedsASolidThatAbsorbs) {
    const std::string message = test::scene_error_of("glass_thin_absorbs", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "materials": { "m": { "transmission": 1, "thin": true, "attenuation_distance": 1 } },
      "objects": [{ "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" }]
    })");
    test::expect_error_message(message, "", {"materials.m.attenuation_distance", "needs \"transmission\" and no \"thin\""});
    for (const char* clear : {R"("attenuation_color": [1, 1, 1], "attenuation_distance": 1)", R"("attenuation_color": [0.5, 1, 1])"}) {
        SCOPED_TRACE(clear);
        const Scene scene = sheet("clear_slab", fmt::format(R"({{ "transmission": 1, {} }})", clear), kSlabBack);
        const FlatScene flat = flatten_scene(scene);
        EXPECT_TRUE(flat.features.has(Feature::HAS_REFRACTION));
        EXPECT_FALSE(flat.features.has(Feature::HAS_ABSORPTION));
        EXPECT_EQ(flat.materials.at(0).attenuation, vec3(0.0f));
    }
}

// The host's material (flat_scene.cpp) is the one the kernel rebuilds at a textured
// hit (texture.glsl, set_metallic_roughness): glass takes transmission (1 - metallic),
// the metal keeps its share of the whole, the dielectric reflects ((ior - 1) /
// (ior + 1))^2.
TEST(Transmission, HostAndKernelBuildTheSameMaterial) {
    const Scene scene = test::scene_from_text("glass_material", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "render": { "mode": "global" },
      "materials": { "m": { "base_color": [0.8, 0.6, 0.4], "metallic": 0.5, "roughness": 0.3, "transmission": 0.5, "ior": 2 } },
      "objects": [{ "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" }]
    })");
    const FlatScene flat = flatten_scene(scene);
    ASSERT_TRUE(flat.features.has(Feature::HAS_REFRACTION));
    const kernel::Material host = flat.materials.at(0);
    EXPECT_FLOAT_EQ(host.transmission, 0.5f);
    EXPECT_FLOAT_EQ(host.dielectric_f0, float(1.0 / 9.0));
    EXPECT_EQ(host.thin_walled, 0u);
    const vec3 base(0.8f, 0.6f, 0.4f);
    // Glass 0.25 of the whole, the metal 0.5 of the whole: 2/3 of the other 0.75.
    const vec3 diffuse = base / 3.0f, transmit = 0.25f * base;
    const vec3 f0 = glm::mix(vec3(1.0f / 9.0f), base, 2.0f / 3.0f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(host.diffuse[c], diffuse[c], 1e-6f);
        EXPECT_NEAR(host.transmit[c], transmit[c], 1e-6f);
        EXPECT_NEAR(host.ggx_f0[c], f0[c], 1e-6f);
    }

    kernel::Kernel k = make_kernel(flat);
    kernel::Material rebuilt = host;
    k.set_metallic_roughness(rebuilt, base, 0.5f, 0.3f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(rebuilt.diffuse[c], host.diffuse[c], 1e-6f);
        EXPECT_NEAR(rebuilt.transmit[c], host.transmit[c], 1e-6f);
        EXPECT_NEAR(rebuilt.ggx_f0[c], host.ggx_f0[c], 1e-6f);
    }
    EXPECT_FLOAT_EQ(rebuilt.ggx_alpha, host.ggx_alpha);
    // The lobes split the material: glass 0.25, the smooth lobes the rest.
    const kernel::Kernel::Lobes lobes = k.material_lobes(rebuilt, vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(lobes.glass.weight, 0.25f);
    EXPECT_FLOAT_EQ(lobes.smooth_share, 0.75f);
    EXPECT_EQ(lobes.glass.reflected, vec3(0.25f));
    EXPECT_EQ(lobes.glass.color, host.transmit);
}

// Without global mode the glass is compiled out (local mode shades the material's
// diffuse lobe, as for every metallic-roughness material), and a "thin" without
// "transmission" is refused.
TEST(Transmission, LocalModeLeavesItOutAndThinNeedsTransmission) {
    const Scene local = test::scene_from_text("glass_local", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "materials": { "m": { "base_color": [1, 1, 1], "transmission": 1 } },
      "objects": [{ "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" }]
    })");
    EXPECT_FALSE(flatten_scene(local).features.has(Feature::HAS_REFRACTION));
    const std::string message = test::scene_error_of("glass_thin", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "materials": { "m": { "base_color": [1, 1, 1], "thin": true } },
      "objects": [{ "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" }]
    })");
    test::expect_error_message(message, "", {"materials.m.thin", "a thin wall needs \"transmission\""});
}

}  // namespace
}  // namespace vkrt
