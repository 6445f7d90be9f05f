// A material's second mapping of texture coordinates (kernel/texture.glsl,
// HAS_SECOND_MAPPING), through the reference kernel: the coordinates each texture
// slot reads, exactly, from the triangle's second coordinates (vertex_data.glsl) or
// its first, through the second transform; a normal map on the second mapping takes
// its tangent frame from that mapping; an emission texture on it lights by it; and
// with the feature off every texture reads the first mapping. Then the scene file's
// second_texture_transform: an emission texture on it renders, on both backends, as
// it does on the first mapping through the same transform; and its errors.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "flatten/flat_scene.hpp"
#include "image/compare.hpp"
#include "image/image.hpp"
#include "image/image_files.hpp"
#include "kernel/kernel.hpp"
#include "mapped_triangle.hpp"
#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using kernel::Kernel;
using kernel::vec2;
using kernel::vec3;

const std::array<vec2, 3> kAlongEdges = {vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(0.0f, 1.0f)};

// The second coordinates of one triangle as the table holds them (float bits).
std::vector<std::uint32_t> second_uv_words(std::array<vec2, 3> corners) {
    std::vector<std::uint32_t> words;
    for (vec2 c : corners) {
        words.push_back(glm::floatBitsToUint(c.x));
        words.push_back(glm::floatBitsToUint(c.y));
    }
    return words;
}

// A MappedTriangle whose material reads `maps` on a second mapping: from the second
// coordinates `second` where own_coordinates, else from the first, through the
// transform whose rows are u2 and v2.
struct SecondMapped : test::MappedTriangle {
    std::vector<std::uint32_t> table;

    SecondMapped(vec3 ts, std::uint32_t maps, bool own_coordinates, std::array<vec2, 3> second, vec3 u2 = vec3(1, 0, 0),
                 vec3 v2 = vec3(0, 1, 0))
        : MappedTriangle(ts, kAlongEdges), table(second_uv_words(second)) {
        materials[0].second_maps = maps;
        materials[0].second_coords = own_coordinates ? 1u : 0u;
        materials[0].uv2_u = u2;
        materials[0].uv2_v = v2;
        k.table_words = table;
        kernel::set_second_uv_first_word(k.params, 0u);
    }
};

constexpr std::uint32_t bit(std::uint32_t slot) { return 1u << slot; }

TEST(SecondMapping, EachSlotReadsItsMappingExactly) {
    SecondMapped t(vec3(0, 0, 1), bit(kernel::MAP_EMISSION), true,
                   {vec2(0.5f, 0.5f), vec2(0.5f, 1.0f), vec2(1.0f, 0.5f)}, vec3(1, 0, 0), vec3(0, 1, 0.25f));
    t.materials[0].uv_u = vec3(2.0f, 0.0f, 0.5f);
    t.materials[0].uv_v = vec3(0.0f, 4.0f, 0.0f);
    const kernel::Material& m = t.materials[0];
    // At weights (0.25, 0.5) the first coordinates are (0.25, 0.5), the second
    // (0.5, 0.5) + 0.25 (0, 0.5) + 0.5 (0.5, 0) = (0.75, 0.625).
    const Kernel::TextureCoords c = t.k.texture_coords(m, 0u, vec2(0.25f, 0.5f), vec2(0.25f, 0.5f));
    EXPECT_EQ(c.first, vec2(1.0f, 2.0f));
    EXPECT_EQ(c.second, vec2(0.75f, 0.875f));
    EXPECT_EQ(t.k.slot_uv(m, c, kernel::MAP_EMISSION), c.second);
    for (std::uint32_t slot = 0; slot < kernel::MAP_SLOTS; ++slot) {
        if (slot != kernel::MAP_EMISSION) {
            EXPECT_EQ(t.k.slot_uv(m, c, slot), c.first) << "slot " << slot;
        }
    }
    // The second mapping of the first coordinates: (0.25, 0.5 + 0.25).
    t.materials[0].second_coords = 0u;
    EXPECT_EQ(t.k.texture_coords(m, 0u, vec2(0.25f, 0.5f), vec2(0.25f, 0.5f)).second, vec2(0.25f, 0.75f));
}

TEST(SecondMapping, WithTheFeatureOffEveryTextureReadsTheFirst) {
    SecondMapped t(vec3(0, 0, 1), bit(kernel::MAP_EMISSION) | bit(kernel::MAP_NORMAL), true,
                   {vec2(0.5f, 0.5f), vec2(0.5f, 1.0f), vec2(1.0f, 0.5f)});
    t.k.HAS_SECOND_MAPPING = false;
    const Kernel::TextureCoords c = t.k.texture_coords(t.materials[0], 0u, vec2(0.25f, 0.5f), vec2(0.25f, 0.5f));
    EXPECT_EQ(c.second, c.first);
    EXPECT_EQ(t.k.slot_uv(t.materials[0], c, kernel::MAP_EMISSION), vec2(0.25f, 0.5f));
}

// (0.5, 0, 1) in tangent space leans the normal toward +u: along x on the first
// coordinates, along y on second coordinates whose u runs up the triangle's y.
TEST(SecondMapping, ANormalMapOnTheSecondMappingLeansAlongItsCoordinates) {
    const vec3 tilt(0.5f, 0.0f, 1.0f);
    const vec3 up(0.0f, 0.0f, 1.0f);
    const std::array<vec2, 3> u_along_y = {vec2(0.0f, 0.0f), vec2(0.0f, 1.0f), vec2(1.0f, 0.0f)};
    SecondMapped own(tilt, bit(kernel::MAP_NORMAL), true, u_along_y);
    const vec3 n = own.normal(up);
    EXPECT_NEAR(n.x, 0.0f, 1e-7f);
    EXPECT_NEAR(n.y, 1.0f / std::sqrt(5.0f), 1e-6f);
    EXPECT_NEAR(n.z, 2.0f / std::sqrt(5.0f), 1e-6f);

    // The same coordinates made by the second transform swapping u and v of the first.
    SecondMapped swapped(tilt, bit(kernel::MAP_NORMAL), false, kAlongEdges, vec3(0, 1, 0), vec3(1, 0, 0));
    EXPECT_EQ(swapped.normal(up), n) << "the same frame, bit for bit";

    // Another slot on the second mapping leaves the normal map on the first.
    SecondMapped other(tilt, bit(kernel::MAP_EMISSION), true, u_along_y);
    EXPECT_NEAR(other.normal(up).x, 1.0f / std::sqrt(5.0f), 1e-6f);
    own.k.HAS_SECOND_MAPPING = false;
    EXPECT_EQ(own.normal(up), other.normal(up));
}

// An emission texture of two texels, white then black along u, on the second
// mapping: the triangle emits what the second coordinates read, in shading and in
// the light samples' radiance alike (triangle_emission).
TEST(SecondMapping, AnEmissionTextureOnTheSecondMappingEmitsByIt) {
    SecondMapped t(vec3(0, 0, 1), bit(kernel::MAP_EMISSION), true,
                   {vec2(0.75f, 0.5f), vec2(0.75f, 0.5f), vec2(0.75f, 0.5f)});
    t.words = {glm::packHalf2x16(vec2(1.0f, 1.0f)), glm::packHalf2x16(vec2(1.0f, 1.0f)),
               glm::packHalf2x16(vec2(0.0f, 0.0f)), glm::packHalf2x16(vec2(0.0f, 1.0f))};
    t.records = {kernel::Texture(kernel::uvec4(0u, 2u, 1u, 0u), kernel::vec4(1.0f, 0.0f, 0.0f, 0.0f))};
    t.k.texture_words = t.words;
    t.k.textures = t.records;
    t.materials[0].normal_map = 0u;
    t.materials[0].emission_map = 1u;
    t.materials[0].emission = vec3(2.0f);
    // First coordinates (0.25, 0.25): texel 0's centre, white; second (0.75, 0.5): texel 1's, black.
    Kernel::Hit h = t.hit();
    h.bary = vec2(0.25f, 0.25f);
    EXPECT_EQ(t.k.surface_material(h).emission, vec3(0.0f));
    EXPECT_EQ(t.k.triangle_emission(t.materials[0], t.triangles[0], 0u, 0.25f, 0.25f), vec3(0.0f));
    t.k.HAS_SECOND_MAPPING = false;
    EXPECT_EQ(t.k.surface_material(h).emission, vec3(2.0f));
    EXPECT_EQ(t.k.triangle_emission(t.materials[0], t.triangles[0], 0u, 0.25f, 0.25f), vec3(2.0f));
}

// A quad filling the view, lit by nothing but its own emission through a 4 x 4
// checkerboard texture, in the scene file's words `maps` (its texture fields).
std::string emitting_quad(const std::string& maps) {
    Image img(4, 4);
    for (std::uint32_t y = 0; y < 4; ++y) {
        for (std::uint32_t x = 0; x < 4; ++x) {
            for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = (x + y) % 2 == 0 ? 1.0f : 0.25f * float(c + 1);
        }
    }
    const std::filesystem::path checker = test::temp_dir("second_mapping") / "checker.exr";
    write_image(img, checker);
    return R"({
      "camera": { "eye": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 24, "height": 24 },
      "render": { "mode": "global", "spp": 2, "max_bounces": 1, "background": [0, 0, 0] },
      "materials": { "m": { "diffuse": [0.5, 0.5, 0.5], "emission": [1, 1, 1], "emission_texture": ")" + checker.string() + R"(")" +
           maps + R"( } },
      "objects": [ { "type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "m" } ]
    })";
}

TEST(SecondMappingScene, AnEmissionTextureOnTheSecondTransformRendersAsOnTheFirst) {
    const Scene second = test::scene_from_text(
        "second", emitting_quad(R"(, "second_texture_transform": { "scale": [3, 2], "rotation": 30,
                                    "textures": ["emission_texture"] })"));
    const Scene first = test::scene_from_text(
        "first", emitting_quad(R"(, "texture_transform": { "scale": [3, 2], "rotation": 30 })"));
    const Scene plain = test::scene_from_text("plain", emitting_quad(""));
    ASSERT_EQ(second.materials[0].second_mapping.maps, 1u << kernel::MAP_EMISSION);
    EXPECT_FALSE(second.materials[0].second_mapping.own_coordinates);
    EXPECT_TRUE(flatten_scene(second).features.has(Feature::HAS_SECOND_MAPPING));
    EXPECT_FALSE(flatten_scene(first).features.has(Feature::HAS_SECOND_MAPPING));
    const Image a = test::render_cpu(second).image;
    const Image b = test::render_cpu(first).image;
    EXPECT_EQ(compare_images(a, b, 0.0).pixels_over, 0u) << "the same arithmetic on either mapping";
    EXPECT_GT(compare_images(a, test::render_cpu(plain).image, 1e-3).pixels_over, 0u) << "the transform is applied";
    const ImageDiff gpu = compare_images(test::render_vulkan(second).image, a, 1e-5);
    EXPECT_EQ(gpu.pixels_over, 0u) << "max abs " << gpu.max_abs;
}

TEST(SecondMappingScene, BadSecondTransformsAreRefused) {
    const auto error = [](const std::string& name, const std::string& maps) {
        return test::scene_error_of(name, emitting_quad(maps));
    };
    test::expect_error_message(error("no_textures", R"(, "second_texture_transform": { "scale": [2, 2] })"), "",
                               {"second_texture_transform", "needs \"textures\""});
    test::expect_error_message(
        error("colour", R"(, "texture": "checker.exr", "second_texture_transform": { "textures": ["texture"] })"), "",
        {"second_texture_transform.textures[0]", "the colour texture reads \"texture_transform\""});
    test::expect_error_message(
        error("absent", R"(, "second_texture_transform": { "textures": ["specular_texture"] })"), "",
        {"textures[0]", "the material has no \"specular_texture\""});
    test::expect_error_message(error("unknown", R"(, "second_texture_transform": { "textures": ["bump"] })"), "",
                               {"textures[0]", "'bump' is not a texture field", "normal_map"});
    test::expect_error_message(
        error("key", R"(, "second_texture_transform": { "textures": ["emission_texture"], "offst": [1, 0] })"), "",
        {"offst"});
}

}  // namespace
}  // namespace vkrt
