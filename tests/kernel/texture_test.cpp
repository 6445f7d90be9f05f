// Colour textures (shaders/kernel/texture.glsl, host/scene/texture_image.cpp): the
// sRGB decoding, bilinear filtering and wrap modes with exact values through the
// reference kernel, the coordinate transform, a textured quad on both backends,
// a distant fine checkerboard, and bad texture input.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "flatten/flat_scene.hpp"
#include "image/image.hpp"
#include "kernel/kernel.hpp"
#include "scene/load_scene.hpp"
#include "scene/texture_image.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::Kernel;
using kernel::uvec4;
using kernel::vec2;
using kernel::vec4;

TEST(Texture, SrgbDecodesByTheStandardsCurve) {
    EXPECT_EQ(srgb_to_linear(0.0), 0.0);
    EXPECT_DOUBLE_EQ(srgb_to_linear(1.0), 1.0);
    EXPECT_DOUBLE_EQ(srgb_to_linear(0.04045), 0.04045 / 12.92);
    EXPECT_NEAR(srgb_to_linear(0.5), 0.214041140, 1e-9);
    // The two pieces meet at the knee.
    EXPECT_NEAR(srgb_to_linear(0.04045 + 1e-12), srgb_to_linear(0.04045), 1e-7);
}

// A kernel reading one texture of the given texels (row-major from the top).
struct OneTexture {
    std::vector<kernel::Texture> records;
    std::vector<std::uint32_t> words;
    Kernel k;

    OneTexture(std::uint32_t w, std::uint32_t h, const std::vector<vec4>& texels, std::uint32_t wrap) {
        records.push_back(kernel::Texture(uvec4(0u, w, h, wrap), kernel::vec4(0.0f)));
        for (const vec4& c : texels) {
            words.push_back(glm::packHalf2x16(vec2(c.r, c.g)));
            words.push_back(glm::packHalf2x16(vec2(c.b, c.a)));
        }
        k.textures = records;
        k.texture_words = words;
    }
    float at(float u, float v) { return k.texture_bilinear(k.load_texture(0), vec2(u, v)).r; }
};

// A 2 x 2 texture of 0, 1 / 2, 3 (red channel): texel centres at 1/4 and 3/4.
std::vector<vec4> two_by_two() { return {vec4(0, 0, 0, 1), vec4(1, 0, 0, 1), vec4(2, 0, 0, 1), vec4(3, 0, 0, 1)}; }

TEST(Texture, BilinearIsExactAtCentresAndBetweenThem) {
    OneTexture t(2, 2, two_by_two(), kernel::WRAP_CLAMP | (kernel::WRAP_CLAMP << 2u));
    EXPECT_EQ(t.at(0.25f, 0.25f), 0.0f);
    EXPECT_EQ(t.at(0.75f, 0.25f), 1.0f);
    EXPECT_EQ(t.at(0.25f, 0.75f), 2.0f);
    EXPECT_EQ(t.at(0.75f, 0.75f), 3.0f);
    EXPECT_EQ(t.at(0.5f, 0.5f), 1.5f);
    EXPECT_EQ(t.at(0.5f, 0.25f), 0.5f);
    EXPECT_EQ(t.at(0.375f, 0.25f), 0.25f);
    // Clamped: beyond the edge the edge texels continue.
    EXPECT_EQ(t.at(0.0f, 0.25f), 0.0f);
    EXPECT_EQ(t.at(-3.0f, 0.75f), 2.0f);
    EXPECT_EQ(t.at(7.0f, 7.0f), 3.0f);
}

TEST(Texture, RepeatAndMirrorWrapAsTheirNamesSay) {
    OneTexture repeat(2, 2, two_by_two(), kernel::WRAP_REPEAT | (kernel::WRAP_REPEAT << 2u));
    // Half way between the last texel and the first again.
    EXPECT_EQ(repeat.at(1.0f, 0.25f), 0.5f);
    EXPECT_EQ(repeat.at(0.0f, 0.25f), 0.5f);
    EXPECT_EQ(repeat.at(1.25f, 0.25f), 0.0f);
    EXPECT_EQ(repeat.at(-0.25f, 0.25f), 1.0f);
    EXPECT_EQ(repeat.at(-100.75f, 1000.25f), 0.0f);
    OneTexture mirror(2, 2, two_by_two(), kernel::WRAP_MIRROR | (kernel::WRAP_MIRROR << 2u));
    // Across the edge the image continues reflected: the edge texel twice.
    EXPECT_EQ(mirror.at(1.0f, 0.25f), 1.0f);
    EXPECT_EQ(mirror.at(1.25f, 0.25f), 1.0f);
    EXPECT_EQ(mirror.at(1.75f, 0.25f), 0.0f);
    EXPECT_EQ(mirror.at(-0.25f, 0.25f), 0.0f);
    EXPECT_EQ(mirror.at(2.25f, 0.25f), 0.0f);
    // Coordinates that are not finite read a texel, never outside the texture.
    EXPECT_TRUE(std::isfinite(repeat.at(NAN, INFINITY)));
    EXPECT_TRUE(std::isfinite(mirror.at(-INFINITY, 1e38f)));
}

// A metallic-roughness material rebuilt from its factors times its textures: base
// colour times the colour texture, metallic times blue, roughness times green.
TEST(Texture, MetallicRoughnessTexturesScaleTheFactors) {
    Kernel k;
    const std::vector<kernel::Texture> records = {kernel::Texture(uvec4(0u, 1u, 1u, 0u), kernel::vec4(0.0f)),
                                                  kernel::Texture(uvec4(2u, 1u, 1u, 0u), kernel::vec4(0.0f))};
    const std::vector<std::uint32_t> words = {glm::packHalf2x16(vec2(0.5f, 1.0f)), glm::packHalf2x16(vec2(0.25f, 1.0f)),
                                              glm::packHalf2x16(vec2(1.0f, 0.5f)), glm::packHalf2x16(vec2(0.375f, 1.0f))};
    k.textures = records;
    k.texture_words = words;
    // Factors: base (0.8, 0.6, 0.4), metallic 0.5, roughness 0.6 (as flat_scene.cpp writes them).
    kernel::Material pbr{};
    pbr.diffuse = glm::vec3(0.4f, 0.3f, 0.2f);
    pbr.kd = 1.0f;
    pbr.ior = 1.5f;
    pbr.ggx_f0 = glm::vec3(0.42f, 0.32f, 0.22f);
    pbr.dielectric_f0 = 0.04f;
    pbr.dielectric_f0_rgb = glm::vec3(0.04f);
    pbr.dielectric_f90 = 1.0f;
    pbr.ggx_f90 = 1.0f;
    pbr.ggx_alpha = 0.36f;
    pbr.color_map = 1u;
    pbr.metal_rough_map = 2u;
    pbr.uv_u = glm::vec3(1.0f, 0.0f, 0.0f);
    pbr.uv_v = glm::vec3(0.0f, 1.0f, 0.0f);
    pbr.base_color = glm::vec3(0.8f, 0.6f, 0.4f);
    pbr.metallic = 0.5f;
    pbr.roughness = 0.6f;
    const std::vector<kernel::Material> materials = {pbr};
    k.materials = materials;
    // The triangle hit: its record says it has no vertex colours.
    const std::vector<kernel::Triangle> triangles(1);
    k.triangles = triangles;
    Kernel::Hit hit = k.no_hit();
    hit.material = 0u;
    hit.prim = kernel::REF_TRIANGLE << kernel::REF_KIND_SHIFT;
    hit.uv = vec2(0.5f, 0.5f);
    const kernel::Material m = k.surface_material(hit);
    // metallic 0.5 * 0.375, roughness 0.6 * 0.5; base (0.4, 0.6, 0.1).
    const float metallic = 0.1875f, alpha = 0.09f;
    const glm::vec3 base(0.4f, 0.6f, 0.1f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(m.diffuse[c], (1.0f - metallic) * base[c], 1e-6f) << c;
        EXPECT_NEAR(m.ggx_f0[c], 0.04f + (base[c] - 0.04f) * metallic, 1e-6f) << c;
    }
    EXPECT_EQ(m.kd, 1.0f);
    EXPECT_NEAR(m.ggx_alpha, alpha, 1e-6f);
    // On a sphere the factors stand.
    hit.prim = kernel::REF_SPHERE << kernel::REF_KIND_SHIFT;
    EXPECT_EQ(k.surface_material(hit).ggx_alpha, 0.36f);
}

TEST(Texture, TransformFollowsKhrTextureTransform) {
    // The extension's example: offset (0, 1), a quarter turn, scale 1/2 shows the
    // image's lower left quadrant (v runs down), turned clockwise.
    const auto m = texture_transform(0.0, 1.0, std::numbers::pi / 2.0, 0.5, 0.5);
    const auto apply = [&](double u, double v) { return glm::dvec2(m[0] * u + m[1] * v + m[2], m[3] * u + m[4] * v + m[5]); };
    const glm::dvec2 a = apply(0, 0), b = apply(1, 0), c = apply(1, 1);
    EXPECT_NEAR(a.x, 0.0, 1e-12);
    EXPECT_NEAR(a.y, 1.0, 1e-12);
    EXPECT_NEAR(b.x, 0.0, 1e-12);
    EXPECT_NEAR(b.y, 0.5, 1e-12);
    EXPECT_NEAR(c.x, 0.5, 1e-12);
    EXPECT_NEAR(c.y, 0.5, 1e-12);
}

// The four quadrants of quadrant_texture: red, green / blue, grey (top left, top
// right / bottom left, bottom right); and where a 32 x 32 view of a quad that
// spans 2 / (2 tan 15 deg 3) = 1.24 of it (the tests' camera) sees each quadrant's
// middle, 4 pixels from each edge.
constexpr float kQuadrants[4][3] = {{0.8f, 0.1f, 0.1f}, {0.1f, 0.7f, 0.2f}, {0.2f, 0.3f, 0.9f}, {0.5f, 0.5f, 0.5f}};
constexpr std::uint32_t kQuadrantPixels[4][2] = {{8, 8}, {23, 8}, {8, 23}, {23, 23}};

// Each quadrant's middle pixel holds `quadrant(q)`'s colour within `tolerance`.
template <class Quadrant>
void expect_quadrants(const Image& image, Quadrant quadrant, float tolerance, const char* what) {
    for (int q = 0; q < 4; ++q) {
        const float* v = image.pixel(kQuadrantPixels[q][0], kQuadrantPixels[q][1]);
        const float* expected = kQuadrants[quadrant(q)];
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], expected[c], tolerance) << what << ", quadrant " << q << " channel " << c;
    }
}

// Writes a linear float texture of the four quadrants, each 4 x 4 texels.
std::filesystem::path quadrant_texture(const std::string& name) {
    Image img(8, 8);
    for (std::uint32_t y = 0; y < 8; ++y) {
        for (std::uint32_t x = 0; x < 8; ++x) {
            const float* c = kQuadrants[(y / 4) * 2 + x / 4];
            std::copy(c, c + 3, img.pixel(x, y));
        }
    }
    const std::filesystem::path file = test::temp_dir("texture") / (name + ".exr");
    write_image(img, file);
    return file;
}

// Under a white sky a Lambertian quad, alone, shows its albedo: here the texture's
// colour, exactly, wherever a pixel's samples stay inside one quadrant (bilinear
// filtering of equal texels), on both backends.
TEST(TextureRender, ATexturedQuadUnderAWhiteSkyShowsTheTexture) {
    const std::filesystem::path texture = quadrant_texture("quadrants");
    const Scene scene = test::scene_from_text("textured_quad", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 32, "height": 32 },
      "render": { "mode": "global", "spp": 4, "max_bounces": 2, "background": [1, 1, 1] },
      "materials": { "m": { "diffuse": [1, 1, 1], "texture": ")" + texture.string() + R"(" } },
      "objects": [ { "type": "quad", "corner": [-1, 1, 0], "edge1": [2, 0, 0], "edge2": [0, -2, 0], "material": "m" } ]
    })");
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_TRUE(flatten_scene(scene).features.has(Feature::HAS_TEXTURES));
    for (const bool vulkan : {false, true}) {
        const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
        // The texels are half floats.
        expect_quadrants(out.image, [](int q) { return q; }, 1e-3f, vulkan ? "vulkan" : "cpu");
    }
}

// Spheres have no texture coordinates: a textured material shows its colour there.
TEST(TextureRender, ASphereKeepsTheUntexturedColour) {
    const std::filesystem::path texture = quadrant_texture("on_a_sphere");
    const Scene scene = test::scene_from_text("textured_sphere", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 16, "height": 16 },
      "render": { "mode": "global", "spp": 4, "max_bounces": 2, "background": [1, 1, 1] },
      "materials": { "m": { "diffuse": [0.5, 0.5, 0.5], "texture": ")" + texture.string() + R"(" } },
      "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "m" },
                   { "type": "quad", "corner": [-9, -9, -5], "edge1": [0, 1, 0], "edge2": [1, 0, 0], "material": "m" } ]
    })");
    for (const bool vulkan : {false, true}) {
        const RenderOutcome out = vulkan ? test::render_vulkan(scene) : test::render_cpu(scene);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(out.image.pixel(8, 8)[c], 0.5f, 1e-5f) << (vulkan ? "vulkan" : "cpu");
    }
}

// No mipmaps: a pixel's jittered samples spread over its footprint, so a checkerboard
// far finer than the pixels averages to its mean rather than aliasing into patterns.
TEST(TextureRender, AFineCheckerboardFarAwayAveragesToGrey) {
    Image img(256, 256);
    for (std::uint32_t y = 0; y < 256; ++y) {
        for (std::uint32_t x = 0; x < 256; ++x) std::fill_n(img.pixel(x, y), 3, ((x + y) & 1u) ? 1.0f : 0.0f);
    }
    const std::filesystem::path file = test::temp_dir("texture") / "checker.exr";
    write_image(img, file);
    Scene scene = test::scene_from_text("fine_checker", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 16, "height": 16 },
      "render": { "mode": "global", "spp": 256, "max_bounces": 1, "background": [1, 1, 1] },
      "materials": { "m": { "diffuse": [1, 1, 1], "texture": ")" + file.string() + R"(" } },
      "objects": [ { "type": "quad", "corner": [-1, 1, 0], "edge1": [2, 0, 0], "edge2": [0, -2, 0], "material": "m" } ]
    })");
    const RenderOutcome out = test::render_cpu(scene);
    for (std::uint32_t y = 4; y < 12; ++y) {
        for (std::uint32_t x = 4; x < 12; ++x) EXPECT_NEAR(out.image.pixel(x, y)[0], 0.5f, 0.06f) << x << "," << y;
    }
    // One sample at each pixel's centre aliases: the pixels disagree wildly.
    scene.render.spp = 1;
    scene.render.jitter = false;
    const RenderOutcome aliased = test::render_cpu(scene);
    float lo = 1.0f, hi = 0.0f;
    for (std::uint32_t y = 4; y < 12; ++y) {
        for (std::uint32_t x = 4; x < 12; ++x) {
            lo = std::min(lo, aliased.image.pixel(x, y)[0]);
            hi = std::max(hi, aliased.image.pixel(x, y)[0]);
        }
    }
    EXPECT_GT(hi - lo, 0.3f);
}

// A glTF quad with TEXCOORD_0 and a base colour texture (an 8-bit PNG beside the
// file), with and without KHR_texture_transform.
std::filesystem::path textured_gltf(const std::string& name, const std::string& texture_info, int wrap) {
    const std::filesystem::path dir = test::temp_dir("texture_gltf");
    const std::filesystem::path exr = quadrant_texture(name);
    write_image(read_image(exr), dir / (name + ".png"));
    test::write_quad_buffer(dir / (name + ".bin"));
    const std::filesystem::path file = dir / (name + ".gltf");
    std::ofstream(file) << R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "extensionsUsed": ["KHR_texture_transform"],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"metallicFactor": 0, "baseColorTexture": )" + texture_info + R"(}}],
      "textures": [{"source": 0, "sampler": 0}],
      "samplers": [{"wrapS": )" + std::to_string(wrap) + R"(, "wrapT": )" + std::to_string(wrap) + R"(}],
      "images": [{"uri": ")" + name + R"(.png"}],
      )" + test::quad_buffer_json(name + ".bin") + R"(
    })";
    return file;
}

// The four quadrants where the pixels of TextureRender's view show them, through
// an 8-bit sRGB file (a few thousandths off), and shifted by half the texture in
// both directions by a transform over a repeating sampler.
TEST(TextureGltf, BaseColourTextureOnTexcoord0WithItsTransform) {
    for (const bool shifted : {false, true}) {
        SCOPED_TRACE(shifted ? "offset [0.5, 0.5]" : "no transform");
        const std::string info = shifted ? R"({"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.5]}}})"
                                         : R"({"index": 0})";
        Scene scene = load_scene(textured_gltf(shifted ? "shifted" : "plain", info, 10497));
        EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
        ASSERT_EQ(scene.textures.size(), 1u);
        EXPECT_EQ(scene.textures[0].wrap_s, Wrap::Repeat);
        ASSERT_TRUE(scene.triangles.at(0).uvs.has_value());
        // Lambertian under a white sky, to see the texture itself (glTF's material
        // adds a view-dependent Fresnel share).
        for (Material& m : scene.materials) {
            m.metallic_roughness.reset();
            m.diffuse = glm::dvec3(1.0);
        }
        test::view_quad_head_on(scene, 32, 4, 1.0);
        const RenderOutcome out = test::render_cpu(scene);
        expect_quadrants(out.image, [&](int q) { return shifted ? 3 - q : q; }, 0.01f, "cpu");
    }
}

// The metallic-roughness texture is data, not colour: the same image as the base
// colour's is decoded a second time, linear.
TEST(TextureGltf, MetallicRoughnessTextureIsReadLinear) {
    const std::filesystem::path file = textured_gltf("mr", R"({"index": 0})", 10497);
    std::string text;
    {
        std::ifstream in(file);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::string base = R"("baseColorTexture": {"index": 0})";
    text.replace(text.find(base), base.size(), base + R"(, "metallicFactor": 1, "roughnessFactor": 1, "metallicRoughnessTexture": {"index": 0})");
    // The material's metallicFactor 0 given before stays the first one read: drop it.
    text.replace(text.find(R"("metallicFactor": 0, )"), 20, "");
    std::ofstream(file) << text;
    const Scene scene = load_scene(file);
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    ASSERT_EQ(scene.textures.size(), 2u);
    const Material& m = scene.materials.at(0);
    EXPECT_EQ(m.texture, std::optional<std::uint32_t>(0u));
    EXPECT_EQ(m.metallic_roughness_texture, std::optional<std::uint32_t>(1u));
    // Texel (0, 0) is red 0.8 (linear), stored in the PNG as sRGB byte 231.
    EXPECT_NEAR(texel_value(scene.textures[0], scene.texels.words(), 0).r, 0.8f, 0.005f);
    EXPECT_NEAR(texel_value(scene.textures[1], scene.texels.words(), 0).r, 231.0f / 255.0f, 1e-6f);
    // One image, decoded once: the two records read the same bytes, as sRGB and as data.
    EXPECT_EQ(scene.textures[0].first_word, scene.textures[1].first_word);
    EXPECT_TRUE(scene.textures[0].srgb);
    EXPECT_FALSE(scene.textures[1].srgb);
    EXPECT_TRUE(flatten_scene(scene).features.has(Feature::HAS_TEXTURES));
}

TEST(TextureGltf, SamplerWrapModesAreRead) {
    const Scene clamp = load_scene(textured_gltf("clamped", R"({"index": 0})", 33071));
    EXPECT_EQ(clamp.textures.at(0).wrap_t, Wrap::Clamp);
    const Scene mirror = load_scene(textured_gltf("mirrored", R"({"index": 0})", 33648));
    EXPECT_EQ(mirror.textures.at(0).wrap_s, Wrap::Mirror);
}

TEST(TextureErrors, EachNamesTheMaterialAndTheFile) {
    const std::filesystem::path dir = test::temp_dir("texture_errors");
    const auto error_of = [&](const std::string& material) {
        return test::scene_error_of("bad_texture", R"({
              "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
              "materials": { "m": )" + material + R"( },
              "objects": [ { "type": "quad", "corner": [-1, 1, 0], "edge1": [2, 0, 0], "edge2": [0, -2, 0], "material": "m" } ]
            })");
    };
    const std::string absent = (dir / "absent.png").string();
    test::expect_error_message(error_of(R"({"texture": ")" + absent + R"("})"), "",
                               {"materials.m.texture", "absent.png", "no such file"});
    std::ofstream(dir / "garbage.png") << "not a PNG at all";
    test::expect_error_message(error_of(R"({"texture": ")" + (dir / "garbage.png").string() + R"("})"), "",
                               {"materials.m.texture", "garbage.png", "cannot read it as an image"});
    test::expect_error_message(error_of(R"({"texture_transform": {"scale": [2, 2]}})"), "",
                               {"materials.m.texture_transform", "needs a \"texture\""});
    test::expect_error_message(error_of(R"({"texture": "", "diffuse": [1, 1, 1]})"), "",
                               {"materials.m.texture", "expected a file name"});
    const std::string garbage = (dir / "garbage.png").string();
    test::expect_error_message(error_of(R"({"texture": ")" + garbage + R"(", "texture_transform": {"scale": [2]}})"), "",
                               {"materials.m.texture_transform.scale", "expected an array of 2 numbers"});
    test::expect_error_message(error_of(R"({"texture": ")" + garbage + R"(", "texture_transform": {"skew": 1}})"), "",
                               {"materials.m.texture_transform", "unknown field 'skew'"});
}

// A JSON texture_transform is glTF's, with the rotation in degrees.
TEST(Texture, JsonTextureTransformReadsAsGltfsInDegrees) {
    const std::filesystem::path texture = quadrant_texture("transformed");
    const Scene scene = test::scene_from_text("texture_transform", R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0] },
      "materials": { "m": { "texture": ")" + texture.string() + R"(",
                            "texture_transform": { "offset": [0, 1], "rotation": 90, "scale": [0.5, 0.5] } },
                     "plain": { "texture": ")" + texture.string() + R"(" } },
      "objects": [ { "type": "quad", "corner": [-1, 1, 0], "edge1": [2, 0, 0], "edge2": [0, -2, 0], "material": "m" } ]
    })");
    const auto expected = texture_transform(0.0, 1.0, std::numbers::pi / 2.0, 0.5, 0.5);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(scene.materials.at(0).uv_transform[i], expected[i], 1e-12) << i;
    const std::array<double, 6> identity = {1, 0, 0, 0, 1, 0};
    EXPECT_EQ(scene.materials.at(1).uv_transform, identity);
    EXPECT_EQ(scene.textures.size(), 2u) << "each material reads its own file";
}

// OpenImageIO's message for a PNG cut short spans lines; the error stays one.
TEST(TextureErrors, ATruncatedGltfImageGetsOneLine) {
    const std::filesystem::path file = textured_gltf("truncated", R"({"index": 0})", 10497);
    const std::filesystem::path png = file.parent_path() / "truncated.png";
    std::filesystem::resize_file(png, std::filesystem::file_size(png) / 2);
    test::expect_error_message(test::load_error_of(file), "", {"truncated.gltf", "images[0]", "cannot read"});
}

TEST(TextureErrors, GltfImagesThatCannotBeReadNameTheImage) {
    const std::filesystem::path file = textured_gltf("broken", R"({"index": 0})", 10497);
    std::ofstream(file.parent_path() / "broken.png") << "not a PNG at all";
    test::expect_error_message(test::load_error_of(file), "", {"broken.gltf", "images[0]", "cannot read the image it holds"});
    const std::filesystem::path bad_transform =
        textured_gltf("bad_transform", R"({"index": 0, "extensions": {"KHR_texture_transform": {"scale": [1]}}})", 10497);
    test::expect_error_message(test::load_error_of(bad_transform), "",
                                   {"baseColorTexture.extensions.KHR_texture_transform.scale", "expected an array of 2 numbers"});
    const std::filesystem::path missing = textured_gltf("missing_texture", R"({"index": 3})", 10497);
    test::expect_error_message(test::load_error_of(missing), "",
                                   {"materials[0].pbrMetallicRoughness.baseColorTexture.index", "texture 3 does not exist"});
}

}  // namespace
}  // namespace vkrt
