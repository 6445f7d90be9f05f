// glTF's texture coordinate sets (glTF 2.0, 3.9.2 textureInfo.texCoord): a material's
// textures read TEXCOORD_<texCoord> of the primitives that use it, on two mappings at
// most (a set and a transform each, Material::SecondMapping: a texture on a third is
// left out and named); a negative set is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/vec2.hpp>

#include "scene/load_scene.hpp"
#include "test_support.hpp"

namespace vkrt {
namespace {

using glm::dvec2;

// A quad (test_support's buffer) whose TEXCOORD_1 is the quad's own coordinates,
// (0, 0) at the top left, and whose TEXCOORD_0 is another set: the first eight floats
// of its positions read as four pairs. `material` is the JSON of its one material;
// texture 0 is a PNG beside the file.
std::filesystem::path two_set_quad(const std::string& name, const std::string& material) {
    const std::filesystem::path dir = test::temp_dir("gltf_texcoord_" + name);
    test::write_quad_buffer(dir / "quad.bin");
    std::filesystem::copy_file(test::source_dir() / "tests" / "scenes" / "stability" / "alpha_rows.png",
                               dir / "image.png", std::filesystem::copy_options::overwrite_existing);
    std::string buffer = test::quad_buffer_json("quad.bin");
    buffer.replace(buffer.rfind("}]"), 2, R"(}, {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC2"}])");
    const std::filesystem::path file = dir / (name + ".gltf");
    std::ofstream(file) << R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 3, "TEXCOORD_1": 1}, "indices": 2,
                                  "material": 0}]}],
      "materials": [)" + material + R"(],
      "textures": [{"source": 0}], "images": [{"uri": "image.png"}],
      )" + buffer + "}";
    return file;
}

// The first triangle's corners are vertices 0, 2 and 1 (test_support's indices).
const std::array<dvec2, 3> kSetOne{dvec2(0, 0), dvec2(1, 1), dvec2(1, 0)};
const std::array<dvec2, 3> kSetZero{dvec2(-1, 1), dvec2(1, 0), dvec2(0, 1)};

bool warned(const Scene& s, const std::string& text) {
    return std::any_of(s.warnings.begin(), s.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

TEST(GltfTexCoord, TexturesReadTheSetTheyName) {
    const Scene one = load_scene(two_set_quad("one", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0, "texCoord": 1}}, "normalTexture": {"index": 0, "texCoord": 1}})"));
    ASSERT_EQ(one.triangles.size(), 2u);
    ASSERT_TRUE(one.triangles[0].uvs.has_value());
    EXPECT_EQ(*one.triangles[0].uvs, kSetOne);
    EXPECT_TRUE(one.materials[0].texture.has_value());
    EXPECT_TRUE(one.materials[0].normal_map.has_value());
    EXPECT_TRUE(one.warnings.empty()) << one.warnings.front();

    const Scene zero = load_scene(two_set_quad("zero", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0}}})"));
    ASSERT_TRUE(zero.triangles[0].uvs.has_value());
    EXPECT_EQ(*zero.triangles[0].uvs, kSetZero);
}

// KHR_materials_transmission's texture is one of the material's, on its set too.
TEST(GltfTexCoord, TheTransmissionTextureReadsItsSet) {
    const Scene s = load_scene(two_set_quad("transmission", R"({"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1,
                                                      "transmissionTexture": {"index": 0, "texCoord": 1}}}})"));
    EXPECT_TRUE(s.materials[0].transmission_texture.has_value());
    EXPECT_EQ(*s.triangles[0].uvs, kSetOne);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

// The layers' textures (KHR_materials_clearcoat's, _sheen's and _specular's) are the
// material's too, on its set: the colours read as sRGB, the rest as linear data.
TEST(GltfTexCoord, TheLayersTexturesReadTheirSet) {
    const Scene s = load_scene(two_set_quad("layers", R"({"pbrMetallicRoughness": {"metallicFactor": 0},
        "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatTexture": {"index": 0, "texCoord": 1},
                                                   "clearcoatRoughnessTexture": {"index": 0, "texCoord": 1},
                                                   "clearcoatNormalTexture": {"index": 0, "texCoord": 1, "scale": 0.5}},
                       "KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenColorTexture": {"index": 0, "texCoord": 1},
                                               "sheenRoughnessTexture": {"index": 0, "texCoord": 1}},
                       "KHR_materials_specular": {"specularTexture": {"index": 0, "texCoord": 1},
                                                  "specularColorTexture": {"index": 0, "texCoord": 1}}}})"));
    const Material& m = s.materials[0];
    ASSERT_TRUE(m.clearcoat_texture && m.clearcoat_roughness_texture && m.sheen_color_texture && m.sheen_roughness_texture &&
                m.clearcoat_normal_map);
    EXPECT_EQ(*m.clearcoat_texture, *m.clearcoat_roughness_texture) << "one image, one encoding: one texture";
    EXPECT_NE(*m.clearcoat_normal_map, *m.clearcoat_texture) << "a normal map is decoded as normals";
    EXPECT_EQ(s.textures[*m.clearcoat_normal_map].normal_scale, 0.5);
    EXPECT_NE(*m.sheen_color_texture, *m.sheen_roughness_texture) << "sRGB and linear are two textures";
    ASSERT_TRUE(m.specular_texture && m.specular_color_texture);
    EXPECT_EQ(*m.specular_texture, *m.sheen_roughness_texture);
    EXPECT_EQ(*m.specular_color_texture, *m.sheen_color_texture);
    EXPECT_EQ(*s.triangles[0].uvs, kSetOne);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

// KHR_texture_transform's texCoord overrides the textureInfo's (the extension says so).
TEST(GltfTexCoord, TheTransformsSetOverrides) {
    const Scene s = load_scene(two_set_quad("transform", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}}}})"));
    ASSERT_TRUE(s.triangles[0].uvs.has_value());
    EXPECT_EQ(*s.triangles[0].uvs, kSetOne);
}

// The first texture's set is the first mapping; a later texture on another set makes
// the second, whose coordinates the triangles carry beside their first.
TEST(GltfTexCoord, ALaterTextureOnAnotherSetReadsTheSecondMapping) {
    const Scene s = load_scene(two_set_quad("mixed", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0, "texCoord": 1}}, "emissiveFactor": [1, 1, 1],
        "emissiveTexture": {"index": 0}})"));
    const Material& m = s.materials[0];
    EXPECT_TRUE(m.texture.has_value());
    EXPECT_TRUE(m.emission_texture.has_value());
    EXPECT_EQ(m.second_mapping.maps, 1u << kernel::MAP_EMISSION);
    EXPECT_TRUE(m.second_mapping.own_coordinates);
    EXPECT_EQ(m.second_mapping.transform, (std::array<double, 6>{1, 0, 0, 0, 1, 0}));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(*s.triangles[0].uvs, kSetOne);
    ASSERT_TRUE(s.triangles[0].second_uvs.has_value());
    EXPECT_EQ(*s.triangles[0].second_uvs, kSetZero);
}

// A later texture on the first set through another transform makes a second mapping
// of the same coordinates: the triangles carry no second set.
TEST(GltfTexCoord, ALaterTransformReadsTheSecondMappingOfTheSameSet) {
    const Scene s = load_scene(two_set_quad("retransformed", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 0,
        "extensions": {"KHR_texture_transform": {"scale": [2, 4]}}}}, "normalTexture": {"index": 0,
        "extensions": {"KHR_texture_transform": {"scale": [2, 4]}}}})"));
    const Material& m = s.materials[0];
    EXPECT_TRUE(m.texture && m.metallic_roughness_texture && m.normal_map);
    EXPECT_EQ(m.second_mapping.maps, (1u << kernel::MAP_METAL_ROUGH) | (1u << kernel::MAP_NORMAL));
    EXPECT_FALSE(m.second_mapping.own_coordinates);
    EXPECT_EQ(m.second_mapping.transform, (std::array<double, 6>{2, 0, 0, 0, 4, 0}));
    EXPECT_EQ(m.uv_transform, (std::array<double, 6>{1, 0, 0, 0, 1, 0}));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(*s.triangles[0].uvs, kSetZero);
    EXPECT_FALSE(s.triangles[0].second_uvs.has_value());
}

// Extensions' textures take the second mapping as the core ones do.
TEST(GltfTexCoord, AnExtensionsTextureReadsTheSecondMapping) {
    const Scene s = load_scene(two_set_quad("extension", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0}},
        "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1,
                                                   "clearcoatNormalTexture": {"index": 0, "texCoord": 1}}}})"));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.second_mapping.maps, 1u << kernel::MAP_COAT_NORMAL);
    EXPECT_TRUE(m.second_mapping.own_coordinates);
    EXPECT_EQ(*s.triangles[0].uvs, kSetZero);
    EXPECT_EQ(*s.triangles[0].second_uvs, kSetOne);
}

TEST(GltfTexCoord, ATextureOnAThirdMappingIsLeftOutAndNamed) {
    const Scene s = load_scene(two_set_quad("third", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0, "texCoord": 1}}, "emissiveFactor": [1, 1, 1],
        "emissiveTexture": {"index": 0}, "normalTexture": {"index": 0,
        "extensions": {"KHR_texture_transform": {"offset": [0.5, 0]}}}})"));
    const Material& m = s.materials[0];
    EXPECT_TRUE(m.texture && m.emission_texture);
    EXPECT_FALSE(m.normal_map.has_value());
    EXPECT_EQ(m.second_mapping.maps, 1u << kernel::MAP_EMISSION);
    EXPECT_TRUE(warned(s, "a material's textures on more than two mappings of texture coordinates (TEXCOORD_n and "
                          "KHR_texture_transform), rendered without the later textures"));
}

TEST(GltfTexCoord, ANegativeSetIsRefused) {
    const std::filesystem::path file = two_set_quad("negative", R"({"pbrMetallicRoughness": {"metallicFactor": 0,
        "baseColorTexture": {"index": 0, "texCoord": -1}}})");
    test::expect_error_message(test::load_error_of(file), "",
                               {"materials[0].pbrMetallicRoughness.baseColorTexture.texCoord", "expected an integer from 0, got -1"});
}

}  // namespace
}  // namespace vkrt
