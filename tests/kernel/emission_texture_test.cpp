// Emission textures (kernel/texture.glsl, shapes/triangle.glsl; the power estimate in
// host/flatten/flat_scene.cpp): an emitter seen directly shows its texels times its
// emission on both backends; lit by a textured emitter, a diffuse patch gets the
// closed-form irradiance, by next-event estimation with MIS and by BSDF sampling
// alone; a black texture is no light; glTF's emissiveTexture.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cpu/cpu_backend.hpp"
#include "flatten/flat_scene.hpp"
#include "image/image.hpp"
#include "image/image_files.hpp"
#include "kernel/kernel.hpp"
#include "scene/load_scene.hpp"
#include "scene/texture_image.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

// Two texels of A, then two of B, left to right (u): a texture whose texels i and
// 3 - i add to A + B, so that L(u) + L(1 - u) = A + B under bilinear filtering.
const glm::vec3 kA(2.0f, 0.5f, 0.25f);
const glm::vec3 kB(0.25f, 0.5f, 1.0f);

std::filesystem::path two_colour_texture(const std::string& name, glm::vec3 a = kA, glm::vec3 b = kB) {
    Image img(4, 1);
    for (std::uint32_t x = 0; x < 4; ++x) {
        const glm::vec3 c = x < 2 ? a : b;
        for (int k = 0; k < 3; ++k) img.pixel(x, 0)[k] = c[k];
    }
    const std::filesystem::path file = test::temp_dir("emission_texture_" + name) / (name + ".exr");
    write_image(img, file);
    return file;
}

// A quad emitter facing the camera at +z, emission (1.5, 1, 2) times the texture;
// u runs along +x. The tests' camera sees u from 0.125 to 0.375 (pure A: the
// texture repeats, so below 0.125 it blends into B) in pixel columns 1 to 4, and u
// from 0.625 to 0.875 (pure B) in 11 to 14.
TEST(EmissionTextureRender, AnEmitterSeenDirectlyShowsItsTexels) {
    const std::filesystem::path texture = two_colour_texture("direct");
    const glm::vec3 factor(1.5f, 1.0f, 2.0f);
    for (const std::string mode : {"local", "global"}) {
        SCOPED_TRACE(mode);
        const Scene scene = test::scene_from_text("direct_" + mode, R"({
          "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 16, "height": 16 },
          "render": { "mode": ")" + mode + R"(", "spp": 4, "background": [0, 0, 0] },
          "materials": { "lamp": { "emission": [1.5, 1, 2], "emission_texture": ")" + texture.string() + R"(" } },
          "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "lamp" } ]
        })");
        EXPECT_TRUE(flatten_scene(scene).features.has(Feature::HAS_TEXTURES));
        for (const bool vulkan : {false, true}) {
            const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
            for (std::uint32_t y = 2; y < 14; y += 5) {
                for (std::uint32_t x : {1u, 4u, 11u, 14u}) {
                    const glm::vec3 expected = factor * (x < 8 ? kA : kB);
                    for (int c = 0; c < 3; ++c) {
                        EXPECT_NEAR(out.image.pixel(x, y)[c], expected[c], 1e-5f)
                            << (vulkan ? "vulkan " : "cpu ") << x << "," << y << " channel " << c;
                    }
                }
            }
        }
    }
}

// The emitter's power is its area times the mean of emission times the texture's
// mean: (A + B) / 2 * (1.5, 1, 2) = (1.6875, 0.5, 1.25), mean 1.1458.., area 4.
TEST(EmissionTexture, PowerEstimateIsTheTexturesMean) {
    const std::filesystem::path texture = two_colour_texture("power");
    const Scene scene = test::scene_from_text("power", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "render": { "mode": "global" },
      "materials": { "lamp": { "emission": [1.5, 1, 2], "emission_texture": ")" + texture.string() + R"(" } },
      "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "lamp" } ]
    })");
    const FlatScene flat = flatten_scene(scene);
    ASSERT_EQ(flat.emitters.size(), 1u);
    const double mean = (1.6875 + 0.5 + 1.25) / 3.0;
    EXPECT_NEAR(kernel::emitter_power(flat.params), 4.0 * mean, 1e-5);
    // The quad's footprint is the whole texture: its record carries the same mean.
    EXPECT_NEAR(std::bit_cast<float>(flat.triangles.at(0).meta.w), mean, 1e-6);
}

// A black emission texture: the material emits nothing, and the quad is no light
// (the emitter list would be empty, so area lights are left out; nothing divides by
// its zero power).
TEST(EmissionTexture, ABlackTextureIsNoLight) {
    const std::filesystem::path texture = two_colour_texture("black", glm::vec3(0.0f), glm::vec3(0.0f));
    const Scene scene = test::scene_from_text("black", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 8, "height": 8 },
      "render": { "mode": "global", "spp": 4, "max_bounces": 2, "background": [0, 0, 0] },
      "materials": { "lamp": { "emission": [5, 5, 5], "emission_texture": ")" + texture.string() + R"(" },
                     "white": { "diffuse": [1, 1, 1] } },
      "objects": [ { "type": "quad", "corner": [-9, -9, -1], "edge1": [18, 0, 0], "edge2": [0, 18, 0], "material": "white" },
                   { "type": "quad", "corner": [-0.5, -0.5, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "lamp" } ]
    })");
    const FlatScene flat = flatten_scene(scene);
    EXPECT_TRUE(flat.emitters.empty());
    EXPECT_FALSE(flat.features.has(Feature::HAS_AREA_LIGHTS));
    const RenderOutcome out = test::render_cpu(scene);
    test::expect_sane(out);
    EXPECT_EQ(test::max_abs_difference(out.image, Image(8, 8)), 0.0f);
}

// The form factor from a point to a rectangle X d by Y d in a parallel plane at
// distance d, with a corner straight above the point.
double corner_form_factor(double x, double y) {
    const double a = std::sqrt(1.0 + x * x), b = std::sqrt(1.0 + y * y);
    return (x / a * std::atan(y / a) + y / b * std::atan(x / b)) / (2.0 * std::numbers::pi);
}

// Per channel, the mean over the image of the samples' radiance and its standard
// error (from the samples' variance per pixel, the pixels independent).
struct ChannelMeans {
    glm::dvec3 mean{0.0};
    glm::dvec3 standard_error{0.0};
};

ChannelMeans channel_means(const Scene& scene) {
    const FlatScene flat = flatten_scene(scene);
    kernel::Kernel k = make_kernel(flat);
    glm::dvec3 sum(0.0), variance(0.0);
    const double n = flat.samples_per_pixel;
    const double pixels = double(scene.camera.width) * scene.camera.height;
    for (std::uint32_t y = 0; y < scene.camera.height; ++y) {
        for (std::uint32_t x = 0; x < scene.camera.width; ++x) {
            glm::dvec3 s(0.0), s2(0.0);
            for (std::uint32_t i = 0; i < flat.samples_per_pixel; ++i) {
                const glm::dvec3 r(k.render_sample(x, y, i).radiance);
                s += r;
                s2 += r * r;
            }
            const glm::dvec3 mean = s / n;
            sum += mean;
            variance += glm::max(glm::dvec3(0.0), s2 / n - mean * mean) / (n - 1.0);
        }
    }
    return {sum / pixels, glm::sqrt(variance) / pixels};
}

// A small diffuse patch (albedo 0.5) at the origin facing +z, under an 8 x 8
// textured emitter at z = 1 facing it, centred over it; the camera between them
// looks down at the patch alone. By the texture's symmetry, L(y) + L(-y) = A + B,
// so the patch's radiance is albedo * (A + B) / 2 * F with F = 4 corner form factors
// of (4, 4), 0.9513: each estimator must agree with it, and next-event estimation
// (density from the texture's mean, radiance at the point drawn) with BSDF sampling
// alone (radiance at the point hit).
TEST(EmissionTextureRender, NeeAndBsdfSamplingAgreeWithTheClosedForm) {
    const std::filesystem::path texture = two_colour_texture("irradiance");
    Scene scene = test::scene_from_text("irradiance", R"({
      "camera": { "eye": [0, 0, 0.5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 8, "width": 8, "height": 8 },
      "render": { "mode": "global", "spp": 512, "max_bounces": 1, "background": [0, 0, 0] },
      "materials": { "lamp": { "emission": [1, 1, 1], "emission_texture": ")" + texture.string() + R"(" },
                     "patch": { "diffuse": [0.5, 0.5, 0.5] } },
      "objects": [ { "type": "quad", "corner": [-4, -4, 1], "edge1": [0, 8, 0], "edge2": [8, 0, 0], "material": "lamp" },
                   { "type": "quad", "corner": [-0.05, -0.05, 0], "edge1": [0.1, 0, 0], "edge2": [0, 0.1, 0], "material": "patch" } ]
    })");
    const double form_factor = 4.0 * corner_form_factor(4.0, 4.0);
    const glm::dvec3 expected = 0.5 * glm::dvec3(kA + kB) / 2.0 * form_factor;
    scene.render.nee = true;
    const ChannelMeans nee = channel_means(scene);
    scene.render.nee = false;
    const ChannelMeans bsdf = channel_means(scene);
    for (int c = 0; c < 3; ++c) {
        // The patch's own extent lowers its mean irradiance by about 1e-3 of it.
        const double bias = 2e-3 * expected[c];
        EXPECT_NEAR(nee.mean[c], expected[c], 4.0 * nee.standard_error[c] + bias) << "nee, channel " << c;
        EXPECT_NEAR(bsdf.mean[c], expected[c], 4.0 * bsdf.standard_error[c] + bias) << "bsdf, channel " << c;
        const double se = std::sqrt(nee.standard_error[c] * nee.standard_error[c] + bsdf.standard_error[c] * bsdf.standard_error[c]);
        EXPECT_LT(std::abs(nee.mean[c] - bsdf.mean[c]), 4.0 * se) << "channel " << c;
        std::printf("channel %d: expected %.5f, nee %.5f +- %.5f, bsdf %.5f +- %.5f\n", c, expected[c], nee.mean[c],
                    nee.standard_error[c], bsdf.mean[c], bsdf.standard_error[c]);
    }
}

// glTF's emissiveTexture, sRGB, times emissiveFactor times the emissive strength.
TEST(EmissionTextureGltf, EmissiveTextureMultipliesFactorAndStrength) {
    const std::filesystem::path dir = test::temp_dir("emission_texture_gltf");
    Image img(1, 1);
    img.pixel(0, 0)[0] = 0.5f;
    img.pixel(0, 0)[1] = 0.25f;
    img.pixel(0, 0)[2] = 1.0f;
    write_image(img, dir / "glow.png");
    const float positions[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
    const float uvs[6] = {0, 0, 1, 0, 0.5f, 1};
    std::ofstream bin(dir / "glow.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
    bin.write(reinterpret_cast<const char*>(uvs), sizeof uvs);
    bin.close();
    const std::filesystem::path file = dir / "glow.gltf";
    std::ofstream(file) << R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "extensionsUsed": ["KHR_materials_emissive_strength"],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
      "materials": [{"emissiveFactor": [1, 0.5, 1], "emissiveTexture": {"index": 0},
                     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}],
      "textures": [{"source": 0}],
      "images": [{"uri": "glow.png"}],
      "buffers": [{"byteLength": 60, "uri": "glow.bin"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]
    })";
    Scene scene = load_scene(file);
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    const Material& m = scene.materials.at(0);
    ASSERT_TRUE(m.emission_texture.has_value());
    EXPECT_EQ(m.emission, glm::dvec3(4.0, 2.0, 4.0));
    // sRGB-decoded: the PNG holds the encoded bytes of these linear values.
    const glm::vec4 t = texel_value(scene.textures.at(*m.emission_texture), scene.texels.words(), 0);
    EXPECT_NEAR(t.r, 0.5f, 3e-3f);
    EXPECT_NEAR(t.g, 0.25f, 3e-3f);
    test::view_quad_head_on(scene, 16, 4, 0.0);
    const Image image = test::render_cpu(scene).image;
    const float* p = image.pixel(8, 9);
    EXPECT_NEAR(p[0], 4.0f * t.r, 1e-2f);
    EXPECT_NEAR(p[1], 2.0f * t.g, 1e-2f);
    EXPECT_NEAR(p[2], 4.0f * t.b, 1e-2f);
}

TEST(EmissionTextureErrors, AMissingFileNamesTheMaterialAndTheFile) {
    const std::filesystem::path dir = test::temp_dir("emission_texture_errors");
    const std::string error = test::scene_error_of("bad_emission_texture", R"({
          "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
          "materials": { "m": { "emission": [1, 1, 1], "emission_texture": ")" + (dir / "absent.png").string() + R"(" } },
          "objects": [ { "type": "quad", "corner": [-1, 1, 0], "edge1": [2, 0, 0], "edge2": [0, -2, 0], "material": "m" } ]
        })");
    test::expect_error_message(error, "", {"materials.m.emission_texture", "absent.png", "no such file"});
}

}  // namespace
}  // namespace vkrt
